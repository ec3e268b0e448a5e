#!/usr/bin/python3
"""Bonded hypervelocity benchmark: CraterKit against LAMMPS on the same impact.

The headline case of Watson & Steinhauser 2017 (seed 003): an aluminium sphere (9.53 mm,
6.7 km/s) on a plate (t/D = 0.425), cubic lattices of spacing r_eq = 2^(1/6) sigma, the law of
the paper at the run's sigma (eps = 0.01 J, kappa = 4.56e6 N/m at the headline size, r_cut =
1.5 sigma), the same Boltzmann jitter and the same time step (the paper's 1e-10 s scaled with
sigma). LAMMPS runs the deck CraterKit's own writer makes for this set-up
(bonded/BondedLammpsDeck.h, written by `ck_bonded_bench lammps-deck`): the same atoms,
velocities and bonds, pair_style lj/cut at 2^(1/6) sigma with pair_modify shift yes (the
repulsion of Eq. 3), Eq. 4's pull-only bond as a `bond_style table` (the writer's default, the
law CraterKit integrates), fix bond/break every step at r_cut, special_bonds 1 1 1 (bonded pairs
repel too), fix nve. One difference remains: LAMMPS breaks at most one bond per atom per step,
CraterKit all of them. The step loops alone are timed (LAMMPS' "Loop time" of the deck's last
run, CraterKit's advance()), after --warmup untimed steps that bring the projectile through its
stand-off into the plate, so that bonds break in the timed steps; prints particle-steps per
second and the ratio.

    benchmarks/hvi_bonded/run.py                       # 1.5e5 particles, 1500 + 1000 steps
    benchmarks/hvi_bonded/run.py --particles 20000 --steps 500
"""

import argparse
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from bench_common import log, mpirun, run  # noqa: E402


def last_json(text):
    return json.loads(text.strip().splitlines()[-1])


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--particles", type=float, default=1.5e5)
    p.add_argument("--steps", type=int, default=1000, help="timed steps")
    p.add_argument("--warmup", type=int, default=1500,
                   help="untimed steps first (the stand-off of 3 sigma takes ~900 at 6.7 km/s)")
    p.add_argument("--ranks", type=int, default=2, help="LAMMPS MPI ranks")
    p.add_argument("--threads", type=int, default=2, help="CraterKit OpenMP threads")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--work", default=None, help="work folder (default: BUILD/hvi_bonded_bench)")
    p.add_argument("--lmp", default="lmp")
    args = p.parse_args(argv)
    bench = os.path.join(args.build, "benchmarks", "hvi_bonded", "ck_bonded_bench")
    work = args.work or os.path.join(args.build, "hvi_bonded_bench")
    os.makedirs(work, exist_ok=True)

    log(f"[1/3] set-up of {args.particles:.3g} particles, as CraterKit's LAMMPS deck "
        f"(bonded/BondedLammpsDeck) in {work}")
    warmup = max(0, args.warmup)
    out, _ = run([bench, "lammps-deck", work, str(args.particles), str(args.steps), str(warmup)])
    law = last_json(out)
    with open(os.path.join(work, law["input"])) as f:
        runs = re.findall(r"^run (\d+)", f.read(), re.M)
    if runs != [str(n) for n in ([warmup] if warmup else []) + [args.steps]]:
        raise RuntimeError(f"the deck runs {runs} steps, not {warmup} + {args.steps}")
    n = law["particles"]

    log(f"[2/3] LAMMPS, {args.ranks} ranks, {args.steps} steps of {n} atoms")
    dump = os.path.join(work, "dump.craterkit")  # the deck appends to it
    if os.path.exists(dump):
        os.remove(dump)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out, _ = run(mpirun(args.ranks) + [args.lmp, "-in", law["input"], "-log", "log.lammps"],
                 env=env, cwd=work)
    m = re.findall(r"Loop time of ([0-9.eE+-]+) on", out)
    if len(m) != len(runs):
        raise RuntimeError("no 'Loop time' for each run in the LAMMPS output:\n" + out[-2000:])
    lammps_seconds = float(m[-1])  # the timed run
    # The deck's report after each run: bonds broken since its start.
    broken = [int(float(b)) for b in re.findall(r"^craterkit: time \S+ broken (\S+)", out, re.M)]
    lammps_broken = broken[-1] if broken else -1
    lammps_timed = broken[-1] - broken[-2] if len(broken) > 1 else lammps_broken
    grid = re.search(r"(\d+ by \d+ by \d+) MPI processor grid", out)
    lammps_rate = n * args.steps / lammps_seconds

    log(f"[3/3] CraterKit, {args.threads} threads, {args.steps} steps of {n} particles")
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    out, _ = run([bench, "run", str(args.particles), str(args.steps), str(warmup)], env=env)
    ck = last_json(out)
    result = {
        "particles": n, "bonds": law["bonds"], "warmup_steps": warmup, "steps": args.steps,
        "dt_s": law["dt"], "lammps_deck": "CraterKit's BondedLammpsDeck, pull-only bond table",
        "lammps_ranks": args.ranks, "lammps_grid": grid.group(1) if grid else None,
        "lammps_loop_s": lammps_seconds,
        "lammps_particle_steps_per_s": lammps_rate, "lammps_broken_bonds": lammps_broken,
        "lammps_broken_timed": lammps_timed,
        "craterkit_threads": args.threads, "craterkit_loop_s": ck["loop_seconds"],
        "craterkit_particle_steps_per_s": ck["particle_steps_per_s"],
        "craterkit_broken_bonds": ck["broken_bonds"], "craterkit_broken_timed": ck["broken_timed"],
        "ratio_craterkit_over_lammps": ck["particle_steps_per_s"] / lammps_rate,
    }
    log(f"LAMMPS    {lammps_rate:.3g} particle-steps/s ({lammps_seconds:.2f} s; bonds broken "
        f"{lammps_broken}, {lammps_timed} in the timed steps)")
    log(f"CraterKit {ck['particle_steps_per_s']:.3g} particle-steps/s ({ck['loop_seconds']:.2f} s; "
        f"bonds broken {ck['broken_bonds']}, {ck['broken_timed']} in the timed steps)")
    log(f"ratio CraterKit / LAMMPS: {result['ratio_craterkit_over_lammps']:.2f}")
    with open(os.path.join(work, "result.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/python3
"""Bonded hypervelocity benchmark: CraterKit against LAMMPS on the same impact.

The headline case of Watson & Steinhauser 2017 (seed 003): an aluminium sphere (9.53 mm,
6.7 km/s) on a plate (t/D = 0.425), cubic lattices of spacing r_eq = 2^(1/6) sigma, the law of
the paper at the run's sigma (eps = 0.01 J, kappa = 4.56e6 N/m at the headline size, r_cut =
1.5 sigma), the same Boltzmann jitter and the same time step (the paper's 1e-10 s scaled with
sigma). CraterKit (ck_bonded_bench, OpenMP) writes its set-up as a LAMMPS data file, so both
codes start from the same atoms, velocities and bonds. LAMMPS: pair_style lj/cut at 2^(1/6)
sigma with pair_modify shift yes (the repulsion of Eq. 3), bond_style harmonic with K = kappa/2
(LAMMPS' harmonic energy is K (r - r0)^2, Eq. 4 is kappa (r - r0)^2 / 2), fix bond/break every
step at r_cut, special_bonds 1 1 1 (bonded pairs repel too), fix nve. One difference remains:
LAMMPS' harmonic bond also pushes when compressed, CraterKit's (Eq. 4) only pulls, so the
broken-bond counts differ somewhat; the work per step is the same. The step loops alone are
timed (LAMMPS' "Loop time", CraterKit's advance()), after --warmup untimed steps that bring the
projectile through its stand-off into the plate, so that bonds break in the timed steps; prints
particle-steps per second and the ratio.

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


LAMMPS_INPUT = """units si
atom_style bond
boundary s s s
atom_modify map array
read_data data.lmp
comm_modify cutoff {comm}
pair_style lj/cut {rc}
pair_coeff * * {epsilon} {sigma} {rc}
pair_modify shift yes
bond_style harmonic
bond_coeff 1 {K} {r_eq}
special_bonds lj 1.0 1.0 1.0
neighbor {skin} bin
neigh_modify every 1 delay 0 check yes
fix integrate all nve
fix break all bond/break 1 1 {r_cut}
timestep {dt}
thermo_style custom step ke pe f_break[2]
thermo {thermo}
run {warmup}
run {steps}
"""


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

    log(f"[1/3] set-up of {args.particles:.3g} particles, written for LAMMPS")
    out, _ = run([bench, "data", os.path.join(work, "data.lmp"), str(args.particles)])
    law = last_json(out)
    sigma = law["sigma"]
    skin = 0.3 * sigma  # CraterKit's Verlet skin (BondedSolverParams::skin)
    # fix bond/break updates the special lists of a broken bond's partners, so it needs ghost
    # atoms out to two bonds (1-3 neighbours), not just one.
    with open(os.path.join(work, "in.lmp"), "w") as f:
        f.write(LAMMPS_INPUT.format(
            comm=2 * law["r_cut"] + 2 * skin, rc=law["r_eq"], epsilon=law["epsilon"], sigma=sigma,
            K=0.5 * law["kappa"], r_eq=law["r_eq"], skin=skin, r_cut=law["r_cut"], dt=law["dt"],
            thermo=max(1, args.steps // 4), warmup=max(0, args.warmup), steps=args.steps))
    n = law["particles"]

    log(f"[2/3] LAMMPS, {args.ranks} ranks, {args.steps} steps of {n} atoms")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out, _ = run(mpirun(args.ranks) + [args.lmp, "-in", "in.lmp", "-log", "log.lammps"],
                 env=env, cwd=work)
    m = re.findall(r"Loop time of ([0-9.eE+-]+) on", out)
    if not m:
        raise RuntimeError("no 'Loop time' in the LAMMPS output:\n" + out[-2000:])
    lammps_seconds = float(m[-1])  # the timed run
    rows = re.findall(r"^\s*(\d+)\s+([-0-9.eE+]+)\s+([-0-9.eE+]+)\s+([-0-9.eE+]+)\s*$", out, re.M)
    lammps_broken = int(float(rows[-1][3])) if rows else -1
    lammps_rate = n * args.steps / lammps_seconds

    log(f"[3/3] CraterKit, {args.threads} threads, {args.steps} steps of {n} particles")
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads))
    out, _ = run([bench, "run", str(args.particles), str(args.steps), str(args.warmup)], env=env)
    ck = last_json(out)
    result = {
        "particles": n, "bonds": law["bonds"], "warmup_steps": args.warmup, "steps": args.steps,
        "dt_s": law["dt"],
        "lammps_ranks": args.ranks, "lammps_loop_s": lammps_seconds,
        "lammps_particle_steps_per_s": lammps_rate, "lammps_broken_bonds": lammps_broken,
        "craterkit_threads": args.threads, "craterkit_loop_s": ck["loop_seconds"],
        "craterkit_particle_steps_per_s": ck["particle_steps_per_s"],
        "craterkit_broken_bonds": ck["broken_bonds"],
        "ratio_craterkit_over_lammps": ck["particle_steps_per_s"] / lammps_rate,
    }
    log(f"LAMMPS    {lammps_rate:.3g} particle-steps/s ({lammps_seconds:.2f} s, "
        f"{lammps_broken} bonds broken)")
    log(f"CraterKit {ck['particle_steps_per_s']:.3g} particle-steps/s ({ck['loop_seconds']:.2f} s, "
        f"{ck['broken_bonds']} bonds broken)")
    log(f"ratio CraterKit / LAMMPS: {result['ratio_craterkit_over_lammps']:.2f}")
    with open(os.path.join(work, "result.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

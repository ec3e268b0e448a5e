#!/usr/bin/python3
"""DEM bed-impact benchmark: CraterKit against LIGGGHTS 3.8 and LAMMPS on one problem.

A settled bed of monodisperse spheres (r = 5 cm, 2000 kg/m^3) in a box with gravity and a
sphere of twice the radius hitting it at 1 m/s. The same particles, contact law (linear
spring-dashpot, tangential spring with Coulomb limit, rolling resistance; twisting where the
code has it), time step and number of steps run in each code on 2 threads (CraterKit,
OpenMP) or 2 MPI ranks (the peers); the step loop alone is timed. CraterKit also runs on
1 thread, for its speed-up from 1 to 2 threads. Prints particle-steps per second and the
ratios.

LAMMPS runs the deck CraterKit's own writer makes for this problem (dem/LammpsDeck.h, the deck
`examples/sci_crater.py --dem-engine lammps` and the LAMMPS deck writer hand to users), written
by `ck_dem_bench lammps-deck`. LIGGGHTS, for which CraterKit has no writer, reads that deck's
data file (the same atoms and shrink-wrapped box) with the input written below.

Method: the machine's speed drifts by 15-50 % over minutes, more than the margins measured,
so the codes run in rounds (--repeat N, default 3): each round runs CraterKit on 1 thread,
CraterKit on 2 threads, LAMMPS and LIGGGHTS back to back, and every ratio is taken within
its round (the 1- against the 2-thread run, the peer against CraterKit's 2-thread run), where
the drift is smallest; the figures quoted are the medians of the per-round ratios (with their
range), never a ratio of medians or of runs from different rounds. Every round's figures are
printed. The table of seconds and particle-steps/s shows each code's median over the rounds.

    benchmarks/dem_bed_impact/run.py                      # 100,000 particles, 1000 steps, 3 rounds
    benchmarks/dem_bed_impact/run.py --particles 20000 --steps 500 --repeat 1

The settled bed is cached in the build directory (settling 10^5 spheres takes minutes).
"""

import argparse
import json
import math
import os
import re
import statistics
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from bench_common import log, mpirun, run  # noqa: E402

# pkdgrav "moderate" regolith coefficients (docs/physics.md §1.7), as ck_dem_bench.cpp sets them,
# for the LIGGGHTS deck (the LAMMPS deck takes them from CraterKit's writer); the dashpot
# coefficients come from ck_dem_bench's output (the clipped normal law).
MU_S, MU_R, BETA = 0.6, 1.05, 0.5


def loop_time(text):
    m = re.search(r"Loop time of ([0-9.eE+-]+) on", text)
    if not m:
        raise RuntimeError("no 'Loop time' in output:\n" + text[-2000:])
    return float(m.group(1))


def atom_types(data):
    """The 'N atom types' of a LAMMPS data file's header."""
    with open(data) as f:
        for line in f:
            m = re.match(r"\s*(\d+)\s+atom types", line)
            if m:
                return int(m.group(1))
    raise RuntimeError(f"no 'atom types' line in {data}")


def liggghts_youngs(ck):
    """Young's modulus that makes LIGGGHTS' hooke stiffness equal CraterKit's k_N.

    LIGGGHTS 3.8 hooke: k_n = 16/15 sqrt(R*) Y* (15 m* V^2 / (16 sqrt(R*) Y*))^(1/5),
    R* = r/2, m* = m/2, Y* = Y / (2 (1 - nu^2)), V = characteristicVelocity.
    """
    nu, V = 0.25, ck["speed"]
    rs, ms = ck["radius"] / 2.0, ck["mass"] / 2.0

    def kn(Y):
        ys = Y / (2.0 * (1 - nu * nu))
        return 16.0 / 15.0 * math.sqrt(rs) * ys * (15.0 * ms * V * V / (16.0 * math.sqrt(rs) * ys)) ** 0.2

    lo, hi = 1.0, 1e14
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if kn(mid) < ck["kn"] else (lo, mid)
    return math.sqrt(lo * hi)


def liggghts_restitution(factor):
    """The restitution LIGGGHTS' hooke law turns into CraterKit's normal damping factor.

    LIGGGHTS: C = 2 sqrt(k m*) (-ln e) / sqrt(pi^2 + ln^2 e) (with limitForce on, no pull);
    inverted for the factor CraterKit uses under its clipped normal force.
    """
    return math.exp(-math.pi * factor / math.sqrt(4.0 - factor * factor))


def liggghts_input(ck, steps, data, types):
    """LIGGGHTS 3.8 input for the problem of CK (ck_dem_bench's JSON), reading DATA (the LAMMPS
    deck's data file, TYPES atom types, all of one material) in a shrink-wrapped box as the
    LAMMPS deck does."""
    Y = liggghts_youngs(ck)
    eps = liggghts_restitution(ck["damping_factor_n"])
    side, depth = ck["side"], ck["depth"]
    skin = 0.2 * ck["radius"]

    def per_type(v):
        return " ".join([str(v)] * types)

    def per_pair(v):
        return f"{types} " + " ".join([str(v)] * (types * types))

    model = "model hooke tangential history rolling_friction epsd2"
    walls = "\n".join(
        f"fix w{i} all wall/gran {model} primitive type 1 {plane} {value} limitForce on"
        for i, (plane, value) in enumerate([("zplane", -depth), ("xplane", -side / 2), ("xplane", side / 2),
                                            ("yplane", -side / 2), ("yplane", side / 2)]))
    return f"""atom_style granular
atom_modify map array
boundary m m m
newton off
communicate single vel yes
units si
hard_particles yes
read_data {data}
neighbor {skin} bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype {per_type(Y)}
fix m2 all property/global poissonsRatio peratomtype {per_type(0.25)}
fix m3 all property/global coefficientRestitution peratomtypepair {per_pair(eps)}
fix m4 all property/global coefficientFriction peratomtypepair {per_pair(MU_S)}
fix m5 all property/global coefficientRollingFriction peratomtypepair {per_pair(MU_R * BETA / 2)}
fix m6 all property/global characteristicVelocity scalar {ck['speed']}
pair_style gran {model} limitForce on
pair_coeff * *
timestep {ck['dt']}
{walls}
fix g all gravity 9.81 vector 0.0 0.0 -1.0
fix nve all nve/sphere
thermo {steps}
run {steps}
"""


def write_decks(args, exe, work, bed):
    """The peers' decks for the bed BED and args.steps steps: LAMMPS' by CraterKit's writer
    (ck_dem_bench lammps-deck) into WORK/lammps, LIGGGHTS' input into WORK/liggghts reading the
    same data file. Returns ck_dem_bench's JSON (the problem's parameters)."""
    lammps = os.path.join(work, "lammps")
    out, _ = run([exe, "lammps-deck", bed, str(args.steps), lammps])
    ck = json.loads(out.strip().splitlines()[-1])
    with open(os.path.join(lammps, ck["input"])) as f:
        runs = re.findall(r"^run (\d+)", f.read(), re.M)
    if runs != [str(args.steps)]:  # one run of the timed steps, whose "Loop time" is read
        raise RuntimeError(f"the LAMMPS deck runs {runs} steps, not [{args.steps}]")
    data = os.path.join(lammps, ck["data"])
    liggghts = os.path.join(work, "liggghts")
    os.makedirs(liggghts, exist_ok=True)
    with open(os.path.join(liggghts, "in.liggghts"), "w") as f:
        f.write(liggghts_input(ck, args.steps, os.path.relpath(data, liggghts), atom_types(data)))
    return ck


def run_round(args, exe, work, bed, ck, skip):
    """One round: CraterKit on 1 and 2 threads, then the peers, back to back. Returns the
    step-loop seconds by code."""
    results = {}
    hashes = set()
    for threads in (1, 2):
        env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMP_PROC_BIND="false")
        log(f"[2/4] CraterKit, {threads} thread(s), {args.steps} steps")
        out, _ = run([exe, "run", bed, str(args.steps)], env=env)
        mine = json.loads(out.strip().splitlines()[-1])
        if mine["particles"] != ck["particles"] or mine["dt"] != ck["dt"] or mine["kn"] != ck["kn"]:
            raise RuntimeError("CraterKit's run and the peers' decks differ in the problem")
        results[f"CraterKit {threads}T"] = mine["seconds"]
        hashes.add(mine["state_hash"])
    if len(hashes) != 1:  # the solver promises the same bits on any number of threads
        raise RuntimeError(f"CraterKit's final states differ between 1 and 2 threads: {hashes}")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    peers = [("lammps", "LAMMPS", ["lmp", "-in", ck["input"], "-log", "log.lammps"],
              "[3/4] LAMMPS, 2 MPI ranks, CraterKit's deck"),
             ("liggghts", "LIGGGHTS", ["liggghts", "-in", "in.liggghts", "-log", "log.liggghts"],
              "[4/4] LIGGGHTS 3.8, 2 MPI ranks (no twisting model)")]
    for key, name, command, message in peers:
        if key in skip:
            continue
        log(message)
        cwd = os.path.join(work, key)
        if key == "lammps":  # the deck appends its final state to its dump
            dump = os.path.join(cwd, "dump.craterkit")
            if os.path.exists(dump):
                os.remove(dump)
        out, _ = run(mpirun(2) + command, env=env, cwd=cwd)
        grid = re.search(r"(\d+ by \d+ by \d+) MPI processor grid", out)
        log(f"      {grid.group(1) if grid else 'unknown'} processor grid, "
            f"loop {loop_time(out):.3f} s")
        results[f"{name} 2 ranks"] = loop_time(out)
    return results


def spread(values):
    """'median of N rounds, lowest-highest' of a list of per-round ratios."""
    text = f"median of {len(values)} round(s)"
    return text if len(values) == 1 else f"{text}, {min(values):.2f}-{max(values):.2f}"


def report(rounds, ck, steps):
    """The per-code medians, the within-round ratios and their medians."""
    n = ck["particles"]
    codes = list(rounds[0])
    median = {code: statistics.median(r[code] for r in rounds) for code in codes}
    log(f"\n{n} particles, {steps} steps, dt = {ck['dt']:.4g} s, k_N = {ck['kn']:.4g} N/m, "
        f"{len(rounds)} round(s); seconds: median over the rounds")
    log(f"{'code':<20} {'seconds':>10} {'particle-steps/s':>18}")
    for code in codes:
        log(f"{code:<20} {median[code]:>10.3f} {n * steps / median[code]:>18.4g}")
    log("\nper round (ratios within the round):")
    scaling = [r["CraterKit 1T"] / r["CraterKit 2T"] for r in rounds]
    peers = [code for code in ("LAMMPS 2 ranks", "LIGGGHTS 2 ranks") if code in codes]
    against = {code: [r[code] / r["CraterKit 2T"] for r in rounds] for code in peers}
    for k, r in enumerate(rounds):
        figures = ", ".join(f"{code} {r[code]:.3f} s" for code in codes)
        ratios = "; ".join([f"1 -> 2 threads {scaling[k]:.2f}x"] +
                           [f"vs {code} {against[code][k]:.2f}x" for code in peers])
        log(f"  round {k + 1}: {figures}; {ratios}")
    log(f"\nCraterKit speed-up 1 -> 2 threads: {statistics.median(scaling):.2f}x ({spread(scaling)})")
    for code in peers:
        log(f"CraterKit (2 threads) vs {code}: {statistics.median(against[code]):.2f}x faster "
            f"({spread(against[code])})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--particles", type=int, default=100000)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--skip", default="", help="comma-separated codes to skip: lammps,liggghts")
    ap.add_argument("--repeat", type=int, default=3,
                    help="rounds of all codes back to back; ratios are medians of the rounds'")
    args = ap.parse_args()
    if args.repeat < 1:
        sys.exit("--repeat must be at least 1")
    exe = os.path.join(args.build, "benchmarks", "dem_bed_impact", "ck_dem_bench")
    if not os.path.isfile(exe):
        sys.exit(f"{exe} not built: run scripts/test or scripts/demo first")
    work = os.path.join(args.build, "benchmarks", f"dem_bed_impact_{args.particles}")
    os.makedirs(work, exist_ok=True)
    bed = os.path.join(work, "bed.txt")
    if not os.path.isfile(bed):
        log(f"[1/4] settling a bed of about {args.particles} spheres (cached in {bed})")
        out, secs = run([exe, "make-bed", bed + ".tmp", str(args.particles)])
        os.replace(bed + ".tmp", bed)
        log(f"      {out.strip().splitlines()[-1]} in {secs:.0f} s")
    else:
        log(f"[1/4] using the cached bed {bed}")
    log(f"      the peers' decks in {work}/lammps (CraterKit's LAMMPS deck writer) and "
        f"{work}/liggghts")
    ck = write_decks(args, exe, work, bed)

    skip = set(filter(None, args.skip.split(",")))
    rounds = []
    for r in range(1, args.repeat + 1):
        log(f"round {r} of {args.repeat}")
        results = run_round(args, exe, work, bed, ck, skip)
        rounds.append(results)
        log(f"      round {r}: " + ", ".join(f"{code} {secs:.3f} s" for code, secs in results.items()))
    report(rounds, ck, args.steps)
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Bed settling benchmark: the wall time of a settled RCP GranularBed, stage by stage.

Two beds of about N monodisperse grains: the DEM bed-impact benchmark's box bed (r = 5 cm,
2000 kg/m^3, settled at 9.81 m/s^2; benchmarks/dem_bed_impact) and the SCI example's bowl bed
(bowl radius 1.05 m, grain density 1190/0.6 kg/m^3, settled at 1000 m/s^2; examples/sci_crater.py).
For each: the seconds of every stage (placement, relaxation of the loose placement, settling,
trim, stiffening to the DEM stage's law, rest in it), the settling steps, the bulk packing
fraction (0.58-0.64 for RCP), the coordination number, the smallest gap over all pairs (the
largest overlap, negative: the contacts carry the bed's weight), and whether the bed is at rest: released
under the impact's gravity, stiffness and contact law for --rest-steps DEM steps, its largest
displacement (in radii) and kinetic energy per grain (in m g r).

    benchmarks/bed_settling/run.py                              # box and bowl, 10^5 grains
    benchmarks/bed_settling/run.py --particles 10000 30000 --containers box
"""

import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.dirname(HERE))
from bench_common import log, run  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--particles", type=int, nargs="+", default=[100000])
    ap.add_argument("--containers", nargs="+", default=["box", "bowl"], choices=["box", "bowl"])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--rest-steps", type=int, default=500)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    args = ap.parse_args()
    exe = os.path.join(args.build, "benchmarks", "bed_settling", "ck_bed_bench")
    if not os.path.isfile(exe):
        sys.exit(f"{exe} not found: cmake --build {args.build} --target ck_bed_bench")
    env = dict(os.environ, OMP_NUM_THREADS=str(args.threads), OMP_PROC_BIND="false")
    rows = []
    for container in args.containers:
        for n in args.particles:
            log(f"{container} bed of about {n} grains on {args.threads} threads ...")
            out, wall = run([exe, container, str(n), str(args.rest_steps)], env=env)
            r = json.loads(out.strip().splitlines()[-1])
            stages = ", ".join(f"{k[:-2]} {v:.1f} s" for k, v in r.items() if k.endswith("_s"))
            log(f"  {r['particles']} grains, {r['seconds']:.1f} s ({stages}); {r['settling_steps']} "
                f"settling steps, {r['bed_rest_steps']} rest steps, packing fraction "
                f"{r['packing_fraction']:.4f}, coordination number {r['coordination_number']:.2f}, smallest gap "
                f"{r['smallest_gap_r']:.3g} r; after {r['rest_steps']} steps released: largest "
                f"displacement {r['rest_max_displacement_r']:.3g} r, kinetic energy "
                f"{r['rest_kinetic_energy_mgr']:.3g} m g r per grain; process {wall:.1f} s")
            rows.append(r)
    log("\n| container | grains | seconds | settling steps | packing fraction | smallest gap / r |"
        "\n|---|---|---|---|---|---|")
    for r in rows:
        log(f"| {r['container']} | {r['particles']} | {r['seconds']:.1f} | {r['settling_steps']} | "
            f"{r['packing_fraction']:.4f} | {r['smallest_gap_r']:.2g} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Validation of the SCI example (issue: CraterProfile, FragmentAnalysis and the SCI crater):
runs examples/sci_crater.py for RCP and HCP beds at two bed sizes, one after the other, and
prints a table of crater diameter, rim diameter and depth against the SCI crater and the
pi-scaling prediction, the RCP/HCP difference and the change between the two sizes.

    benchmarks/sci_crater/run.py                                   # Ryugu, 1e5 and 2e5 grains
    benchmarks/sci_crater/run.py --gravity 9.81 --particles 6000 12000
    benchmarks/sci_crater/run.py --resume ...                      # continue from checkpoints

Anything after -- goes to the example (e.g. -- --sph-target-radius 0.6). Results and reports
go under build/benchmarks/sci_crater/<packing>_<particles>/. At Ryugu gravity each run takes
days on two cores (the example prints its DEM step estimate first).
"""

import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def main(argv):
    split = argv.index("--") if "--" in argv else len(argv)
    own, extra = argv[:split], argv[split + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gravity", type=float, default=1.5e-4)
    p.add_argument("--particles", type=int, nargs="+", default=[100000, 200000])
    p.add_argument("--packings", nargs="+", default=["RCP", "HCP"], choices=["RCP", "HCP"])
    p.add_argument("--resume", action="store_true")
    p.add_argument("--output", default=os.path.join(ROOT, "build", "benchmarks", "sci_crater"))
    args = p.parse_args(own)
    rows = []
    for n in args.particles:
        for packing in args.packings:
            out = os.path.join(args.output, f"{packing}_{n}")
            cmd = [os.path.join(ROOT, "scripts", "pvbatch"), os.path.join(ROOT, "examples", "sci_crater.py"),
                   "--gravity", repr(args.gravity), "--particles", str(n), "--packing", packing,
                   "--output-dir", out] + (["--resume"] if args.resume else []) + extra
            print(f"== {packing}, {n} grains: {' '.join(cmd[1:])}", flush=True)
            start = time.time()
            code = subprocess.call(cmd)
            if code != 0:
                print(f"error: the run exited with {code}", file=sys.stderr)
                return code
            r = json.load(open(os.path.join(out, "report.json")))
            r["wall_s"] = round(time.time() - start, 1)
            rows.append((packing, n, r))
    print("\n| packing | grains | r (m) | D (m) | rim D (m) | depth (m) | D / pi-scaling | wall (s) |")
    print("|---|---|---|---|---|---|---|---|")
    fmt = lambda v: "none" if v is None else f"{v:.3g}"  # noqa: E731
    for packing, n, r in rows:
        print(f"| {packing} | {r['bed_particles']} | {r['grain_radius_m']:.3g} | {fmt(r['crater_diameter_m'])} | "
              f"{fmt(r['rim_diameter_m'])} | {fmt(r['crater_depth_m'])} | {fmt(r['diameter_over_pi_scaling'])} | "
              f"{r['wall_s']} |")
    r0 = rows[0][2]
    print(f"\npi-scaling for these parameters: D = {r0['pi_scaling_diameter_m']} m; SCI crater: "
          f"D = {r0['sci_crater_m']['diameter']} m, rim {r0['sci_crater_m']['rim_diameter']} m, "
          f"depth {r0['sci_crater_m']['depth']} m")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

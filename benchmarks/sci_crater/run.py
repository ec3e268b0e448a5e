#!/usr/bin/env python3
"""Validation of the SCI example: runs examples/sci_crater.py for RCP and HCP beds at two bed sizes on one SPH stage (the first
run's, handed to the others with --sph-state), and prints a table of crater diameter, rim
diameter and depth against the pi-scaling prediction for the run and against the SCI crater,
with the run read at Ryugu's gravity by pi-scaling (D x D_pi(Ryugu) / D_pi(run); in the gravity
regime the crater's shape and D / D_pi would not depend on g, but these runs do: --gravity). Checks, printed as PASS/FAIL: at
the largest RCP bed, the scaled diameter within 15 % and the depth within 25 % of the SCI crater's
(craterkit.sci.SCI_CRATER); HCP smaller and shallower than RCP; the change between the two bed sizes.
Exit status: 0 when every check passes, 1 when one fails, 3 when a run failed (then no
summary.json is written, and an older one is removed first).

    benchmarks/sci_crater/run.py                         # g = 1000, RCP and HCP, 3e4 and 1e5 grains
    benchmarks/sci_crater/run.py --particles 6000 --packings RCP
    benchmarks/sci_crater/run.py --resume ...            # continue the SPH and DEM stages from checkpoints

Anything after -- goes to the example (e.g. -- --sph-resolution 3). Results, reports and a
summary.json go under build/benchmarks/sci_crater/<packing>_<particles>/.
"""

import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
from craterkit.sci import SCI_CRATER as SCI  # noqa: E402

RUN_FAILED = 3  # the exit status when a run failed (1 is a failed check)


def main(argv):
    split = argv.index("--") if "--" in argv else len(argv)
    own, extra = argv[:split], argv[split + 1:]
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--gravity", type=float, default=1000.0)
    p.add_argument("--particles", type=int, nargs="+", default=[30000, 100000])
    p.add_argument("--packings", nargs="+", default=["RCP", "HCP"], choices=["RCP", "HCP", "Loose"])
    p.add_argument("--sph-state", default="", help="a saved SPH state to hand off (default: run the SPH stage once)")
    p.add_argument("--resume", action="store_true")
    p.add_argument("--output", default=os.path.join(ROOT, "build", "benchmarks", "sci_crater"))
    args = p.parse_args(own)
    rows = []
    sph_state = args.sph_state
    summary_path = os.path.join(args.output, "summary.json")
    if os.path.exists(summary_path):
        os.remove(summary_path)  # what an earlier run found must not stand for this one
    for n in args.particles:
        for packing in args.packings:
            out = os.path.join(args.output, f"{packing}_{n}")
            cmd = [os.path.join(ROOT, "scripts", "pvbatch"), os.path.join(ROOT, "examples", "sci_crater.py"),
                   "--gravity", repr(args.gravity), "--particles", str(n), "--packing", packing,
                   "--output-dir", out] + (["--resume"] if args.resume else []) + \
                  (["--sph-state", sph_state] if sph_state else []) + extra
            print(f"== {packing}, {n} grains: {' '.join(cmd[1:])}", flush=True)
            start = time.time()
            code = subprocess.call(cmd)
            report = os.path.join(out, "report.json")
            if code != 0 or not os.path.exists(report) or os.path.getmtime(report) < start - 1.0:
                print(f"error: the run exited with {code}" + ("" if code else " and wrote no report.json"),
                      file=sys.stderr)
                return RUN_FAILED
            r = json.load(open(report))
            r["wall_s"] = round(time.time() - start, 1)
            rows.append((packing, n, r))
            if not sph_state:
                sph_state = os.path.join(out, "sph_handoff.vtp")

    fmt = lambda v, d=3: "none" if v is None else f"{v:.{d}g}"  # noqa: E731
    print("\n| packing | grains | r (m) | D (m) | rim D (m) | depth (m) | D / D_pi | depth / D | "
          "at Ryugu: D / rim D / depth (m) | impactor's depth at the hand-off (m) | DEM steps | wall (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for packing, n, r in rows:
        s = r.get("scaled_to_ryugu_m")
        D, depth = r["crater_diameter_m"], r["crater_depth_m"]
        ryugu = f"{s['diameter']:.3g} / {s['rim_diameter']:.3g} / {s['depth']:.3g}" if s else "none"
        impactor = r.get("impactor_depth_at_handoff_m", {}).get("centre_of_mass_m")  # older reports lack it
        print(f"| {packing} | {r['bed_particles']} | {r['grain_radius_m']:.3g} | {fmt(D)} | {fmt(r['rim_diameter_m'])} | "
              f"{fmt(depth)} | {fmt(r['diameter_over_pi_scaling'])} | {fmt(depth / D if D else None, 2)} | {ryugu} | {fmt(impactor)} | "
              f"{r['dem_steps']} | {r['wall_s']} |")
    r0 = rows[0][2]
    print(f"\npi-scaling for these parameters: D = {r0['pi_scaling_diameter_m']} m; at Ryugu "
          f"{r0['pi_scaling_diameter_at_ryugu_m']} m; SCI crater: D = {SCI['diameter']} m, rim {SCI['rim_diameter']} m, "
          f"depth {SCI['depth']} m. Seconds per stage of the first run: {r0['seconds']}")

    def check(ok, text):
        print(f"{'PASS' if ok else 'FAIL'}: {text}")
        return ok

    by = {(pk, n): r for pk, n, r in rows}
    largest = max(args.particles)
    summary = {"rows": [{"packing": pk, "particles": n, "report": r} for pk, n, r in rows], "checks": []}
    rcp = by.get(("RCP", largest))
    if rcp and rcp.get("scaled_to_ryugu_m"):
        s = rcp["scaled_to_ryugu_m"]
        summary["checks"].append(check(abs(s["diameter"] / SCI["diameter"] - 1.0) <= 0.15,
                                       f"RCP at {largest}: scaled diameter {s['diameter']:.3g} m within 15 % of 14.5 m"))
        summary["checks"].append(check(abs(s["depth"] / SCI["depth"] - 1.0) <= 0.25,
                                       f"RCP at {largest}: scaled depth {s['depth']:.3g} m within 25 % of 2.3 m"))
    hcp = by.get(("HCP", largest))
    if rcp and hcp and rcp["crater_diameter_m"] and hcp["crater_diameter_m"]:
        summary["checks"].append(check(hcp["crater_diameter_m"] < rcp["crater_diameter_m"] and
                                       hcp["crater_depth_m"] < rcp["crater_depth_m"],
                                       f"HCP smaller and shallower than RCP (D {hcp['crater_diameter_m']:.3g} vs "
                                       f"{rcp['crater_diameter_m']:.3g} m, depth {hcp['crater_depth_m']:.3g} vs "
                                       f"{rcp['crater_depth_m']:.3g} m)"))
    if len(args.particles) > 1:
        small = min(args.particles)
        for packing in args.packings:
            a, b = by.get((packing, small)), by.get((packing, largest))
            if a and b and a["crater_diameter_m"] and b["crater_diameter_m"]:
                print(f"{packing}: D changes by {b['crater_diameter_m'] / a['crater_diameter_m'] - 1.0:+.1%} and the "
                      f"depth by {b['crater_depth_m'] / a['crater_depth_m'] - 1.0:+.1%} from {small} to {largest} grains")
    with open(summary_path, "w") as f:
        json.dump(summary, f, indent=1)
    return 0 if all(summary["checks"]) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Runs examples/bed_cross_section.py at its small default size and checks what it wrote."""

import json
import os
import sys

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example bed_cross_section")
code = run_example(source_dir, "bed_cross_section", ["--output-dir", out, "--width", "800"])
t.check(code == 0, f"example exited with {code}")
report = json.load(open(os.path.join(out, "report.json")))
t.check(report["particles"] > 1000, f"too few particles: {report['particles']}")
# A settled random packing of equal frictional spheres: between random loose packing (about
# 0.55, Onoda & Liniger 1990) and random close packing (0.64, Scott & Kilgour 1969), the
# example's grains fewer than 10 across the bowl (walls loosen the edge); its grains rest on one
# another: a mean coordination number between isostatic frictional (4) and frictionless (6)
# packings, with 0.5 for the contacts the weight-bearing overlaps add past isostaticity
# (docs/physics.md §7; GranularBed's rest in the DEM law).
t.check(0.50 <= report["bulk_packing_fraction"] <= 0.64,
        f"bulk packing fraction {report['bulk_packing_fraction']} outside [0.50, 0.64]")
t.check(4.0 <= report["coordination_number"] <= 6.5,
        f"coordination number {report['coordination_number']} outside [4, 6.5]")
print(f"packing fraction {report['bulk_packing_fraction']:.4f}, coordination number {report['coordination_number']:.3f}")
png = os.path.join(out, report["image"])
t.check(os.path.getsize(png) > 10000, "picture missing or empty")
t.check(os.path.isfile(os.path.join(out, "report.md")), "report.md missing")
sys.exit(t.close())

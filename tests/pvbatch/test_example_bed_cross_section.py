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
t.check(0.50 <= report["bulk_packing_fraction"] <= 0.64,
        f"bulk packing fraction {report['bulk_packing_fraction']} outside [0.50, 0.64]")
png = os.path.join(out, report["image"])
t.check(os.path.getsize(png) > 10000, "picture missing or empty")
t.check(os.path.isfile(os.path.join(out, "report.md")), "report.md missing")
sys.exit(t.close())

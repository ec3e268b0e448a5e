"""Runs examples/bed_impact.py at its default size and checks what it wrote."""

import json
import os
import sys

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example bed_impact")
code = run_example(source_dir, "bed_impact", ["--output-dir", out, "--width", "640"])
t.check(code == 0, f"example exited with {code}")
report = json.load(open(os.path.join(out, "report.json")))
t.check(report["bed_particles"] > 500, f"too few particles: {report['bed_particles']}")
t.check(abs(report["end_time_s"] - 0.5) < 1e-3, f"end time {report['end_time_s']}")
t.check(report["max_overlap_fraction"] < 0.05, f"overlap {report['max_overlap_fraction']}")
t.check(len(report["frames"]) == 6, f"frames {report['frames']}")
for frame in report["frames"]:
    t.check(os.path.getsize(os.path.join(out, frame)) > 5000, f"frame {frame} missing or empty")
sys.exit(t.close())

"""Runs examples/hvi_debris_cloud.py at a small size and checks what it wrote."""

import json
import os
import sys

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hvi_debris_cloud")
code = run_example(source_dir, "hvi_debris_cloud",
                   ["--output-dir", out, "--width", "640", "--particles", "3000"])
t.check(code == 0, f"example exited with {code}")
report = json.load(open(os.path.join(out, "report.json")))
t.check(report["particles"] > 2000, f"too few particles: {report['particles']}")
t.check(abs(report["end_time_s"] - 32e-6) < 1e-8, f"end time {report['end_time_s']}")
t.check(report["cloud_particles"] > 0 and 0.0 < report["F_measured"] <= 1.0,
        f"no debris cloud: {report['cloud_particles']} particles, F {report['F_measured']}")
t.check(report["R_measured"] > 0.0 and 0.0 < report["va_over_v0_measured"] < 2.0,
        f"cloud measures R {report['R_measured']}, v_a/v0 {report['va_over_v0_measured']}")
# The front moves ballistically (Section 3.1): its displacement between the last two outputs
# gives the quantile's v_a; 15 % allows for the few dozen particles of a 3000-particle tail.
va, va2 = report["va_over_v0_measured"], report["va_over_v0_two_snapshots"]
t.check(abs(va2 / va - 1.0) < 0.15, f"v_a/v0 {va} against {va2} from two outputs")
t.check(os.path.getsize(os.path.join(out, "debris_cloud.png")) > 5000, "picture missing or empty")
t.check("1.55" in open(os.path.join(out, "report.md")).read(), "report lacks the experiment's R")
sys.exit(t.close())

"""Runs examples/hvi_sweep.py --quick twice: the first runs every point and draws the contour
plots, the second keeps every finished run (resume)."""

import io
import json
import os
import sys
from contextlib import redirect_stdout

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hvi_sweep")
code = run_example(source_dir, "hvi_sweep", ["--quick", "--output-dir", out])
t.check(code == 0, f"example exited with {code}")
results = json.load(open(os.path.join(out, "results.json")))
t.check(len(results) == 7, f"{len(results)} runs, expected 4 + 4 sharing one")
t.check(all(0.0 < r["F"] <= 1.0 for r in results.values()), "a run without a debris cloud")
for name in ("calibration_R", "calibration_va", "calibration_F", "fragmentation_map"):
    t.check(os.path.getsize(os.path.join(out, name + ".png")) > 5000, f"{name}.png missing")
printed = io.StringIO()
with redirect_stdout(printed):
    code = run_example(source_dir, "hvi_sweep", ["--quick", "--output-dir", out])
t.check(code == 0 and printed.getvalue().count(": kept") == 7,
        f"the second sweep did not keep every run: {printed.getvalue()[-500:]!r}")
sys.exit(t.close())

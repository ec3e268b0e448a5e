"""Runs examples/hvi_sweep.py --quick twice: the first runs every point and draws the contour
plots, the second keeps every finished run (resume)."""

import io
import json
import os
import shutil
import sys
from contextlib import redirect_stdout

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hvi_sweep")
shutil.rmtree(out, ignore_errors=True)  # the first sweep runs every point (the second keeps them)
code = run_example(source_dir, "hvi_sweep", ["--quick", "--output-dir", out])
t.check(code == 0, f"example exited with {code}")
results = json.load(open(os.path.join(out, "results.json")))
t.check(len(results) == 7, f"{len(results)} runs, expected 4 + 4 sharing one")
t.check(all(0.0 < r["F"] <= 1.0 for r in results.values()), "a run without a debris cloud")
# Conservation in every run of the sweep (the paper's model is conservative; the energy of each
# broken bond is kept in the total): the total energy to the velocity-Verlet error at the
# paper's step, below 1e-3 over the run (example.hvi_debris_cloud prints 2.8e-4 for 3,000
# particles to 32 us), and the momentum to rounding (no external force acts).
for key, r in results.items():
    t.check(abs(r["energy_drift"]) < 1e-3, f"{key}: total energy drifted by {r['energy_drift']:.3g}")
    t.check(r["momentum_change"] < 1e-10, f"{key}: momentum changed by {r['momentum_change']:.3g}")
print("largest energy drift {:.3g}, momentum change {:.3g}".format(
    max(abs(r["energy_drift"]) for r in results.values()), max(r["momentum_change"] for r in results.values())))
for name in ("calibration_R", "calibration_va", "calibration_F", "fragmentation_map"):
    t.check(os.path.getsize(os.path.join(out, name + ".png")) > 5000, f"{name}.png missing")
printed = io.StringIO()
with redirect_stdout(printed):
    code = run_example(source_dir, "hvi_sweep", ["--quick", "--output-dir", out])
t.check(code == 0 and printed.getvalue().count(": kept") == 7,
        f"the second sweep did not keep every run: {printed.getvalue()[-500:]!r}")
sys.exit(t.close())

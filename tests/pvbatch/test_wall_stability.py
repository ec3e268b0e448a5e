"""benchmarks/sci_crater/wall_stability.py at a small size (10,000 grains, the pit 15 grain
diameters wide), in a bed made as the SCI validation's at Ryugu's gravity, 0.5 sqrt(D_pi/g) of
DEM (contacts set for 0.0233 m/s, 8 times softer than the crater stage's, to keep the test
short; at both stiffnesses pits below 40 degrees stood in the recorded runs, docs/validation.md):

- a pit cut at 15 degrees, half the grains' 30-degree angle of repose (HeapAngle's tests),
  stands: its depth stays the cut's within one grain radius. Pits that stood in the full-size
  runs deepened by 0.1-0.4 radii as the cut surface's grains settled; a slumping wall moves its
  grains by diameters. Its bed's kinetic energy is below the heap test's at-rest level (a
  sanity check);
- the same bed without friction (sliding and rolling) cannot hold a 45-degree wall: the pit
  loses more than a grain diameter of depth (a frictionless pile stands only at a few degrees;
  recorded: 2.8 radii in this time). This is the control that the measure sees a wall fail and
  that the frictions reach the integrator.

Bad arguments are refused by name before any work."""

import json
import os
import sys
import tempfile

from craterkit.testing import Checker, run_script

source_dir = sys.argv[1]
tool = os.path.join(source_dir, "benchmarks", "sci_crater", "wall_stability.py")
t = Checker("test_wall_stability")


def run(args):
    return run_script(tool, args, capture=True)


BAD = ((["--slopes", "95"], "--slopes"), (["--settling-friction", "3"], "--settling-friction"),
       (["--particles", "0"], "--particles"), (["--dem-time", "-1"], "--dem-time"),
       (["--static-friction", "-0.1"], "--static-friction"), (["--rolling-friction", "nan"], "--rolling-friction"),
       (["--pit-diameter", "40"], "--pit-diameter"), (["--max-expected-speed", "inf"], "--max-expected-speed"))
for bad, name in BAD:
    code, _, err = run(bad + ["--output-dir", tempfile.mkdtemp()])
    t.check(code == 2 and name in err, f"{bad} gave exit code {code} and {err.strip()[-200:]!r}")


def pit(slope, extra):
    folder = tempfile.mkdtemp()
    code, printed, _ = run(["--particles", "10000", "--slopes", str(slope), "--dem-time", "0.5", "--frames", "1",
                            "--max-expected-speed", "0.0233", "--output-dir", folder] + extra)
    t.check(code == 0, f"the tool exited with {code}: {printed[-500:]}")
    records = json.load(open(os.path.join(folder, "wall_stability.json")))
    t.check(len(records) == 1, f"{len(records)} records for one pit and one frame")
    t.check(os.path.isfile(os.path.join(folder, f"pit{slope}.png")), "no cross-section written")
    return records[0]


rec = pit(15, [])
change = rec["depth_m"] - rec["cut_depth_m"]
t.check(rec["grains_removed"] > 0, "the cut removed no grains")
t.check(abs(change) < rec["grain_radius_m"],
        f"the 15-degree pit's depth moved by {change:.3g} m (cut {rec['cut_depth_m']:.3g} m, grain radius "
        f"{rec['grain_radius_m']:.3g} m): a slope at half the angle of repose must stand")
t.check(rec["kinetic_energy_per_mgr"] < 1e-3,
        f"the bed is not at rest: kinetic energy {rec['kinetic_energy_per_mgr']:.3g} m g r per grain")
rec = pit(45, ["--static-friction", "0", "--rolling-friction", "0"])
change = rec["depth_m"] - rec["cut_depth_m"]
t.check(change < -2.0 * rec["grain_radius_m"],
        f"the frictionless 45-degree pit's depth moved by {change:.3g} m only (cut {rec['cut_depth_m']:.3g} m, "
        f"grain radius {rec['grain_radius_m']:.3g} m): its walls must slump")
sys.exit(t.close())

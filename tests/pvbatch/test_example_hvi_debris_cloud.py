"""Runs examples/hvi_debris_cloud.py --compare at a small size (the paper's model and the one with
shock heating, docs/physics.md §5.1) and checks what it wrote."""

import json
import os
import sys

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hvi_debris_cloud")
code = run_example(source_dir, "hvi_debris_cloud",
                   ["--output-dir", out, "--width", "640", "--particles", "3000", "--compare",
                    "--set", "ShockViscosityThreshold=450"])
t.check(code == 0, f"example exited with {code}")
report = json.load(open(os.path.join(out, "report.json")))
t.check(report["particles"] > 2000, f"too few particles: {report['particles']}")
t.check(abs(report["end_time_s"] - 32e-6) < 1e-8, f"end time {report['end_time_s']}")
runs = report.get("models", {})
t.check(sorted(runs) == ["None", "ShockViscosity"], f"models run: {sorted(runs)}")
for model, r in runs.items():
    t.check(r["cloud_particles"] > 0 and 0.0 < r["F_measured"] <= 1.0,
            f"{model}: no debris cloud: {r['cloud_particles']} particles, F {r['F_measured']}")
    t.check(r["R_measured"] > 0.0 and 0.0 < r["va_over_v0_measured"] < 2.0,
            f"{model}: cloud measures R {r['R_measured']}, v_a/v0 {r['va_over_v0_measured']}")
    # The front moves ballistically (Section 3.1): its displacement between the last two outputs
    # gives the quantile's v_a; 15 % allows for the few dozen particles of a 3000-particle tail.
    va, va2 = r["va_over_v0_measured"], r["va_over_v0_two_snapshots"]
    t.check(abs(va2 / va - 1.0) < 0.15, f"{model}: v_a/v0 {va} against {va2} from two outputs")
    # The front width (the leading tenth of the mass less its last hundredth) lies inside L_a.
    t.check(0.0 < r["front_sharpness"] < 1.0, f"{model}: front width {r['front_sharpness']} of L_a")
    # --set reaches the source (read back from it), for every model run.
    t.check(r.get("set_properties") == {"ShockViscosityThreshold": 450.0},
            f"{model}: --set ShockViscosityThreshold=450 reached the source as {r.get('set_properties')}")
    print(f"{model}: F {r['F_measured']}, R {r['R_measured']}, v_a/v0 {va}, front {r['front_sharpness']} L_a, "
          f"internal energy {r['internal_energy_J']:.4g} J of {r['total_energy_J']:.4g} J, total energy drift "
          f"{r['total_energy_drift']:.2e}")
if len(runs) == 2:
    paper, shock = runs["None"], runs["ShockViscosity"]
    # The paper's model has no internal energy; shock heating keeps a sizeable share of the
    # impact's energy as internal energy (BondedShock.TotalEnergyAndMomentumKeptThroughAnImpact:
    # more than 1 % at 4 us) and adds no energy error of its own: its total-energy drift stays
    # within twice the paper's model's, the integrator's own error, on the same set-up.
    t.check(paper["internal_energy_J"] == 0.0, f"the paper's model has internal energy {paper['internal_energy_J']}")
    t.check(shock["internal_energy_J"] > 0.01 * shock["total_energy_J"],
            f"ShockViscosity kept {shock['internal_energy_J']:.3g} J of {shock['total_energy_J']:.3g} J as heat")
    t.check(abs(shock["total_energy_drift"]) < 2.0 * abs(paper["total_energy_drift"]) + 1e-6,
            f"total energy drift {shock['total_energy_drift']:.2e} with ShockViscosity, "
            f"{paper['total_energy_drift']:.2e} without")
# A malformed --set is refused by name before any run.
code = run_example(source_dir, "hvi_debris_cloud", ["--output-dir", out, "--set", "ShockViscosityThreshold"])
t.check(code != 0, "--set without a value was accepted")
for image, least in (("debris_cloud_None.png", 5000), ("debris_cloud_ShockViscosity.png", 5000),
                     ("debris_cloud_compare.png", 10000)):
    path = os.path.join(out, image)
    t.check(os.path.isfile(path) and os.path.getsize(path) > least, f"{image} missing or empty")
t.check("1.55" in open(os.path.join(out, "report.md")).read(), "report lacks the experiment's R")
sys.exit(t.close())

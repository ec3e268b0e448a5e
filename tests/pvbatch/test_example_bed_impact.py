"""Runs examples/bed_impact.py at its default size and checks what it wrote: the energy the bed
dissipates and where the impactor comes to rest."""

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
# The physics: the contact law only dissipates (normal and tangential damping, sliding, rolling
# and twisting friction), so the mechanical energy (kinetic + rotational + elastic +
# gravitational) may only fall from output to output; 1 % of the impact's kinetic energy allows
# for the integrator's error. The copper sphere (0.3 m, 5 m/s, 8.4 times the grains' density)
# is stopped by the bed within the run: at 0.5 s it keeps less than 1 % of its kinetic energy.
# (Where it rests is printed, not asserted: two grain diameters across, it is outside the
# penetration laws measured for spheres much larger than the grains.)
imp = report["impactor"]
e0 = 0.5 * imp["mass_kg"] * report["impact_speed_m_s"] ** 2
energy = report["mechanical_energy_J"]
rises = [b - a for a, b in zip(energy, energy[1:])]
t.check(max(rises) < 0.01 * e0, f"the mechanical energy rose by {max(rises):.4g} J (impact {e0:.4g} J): {energy}")
t.check(imp["kinetic_energy_J"] < 0.01 * e0, f"the impactor keeps {imp['kinetic_energy_J']:.4g} J of {e0:.4g} J")
print(f"mechanical energy {energy[0]:.5g} -> {energy[-1]:.5g} J (impact {e0:.4g} J), largest rise "
      f"{max(rises):.3g} J; impactor at {imp['speed_m_s']:.3g} m/s, centre {imp['centre_depth_m']:.3g} m deep")
for frame in report["frames"]:
    t.check(os.path.getsize(os.path.join(out, frame)) > 5000, f"frame {frame} missing or empty")
sys.exit(t.close())

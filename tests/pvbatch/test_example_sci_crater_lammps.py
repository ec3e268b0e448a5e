"""Runs examples/sci_crater.py with --dem-engine lammps at a tiny size (g = 1e4 m/s^2: a 6,000
particle SPH stage, a bed of about 250 grains) next to the same run on CraterKit's DEM, both from
the one SPH hand-off state (the CraterKit run saves it, the LAMMPS run takes it with --sph-state),
and checks: the LAMMPS run wrote its deck, ran it on 2 MPI ranks and read its dump back; both
engines start from the same hand-off (the same particles and momentum, bit for bit, as the bed and
the hand-off are deterministic); they run the same number of steps to the same time (the deck holds
DEMIntegrator's step); the LAMMPS bed comes to rest; and the crater diameter and depth agree within
10 % (issue 34's criterion for the same impact in both codes). Exit 77 (skipped) without LAMMPS."""

import json
import os
import re
import sys

import numpy as np

from craterkit.lammps import lammps_available
from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
if not lammps_available():
    print("LAMMPS (lmp) or mpirun not installed: skipped")
    sys.exit(77)
t = Checker("example sci_crater --dem-engine lammps")
tiny = ["--particles", "300", "--frames", "2", "--width", "300", "--gravity", "10000"]
ck_dir, lmp_dir = os.path.join(out, "craterkit"), os.path.join(out, "lammps")
code = run_example(source_dir, "sci_crater", tiny + ["--output-dir", ck_dir])
t.check(code == 0, f"CraterKit engine: example exited with {code}")
code = run_example(source_dir, "sci_crater", tiny + ["--output-dir", lmp_dir, "--dem-engine", "lammps",
                                                     "--lammps-ranks", "2",
                                                     "--sph-state", os.path.join(ck_dir, "sph_handoff.vtp")])
t.check(code == 0, f"LAMMPS engine: example exited with {code}")
if code != 0:
    sys.exit(t.close())
ck = json.load(open(os.path.join(ck_dir, "report.json")))
lm = json.load(open(os.path.join(lmp_dir, "report.json")))
deck = os.path.join(lmp_dir, "lammps")
t.check(lm["dem_engine"] == "lammps" and ck["dem_engine"] == "craterkit", "engines not reported")
for name in ("in.craterkit", "data.craterkit", "dump.craterkit", "log.lammps"):
    t.check(os.path.isfile(os.path.join(deck, name)), f"LAMMPS run left no {name}")
log = open(os.path.join(deck, "log.lammps")).read() if os.path.isfile(os.path.join(deck, "log.lammps")) else ""
t.check("on 2 procs" in log, "LAMMPS did not run on 2 MPI ranks")
# The same hand-off: the same particles carrying the same momentum.
a, b = ck["dem_totals_after_handoff"], lm["dem_totals_after_handoff"]
t.check(a == b and ck["bed_particles"] == lm["bed_particles"], "the two runs did not start from the same hand-off")
# The same step and end time: the deck's dumps fall on DEMIntegrator's output steps (each the
# nearest step to the output time, so within one step of DEMIntegrator's first step at or after it).
t.check(abs(ck["dem_steps"] - lm["dem_steps"]) <= 1, f"steps {ck['dem_steps']} (CraterKit) vs {lm['dem_steps']} (LAMMPS)")
text = open(os.path.join(deck, "in.craterkit")).read()
dt = float(re.search(r"^timestep (\S+)", text, re.M).group(1))
t.check(abs(ck["dem_end_time_s"] - lm["dem_end_time_s"]) <= 1.5 * dt,
        f"end times {ck['dem_end_time_s']} vs {lm['dem_end_time_s']} s")
t.check(len(lm["crater_growth"]) == 2, f"{len(lm['crater_growth'])} LAMMPS frames read back, 2 expected")
end, start = lm["dem_totals_at_end"]["bed_kinetic_energy_J"], lm["dem_totals_after_handoff"]["bed_kinetic_energy_J"]
t.check(end < 0.5 * start, f"the LAMMPS bed did not come to rest: {start:.3g} J -> {end:.3g} J")
# The crater: the 10 % between the two codes on the same impact.
for key in ("crater_diameter_m", "crater_depth_m"):
    x, y = ck[key], lm[key]
    t.check(x is not None and y is not None and abs(y - x) <= 0.10 * x, f"{key}: CraterKit {x}, LAMMPS {y}")
p_ck, p_lm = np.array(ck["dem_totals_at_end"]["momentum_kg_m_s"]), np.array(lm["dem_totals_at_end"]["momentum_kg_m_s"])
print(f"crater diameter {ck['crater_diameter_m']:.4g} m (CraterKit) vs {lm['crater_diameter_m']:.4g} m (LAMMPS); "
      f"depth {ck['crater_depth_m']:.4g} vs {lm['crater_depth_m']:.4g} m; bed kinetic energy at the end "
      f"{ck['dem_totals_at_end']['bed_kinetic_energy_J']:.3g} vs {end:.3g} J; momentum at the end {p_ck.round(3)} vs "
      f"{p_lm.round(3)} kg m/s; DEM seconds {ck['seconds']['dem']} vs {lm['seconds']['dem']}")
sys.exit(t.close())

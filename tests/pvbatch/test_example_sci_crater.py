"""Runs examples/sci_crater.py at its smallest size (the SCI impactor and regolith at the default
1000 m/s^2: the SPH stage to the late hand-off, a bed of 1,500 grains) and checks what it wrote:
the crater's diameter is within 35 % of the pi-scaling prediction for the run's own parameters,
the hand-off carried the compact SPH material's momentum over exactly and the dropped ejecta
account for the rest, the DEM bed lost energy as it settled, the pi-scaling prediction agrees
with the values computed by hand in docs/physics.md section 4.2, the impactor's reported depth lies
inside the SPH target, and the pictures and report exist; then that a run resumed after its
first frame continues from the checkpoint, and that a bad --sph-coarsening, a negative --cohesion,
--rolling-friction or --late-stage-initial-sound-speed, a zero --handoff-fraction, a zero
--late-stage-sound-speed-exponent and a --late-stage-poisson-ratio of 0.5 are refused; and that
at Ryugu's gravity the example takes the validated set-up, option by option, unless told not to."""

import json
import os
import sys

import numpy as np

from craterkit.scaling import crater_diameter
from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example sci_crater")
code = run_example(source_dir, "sci_crater", ["--particles", "1500", "--frames", "2", "--width", "500",
                                              "--output-dir", out])
t.check(code == 0, f"example exited with {code}")
r = json.load(open(os.path.join(out, "report.json")))

sph = r["sph_totals_at_handoff"]
scale = np.linalg.norm(sph["momentum_kg_m_s"]) + np.linalg.norm(r["sph_ejecta_dropped"]["momentum_kg_m_s"]) + 1.0
# The bed carries the compact material below the curtain; the curtain (compact material above
# the surface) flies on as particles of its own.
t.check(np.allclose(np.add(r["dem_mapped_momentum_kg_m_s"], r["sph_curtain_momentum_kg_m_s"]),
                    r["sph_compact_momentum_kg_m_s"], rtol=0, atol=1e-10 * scale),
        "compact momentum not carried over")
t.check(np.allclose(np.add(r["sph_compact_momentum_kg_m_s"], r["sph_ejecta_dropped"]["momentum_kg_m_s"]),
                    sph["momentum_kg_m_s"], rtol=0, atol=1e-9 * scale),
        "compact and dropped ejecta momentum do not add up to the SPH total")
# What comes down outside the bowl leaves the domain; the DEM particles carry the rest.
t.check(np.allclose(np.add(r["dem_totals_after_handoff"]["momentum_kg_m_s"], r["sph_escaped"]["momentum_kg_m_s"]),
                    r["sph_compact_momentum_kg_m_s"], rtol=0, atol=1e-9 * scale),
        "the DEM particles and the escaped material do not carry the compact momentum (bed not at rest?)")
t.check(r["dem_steps"] > 1000, f"only {r['dem_steps']} DEM steps")
end, start = r["dem_totals_at_end"]["bed_kinetic_energy_J"], r["dem_totals_after_handoff"]["bed_kinetic_energy_J"]
t.check(end < 0.5 * start, f"the bed did not come to rest: kinetic energy {start:.3g} J -> {end:.3g} J")
# The scaling law as implemented against docs/physics.md 4.2 (computed there: 14.5 m at g = 1.5e-4
# and 14.9 m at 1.3e-4 for 2 kg of copper at 2 km/s into 1190 kg/m^3).
t.check(abs(r["pi_scaling_diameter_at_ryugu_m"] - 14.5) < 0.15, f"SCI pi-scaling {r['pi_scaling_diameter_at_ryugu_m']}")
t.check(abs(crater_diameter(2.0, 2000.0, 8900.0, 1190.0, 1.3e-4) - 14.9) < 0.15, "pi-scaling at 1.3e-4 m/s^2")
t.check(abs(r["target"]["bulk_density_kg_m3"] - 1190.0) < 2.0, f"target bulk density {r['target']['bulk_density_kg_m3']}")
# The crater: the criterion, within 35 % of pi-scaling (measured against the settled bed's
# own surface; the hand-off carves the SPH stage's crater and the DEM stage settles it).
ratio = r["diameter_over_pi_scaling"]
t.check(ratio is not None and abs(ratio - 1.0) <= 0.35,
        f"crater diameter {r['crater_diameter_m']} m against pi-scaling {r['pi_scaling_diameter_m']} m")
# The depth: simple craters in granular targets are 0.15-0.3 of their diameter deep (lunar simple
# craters 0.2, laboratory sand craters 0.2-0.3, the SCI crater 0.16); the profile follows the
# grains' tops, so it reads the depth to within a grain radius either way.
depth, diameter, grain = r["crater_depth_m"], r["crater_diameter_m"], r["grain_radius_m"]
t.check(depth is not None and diameter is not None and
        0.15 * diameter - grain <= depth <= 0.3 * diameter + grain,
        f"crater depth {depth} m for a diameter of {diameter} m and grains of radius {grain} m")
# The impactor's track at the hand-off: the dense sphere ploughs into the porous target (at
# 0.41 D_pi here) rather than rebounding (as it did when the regolith carried the basalt
# matrix's shear waves), so it is well below the surface: deeper than 0.1 D_pi (about three
# impactor radii), its deepest particle at least as deep as its centre of mass, and inside
# the SPH target (0.8 D_pi).
pen = r["impactor_depth_at_handoff_m"]
t.check(pen["centre_of_mass_m"] is not None and 0.1 * r["pi_scaling_diameter_m"] < pen["centre_of_mass_m"] <=
        pen["deepest_m"] < 0.8 * r["pi_scaling_diameter_m"], f"impactor's depth at the hand-off {pen}")
# One switch (no --late-stage-initial-sound-speed): the SPH state handed off under the late law
# it was asked for, 10 sqrt(g D_pi) (its own field, LateStageSoundSpeed).
late = r["late_stage"]
t.check(late["initial_sound_speed_m_s"] == 0.0 and late["sound_speed_at_handoff_m_s"] is not None and
        abs(late["sound_speed_at_handoff_m_s"] - late["sound_speed_m_s"]) <= 1e-9 * late["sound_speed_m_s"],
        f"the late stage at the hand-off: {late}")
for image in r["images"]:
    path = os.path.join(out, image)
    t.check(os.path.isfile(path) and os.path.getsize(path) > 10000, f"{image} missing or empty")
md = open(os.path.join(out, "report.md")).read()
t.check("pi_scaling_diameter_m" in md and "figure1_handoff.png" in md, "report.md lacks the prediction or a figure")
# The report says what the run is (scaled gravity, bed size, grains across the crater) and where
# validation stands, and rounds its numbers: no value in its table carries more than 3 digits.
t.check("What this run is" in md and "not Ryugu's" in md and "grain diameters" in md,
        "report.md does not say what the default run is")
t.check("## Validation" in md, "report.md lacks the validation section")
import re  # noqa: E402
long_numbers = [token for line in md.splitlines() if line.startswith("| ")
                for token in re.findall(r"\d*\.\d+", line)
                if len(token.replace(".", "").lstrip("0")) > 3]
t.check(not long_numbers, f"report.md has unrounded numbers: {long_numbers[:3]}")
print(f"crater diameter {r['crater_diameter_m']} m vs pi-scaling {r['pi_scaling_diameter_m']} m")

# Resuming: a run stopped after its first frame goes on from the checkpoint, which holds the
# last requested state, and does not recompute it (the checkpoint stays as it was) or overwrite
# it; the crater is the same to the last bit. --resume takes the SPH stage the first run saved.
import hashlib  # noqa: E402
checkpoint = os.path.join(out, "dem.ckdem")
growth_file = os.path.join(out, "dem_growth.json")
t.check(os.path.isfile(checkpoint) and os.path.isfile(growth_file), "no checkpoint or frame record written")
if os.path.isfile(growth_file):
    growth = json.load(open(growth_file))
    t.check(len(growth) == 2, f"{len(growth)} frames recorded, 2 expected")
    json.dump(growth[:1], open(growth_file, "w"))
    before = hashlib.sha256(open(checkpoint, "rb").read()).hexdigest()
    code = run_example(source_dir, "sci_crater", ["--particles", "1500", "--frames", "2", "--width", "500",
                                                  "--output-dir", out, "--resume"])
    t.check(code == 0, f"resumed example exited with {code}")
    again = json.load(open(os.path.join(out, "report.json")))
    t.check(again["seconds"]["sph"] < 0.2 * r["seconds"]["sph"],
            f"the resumed run's SPH stage took {again['seconds']['sph']} s of the first's {r['seconds']['sph']} s: "
            "it ran again instead of taking the saved one")
    t.check(hashlib.sha256(open(checkpoint, "rb").read()).hexdigest() == before,
            "the resumed run rewrote the checkpoint (it recomputed the DEM stage)")
    t.check(again["crater_diameter_m"] == r["crater_diameter_m"] and again["crater_depth_m"] == r["crater_depth_m"],
            f"resumed crater {again['crater_diameter_m']} m, {again['crater_depth_m']} m against "
            f"{r['crater_diameter_m']} m, {r['crater_depth_m']} m")
    t.check(again["crater_growth"] == growth, "the resumed run's frame record differs")
# Bad input: a graded target outside [1, 100] is refused before any work.
code = run_example(source_dir, "sci_crater", ["--sph-coarsening", "0.5", "--output-dir", out + "_bad"])
t.check(code == 2, f"--sph-coarsening 0.5: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--cohesion", "-1", "--output-dir", out + "_bad"])
t.check(code == 2, f"--cohesion -1: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--handoff-fraction", "0", "--output-dir", out + "_bad"])
t.check(code == 2, f"--handoff-fraction 0: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--rolling-friction", "-0.1", "--output-dir", out + "_bad"])
t.check(code == 2, f"--rolling-friction -0.1: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--late-stage-sound-speed-exponent", "0", "--output-dir", out + "_bad"])
t.check(code == 2, f"--late-stage-sound-speed-exponent 0: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--late-stage-initial-sound-speed", "-5", "--output-dir", out + "_bad"])
t.check(code == 2, f"--late-stage-initial-sound-speed -5: exit code {code}, expected the usage error 2")
code = run_example(source_dir, "sci_crater", ["--late-stage-poisson-ratio", "0.5", "--output-dir", out + "_bad"])
t.check(code == 2, f"--late-stage-poisson-ratio 0.5: exit code {code}, expected the usage error 2")
# The Ryugu preset: at Ryugu's gravity the example takes the validated set-up (sci.RYUGU_PRESET)
# option by option, the user's own options win, and the other gravities keep the general defaults.
import importlib.util  # noqa: E402

from craterkit import sci  # noqa: E402

spec = importlib.util.spec_from_file_location("sci_crater_example", os.path.join(source_dir, "examples", "sci_crater.py"))
example = importlib.util.module_from_spec(spec)
spec.loader.exec_module(example)
ryugu = example.parse_args(["--gravity", str(sci.RYUGU_GRAVITY)])
t.check((ryugu.sph_coarsening, ryugu.handoff_time, ryugu.particles, ryugu.sph_block_steps) == (10.0, 29.5, 30000, 7),
        f"Ryugu preset: coarsening {ryugu.sph_coarsening}, hand-off {ryugu.handoff_time} s, {ryugu.particles} grains, "
        f"block steps {ryugu.sph_block_steps}; expected the validation's 10, 29.5 s, 30000, 7")
own = example.parse_args(["--gravity", "1.5e-4", "--sph-coarsening", "8", "--handoff-fraction", "0.2"])
t.check((own.sph_coarsening, own.handoff_time, own.handoff_fraction, own.particles) == (8.0, 0.0, 0.2, 30000),
        f"the user's --sph-coarsening 8 --handoff-fraction 0.2 at Ryugu: coarsening {own.sph_coarsening}, hand-off "
        f"time {own.handoff_time}, fraction {own.handoff_fraction}, {own.particles} grains")
for words in (["--gravity", "1.5e-4", "--no-preset"], ["--gravity", "1000"]):
    plain = example.parse_args(words)
    t.check(not plain.preset and plain.sph_coarsening == 1.0 and plain.particles == 6000,
            f"{' '.join(words)}: preset {plain.preset}, coarsening {plain.sph_coarsening}, {plain.particles} grains; "
            "expected the general defaults")
sys.exit(t.close())

"""Runs examples/hybrid_handoff.py at its default size and checks what it wrote: the hand-off
carried the compact SPH material's momentum and angular momentum and the ejecta's momentum
over exactly, the DEM ran, and the picture exists."""

import json
import os
import sys

import numpy as np

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hybrid_handoff")
code = run_example(source_dir, "hybrid_handoff", ["--output-dir", out, "--width", "500"])
t.check(code == 0, f"example exited with {code}")
r = json.load(open(os.path.join(out, "report.json")))
scale = np.linalg.norm(r["sph_compact_momentum"]) + np.linalg.norm(r["sph_ejecta_momentum"])
# The bed carries the compact material below the curtain (compact material above the surface);
# the curtain flies on as particles with the ejecta.
t.check(np.allclose(np.add(r["dem_mapped_momentum"], r["sph_curtain_momentum"]), r["sph_compact_momentum"],
                    rtol=0, atol=1e-10 * scale), "compact momentum not carried over")
t.check(np.allclose(r["dem_ejecta_momentum"], np.add(r["sph_ejecta_momentum"], r["sph_curtain_momentum"]),
                    rtol=0, atol=1e-10 * scale), "ejecta and curtain momentum not carried over")
t.check(r["bed_particles_kept"] > 100 and r["dem_steps"] >= 1, "no bed or no DEM steps")
t.check(os.path.getsize(os.path.join(out, r["image"])) > 20000, "picture missing or empty")
sys.exit(t.close())

"""Image test (label render): the cross-section of a small seeded bed against a baseline.

Usage: scripts/pvbatch tests/pvbatch/test_render_cross_section.py BASELINE.png OUTPUT.png
       [--update]   (writes the baseline instead of comparing)
"""

import os
import shutil
import sys

from craterkit import load_plugin
from craterkit.compare import image_difference
from craterkit.cross_section import render_cross_section

# (Not "output": ParaView runs the ProgrammableSource script in __main__ and deletes that name.)
baseline, rendered = sys.argv[1], sys.argv[2]
simple = load_plugin()
bed = simple.GranularBed(Packing="RCP", Container="Bowl", ContainerRadius=5.0,
                         ParticleRadius=0.4, RandomSeed=7)
render_cross_section(bed, rendered, resolution=(400, 240), label="RCP test bed",
                     color_range=(-5.0, 0.0))
if "--update" in sys.argv:
    shutil.copyfile(rendered, baseline)
    print(f"baseline written: {baseline}")
    sys.exit(0)
if not os.path.isfile(baseline):
    print(f"FAIL: no baseline {baseline}; create it with --update and commit it")
    sys.exit(1)
error = image_difference(rendered, baseline)
threshold = 15.0
print(f"image difference {error:.2f} (threshold {threshold})")
print("1 passed, 0 failed" if error <= threshold else "0 passed, 1 failed")
sys.exit(0 if error <= threshold else 1)

"""Run by tests/install/test_install.py with an installed craterkit-pvbatch, from the prefix
alone: the craterkit package, the plugin and the material files are the installed ones, the
versions agree, and the SPH filter finds its materials without CRATERKIT_MATERIALS.

Usage: P/bin/craterkit-pvbatch installed_check.py PREFIX VERSION
"""

import os
import sys

prefix, expected = os.path.realpath(sys.argv[1]), sys.argv[2]
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"FAIL: {message}", flush=True)


def inside(path):
    return path is not None and os.path.realpath(path).startswith(prefix + os.sep)


import craterkit  # noqa: E402
from craterkit.report import git_commit  # noqa: E402

check(inside(craterkit.__file__), f"craterkit imported from {craterkit.__file__}, not from {prefix}")
check(craterkit.__version__ == expected, f"craterkit.__version__ {craterkit.__version__}")
check(craterkit.SOURCE_ROOT is None, f"installed package sees a source tree {craterkit.SOURCE_ROOT}")
check(git_commit() is None, f"installed package reports commit {git_commit()}")
check(inside(craterkit.plugin_path()), f"plugin {craterkit.plugin_path()}")
for name in ("materials", "run-lammps", "plugin"):
    path = craterkit.resource_path(name)
    check(inside(path) and os.path.exists(path), f"resource {name}: {path}")
check(craterkit.material_value("copper", "rho0") > 8000.0, "copper's rho0 from the installed materials")

simple = craterkit.load_plugin()
check(craterkit.plugin_version() == expected, f"plugin version {craterkit.plugin_version()}")
# The SPH filter's default material folder: the installed share/craterkit/materials.
check("CRATERKIT_MATERIALS" not in os.environ, "CRATERKIT_MATERIALS is set")
sph = simple.SPHImpact(ParticlesAcrossImpactor=3, TargetRadius=0.15, EndTime=2e-5, OutputInterval=2e-5)
sph.UpdatePipeline(0.0)
data = craterkit.fetch(sph)
check(data.GetNumberOfPoints() > 100, f"SPHImpact made {data.GetNumberOfPoints()} particles")

print(f"installed check: {len(failures)} failed", flush=True)
sys.exit(1 if failures else 0)

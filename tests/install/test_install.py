#!/usr/bin/env python3
"""`cmake --install BUILD --prefix P` into a temporary prefix, then CraterKit from P alone.

Checks: the install leaves the build tree's plugin as it was; P holds the plugin, the Python
package, craterkit-pvbatch, the examples, the material files and the plugin list; every
installed ELF file has the RUNPATH $ORIGIN and holds no path into the build tree; no installed
text file names the source tree; files an older install listed in its manifest are removed,
and a reinstall replaces changed files. Then, with PATH=P/bin:/usr/bin:/bin and no
PV_PLUGIN_PATH, PYTHONPATH or CRATERKIT_* in the environment, from an empty working folder:
`craterkit-pvbatch P/share/craterkit/examples/bed_impact.py --help`, the installed package's
own checks (tests/install/installed_check.py: versions, where everything comes from, an SPH
source finding the installed materials), and a small run of examples/bed_cross_section.py
(an HCP bed) whose report.json names the version and gives a packing fraction.

Usage: test_install.py BUILD_DIR SOURCE_DIR VERSION
"""

import json
import os
import shutil
import sys
import tempfile

build_dir, source_dir, version = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2]), sys.argv[3]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python"))
from craterkit.testing import Checker, check_tree_paths, timed_run as run  # noqa: E402

checker = Checker("install test")
check, failures = checker.check, checker.failures


def plugin_dir_of_build():
    with open(os.path.join(build_dir, "craterkit-plugin-dir.txt")) as f:
        return f.readline().strip()


def snapshot(folder):
    return {name: os.path.getsize(os.path.join(folder, name)) for name in os.listdir(folder)
            if os.path.isfile(os.path.join(folder, name))}


tmp = tempfile.mkdtemp(prefix="craterkit-install-")
prefix = os.path.join(tmp, "prefix")

# An "older version" in the prefix: its manifest lists a module and an example this version
# does not have, and a Python cache beside the module.
old_files = ["lib/python3/dist-packages/craterkit/old_module.py", "share/craterkit/examples/old_example.py"]
for rel in old_files + ["lib/python3/dist-packages/craterkit/__pycache__/old_module.cpython-311.pyc"]:
    os.makedirs(os.path.dirname(os.path.join(prefix, rel)), exist_ok=True)
    open(os.path.join(prefix, rel), "w").write("# an older CraterKit\n")
os.makedirs(os.path.join(prefix, "share", "craterkit"), exist_ok=True)
with open(os.path.join(prefix, "share", "craterkit", "install-manifest.txt"), "w") as f:
    f.write("# CraterKit 0.0.1: the files installed under this prefix, relative to it.\n")
    f.write("\n".join(old_files + ["share/craterkit/install-manifest.txt"]) + "\n")
untouched = os.path.join(prefix, "share", "craterkit", "not_in_any_manifest.txt")
open(untouched, "w").write("a file of the user's\n")

# Install.
build_plugin_dir = plugin_dir_of_build()
before = snapshot(build_plugin_dir)
done = run(["cmake", "--install", build_dir, "--prefix", prefix])
check(done.returncode == 0, f"cmake --install failed:\n{done.stdout}\n{done.stderr}")
check(snapshot(build_plugin_dir) == before, "the install changed the build tree's plugin folder")
check(os.path.isfile(os.path.join(build_plugin_dir, "CraterKit.so")), "the build tree lost its plugin")

# What is installed.
plugins = None
for root, dirs, files in os.walk(prefix):
    if "CraterKit.so" in files:
        plugins = os.path.dirname(root)
check(plugins is not None and os.path.basename(plugins) == "plugins"
      and os.path.basename(os.path.dirname(plugins)).startswith("paraview-"),
      f"no CraterKit.so under {prefix}/lib/.../paraview-X.Y/plugins/CraterKit")
plugin_dir = os.path.join(plugins or prefix, "CraterKit")
expected = [os.path.join(plugin_dir, f) for f in
            ("CraterKit.so", "libCraterKitFilters.so", "libCraterKitReaders.so", "craterkit-build.json")]
expected += [os.path.join(plugins or prefix, "craterkit.plugins.xml")]
expected += [os.path.join(prefix, p) for p in (
    "bin/craterkit-pvbatch", "bin/craterkit-run-lammps", "bin/paraview.conf",
    "lib/python3/dist-packages/craterkit/__init__.py", "lib/python3/dist-packages/craterkit/_version.py",
    "lib/python3/dist-packages/craterkit/report.py", "share/craterkit/install-manifest.txt",
    "share/doc/craterkit/copyright")]
expected += [os.path.join(prefix, "share/craterkit/examples", f)
             for f in os.listdir(os.path.join(source_dir, "examples")) if f.endswith(".py")]
expected += [os.path.join(prefix, "share/craterkit/materials", f)
             for f in os.listdir(os.path.join(source_dir, "data", "materials")) if f.endswith(".cfg")]
for path in expected:
    check(os.path.isfile(path), f"not installed: {os.path.relpath(path, prefix)}")
for rel in old_files + ["lib/python3/dist-packages/craterkit/__pycache__"]:
    check(not os.path.exists(os.path.join(prefix, rel)), f"a file of the older install is left: {rel}")
check(os.path.isfile(untouched), "the install removed a file no manifest lists")
manifest = open(os.path.join(prefix, "share", "craterkit", "install-manifest.txt")).read()
check(f"CraterKit {version}" in manifest and "bin/craterkit-pvbatch" in manifest.splitlines(),
      "the new manifest does not list this install")

# Nothing points into the build or source tree.
elf_count = check_tree_paths(check, prefix, build_dir, source_dir)
check(elf_count == 3, f"{elf_count} ELF files installed, expected the plugin's 3")

# Reinstall over it: a changed file is replaced, the old manifest's files removed first.
version_py = os.path.join(prefix, "lib/python3/dist-packages/craterkit/_version.py")
open(version_py, "a").write('__version__ = "0.0.1"\n')
done = run(["cmake", "--install", build_dir, "--prefix", prefix])
check(done.returncode == 0 and "Removed the" in done.stdout, f"reinstall:\n{done.stdout}\n{done.stderr}")
check('"0.0.1"' not in open(version_py).read(), "the reinstall left a changed _version.py")

# CraterKit from the prefix alone.
env = {"PATH": f"{prefix}/bin:/usr/bin:/bin", "HOME": os.path.join(tmp, "home"),
       "OMP_NUM_THREADS": "1", "LANG": "C.UTF-8"}
for name in ("DISPLAY", "XAUTHORITY"):  # how the caller renders, if it can
    if name in os.environ:
        env[name] = os.environ[name]
os.makedirs(env["HOME"])
cwd = os.path.join(tmp, "run")
os.makedirs(cwd)
pvbatch = os.path.join(prefix, "bin", "craterkit-pvbatch")
check(shutil.which("craterkit-pvbatch", path=env["PATH"]) == pvbatch, "craterkit-pvbatch is not P/bin's")

done = run(["craterkit-pvbatch", os.path.join(prefix, "share/craterkit/examples/bed_impact.py"), "--help"],
           env=env, cwd=cwd)
check(done.returncode == 0 and "usage:" in done.stdout, f"bed_impact.py --help:\n{done.stdout}\n{done.stderr}")

shutil.copy(os.path.join(source_dir, "tests", "install", "installed_check.py"), cwd)
done = run(["craterkit-pvbatch", "installed_check.py", prefix, version], env=env, cwd=cwd)
print(done.stdout.strip())
check(done.returncode == 0, f"installed_check.py:\n{done.stdout}\n{done.stderr}")

out = os.path.join(cwd, "bed")
done = run(["craterkit-pvbatch", os.path.join(prefix, "share/craterkit/examples/bed_cross_section.py"),
            "--output-dir", out, "--packing", "HCP", "--container-radius", "8", "--width", "480"],
           env=env, cwd=cwd)
check(done.returncode == 0, f"bed_cross_section.py:\n{done.stdout}\n{done.stderr}")
try:
    report = json.load(open(os.path.join(out, "report.json")))
except (OSError, ValueError) as error:
    report = {}
    check(False, f"no report.json: {error}")
check(report.get("craterkit_version") == version, f"report.json craterkit_version {report.get('craterkit_version')}")
check("git_commit" in report and report["git_commit"] is None,
      f"report.json git_commit {report.get('git_commit')!r}: an installed CraterKit has no commit")
# An HCP lattice in the bowl: below the ideal pi/(3 sqrt 2) = 0.7405 by what the wall cuts off.
phi = report.get("bulk_packing_fraction")
check(phi is not None and 0.70 <= phi <= 0.7405, f"bulk packing fraction {phi} outside [0.70, 0.7405]")
check(report.get("particles", 0) > 300, f"particles {report.get('particles')}")

if failures:
    print(f"install test: {len(failures)} failed; the prefix is kept in {prefix}", flush=True)
    sys.exit(1)
shutil.rmtree(tmp)
print("install test: all passed", flush=True)

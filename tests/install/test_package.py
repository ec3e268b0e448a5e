#!/usr/bin/env python3
"""The Debian package: cpack -G DEB on the build (as scripts/package does, into a temporary
folder), then its name, fields, dependencies and contents: the plugin where Debian's ParaView
keeps its plugins, the plugin list and the GUI's paraview.conf, the Python package,
craterkit-pvbatch, the examples and the material files; no -dev package among the
dependencies; every ELF file with the RUNPATH $ORIGIN and no file holding the build folder's
path (nor a text file the source tree's).

Usage: test_package.py BUILD_DIR SOURCE_DIR VERSION
"""

import os
import re
import shutil
import sys
import tempfile

build_dir, source_dir, version = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2]), sys.argv[3]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python"))
from craterkit.testing import Checker, check_tree_paths, timed_run as run  # noqa: E402

checker = Checker("package test")
check, failures = checker.check, checker.failures


missing = [tool for tool in ("cpack", "dpkg-deb", "dpkg-shlibdeps", "readelf") if not shutil.which(tool)]
if missing:
    print(f"skipped: {', '.join(missing)} not found (Debian: apt-get install cmake dpkg-dev binutils)")
    sys.exit(77)
tmp = tempfile.mkdtemp(prefix="craterkit-package-")
done = run(["cpack", "-G", "DEB", "--config", os.path.join(build_dir, "CPackConfig.cmake"), "-B", tmp],
           cwd=tmp)
check(done.returncode == 0, f"cpack failed:\n{done.stdout}\n{done.stderr}")
arch = run(["dpkg", "--print-architecture"]).stdout.strip()
deb = os.path.join(tmp, f"craterkit_{version}_{arch}.deb")
check(os.path.isfile(deb), f"no {os.path.basename(deb)} in {sorted(os.listdir(tmp))}")
if not os.path.isfile(deb):
    sys.exit(1)

# Fields and dependencies.
fields = {}
for line in run(["dpkg-deb", "-f", deb]).stdout.splitlines():
    if line and not line.startswith(" "):
        key, _, value = line.partition(":")
        fields[key] = value.strip()
print("Depends:", fields.get("Depends"))
check(fields.get("Package") == "craterkit" and fields.get("Version") == version,
      f"Package {fields.get('Package')}, Version {fields.get('Version')}")
depends = [d.strip().split()[0] for d in re.split(r"[,|]", fields.get("Depends", "")) if d.strip()]
check(not [d for d in depends if d.endswith("-dev")], f"depends on development packages: {depends}")
for needed in ("paraview", "python3-paraview", "python3-numpy", "python3-matplotlib", "xvfb", "libgomp1"):
    check(needed in depends, f"no dependency on {needed}: {depends}")
check(re.search(r"paraview \(<< 5\.11", fields.get("Depends", "")) is not None,
      "the dependency on paraview does not stop at the 5.11 the plugin was built for")

# Contents.
listing = run(["dpkg-deb", "-c", deb]).stdout
paths = {line.split()[-1].lstrip(".") for line in listing.splitlines() if line.strip()}
plugins = "/usr/lib/x86_64-linux-gnu/paraview-5.11/plugins" if arch == "amd64" else None
expected = ["/usr/bin/craterkit-pvbatch", "/usr/bin/craterkit-run-lammps", "/usr/bin/paraview.conf",
            "/usr/lib/python3/dist-packages/craterkit/__init__.py",
            "/usr/lib/python3/dist-packages/craterkit/_version.py",
            "/usr/share/craterkit/materials/copper.cfg", "/usr/share/craterkit/examples/bed_impact.py",
            "/usr/share/doc/craterkit/copyright"]
if plugins:
    expected += [f"{plugins}/craterkit.plugins.xml", f"{plugins}/CraterKit/CraterKit.so",
                 f"{plugins}/CraterKit/libCraterKitFilters.so", f"{plugins}/CraterKit/libCraterKitReaders.so",
                 f"{plugins}/CraterKit/craterkit-build.json"]
for path in expected:
    check(path in paths, f"not in the package: {path}")
for f in os.listdir(os.path.join(source_dir, "examples")):
    if f.endswith(".py"):
        check(f"/usr/share/craterkit/examples/{f}" in paths, f"example {f} not in the package")
check(not [p for p in paths if p.startswith("/usr/include") or p.endswith(".a")],
      "the package holds headers or static libraries")
check(not [p for p in paths if not p.startswith("/usr/")], "files outside /usr")

# Nothing points into the build or source tree.
root = os.path.join(tmp, "root")
run(["dpkg-deb", "-x", deb, root])
elf = check_tree_paths(check, root, build_dir, source_dir, shown=lambda rel: "/" + rel)
check(elf == 3, f"{elf} ELF files in the package, expected the plugin's 3")
conf = open(os.path.join(root, "usr/bin/paraview.conf")).read().strip()
check(os.path.normpath(os.path.join("/usr/bin", conf)) == f"{plugins}/craterkit.plugins.xml",
      f"paraview.conf names {conf}")

if failures:
    print(f"package test: {len(failures)} failed; kept {tmp}", flush=True)
    sys.exit(1)
shutil.rmtree(tmp)
print(f"package test: all passed ({os.path.basename(deb)})", flush=True)

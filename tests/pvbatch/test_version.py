"""One version everywhere: CMake's PROJECT_VERSION (the argument) equals the plugin's version as
ParaView reports it (Tools > Manage Plugins shows the same), craterkit.__version__, the
"craterkit_version" of a report written by write_report (and its report.md line), the writer
in a DEM checkpoint's header, the versions beside the plugin (craterkit-build.json), and the
version of CITATION.cff and CHANGELOG.md. load_plugin's refusals of a plugin built for another
ParaView or of another CraterKit version name both versions.

Usage: scripts/pvbatch tests/pvbatch/test_version.py VERSION SOURCE_DIR
"""

import json
import os
import re
import shutil
import sys
import tempfile

import craterkit
from craterkit import load_plugin
from craterkit.report import write_report
from craterkit.testing import Checker

expected, source_dir = sys.argv[1], sys.argv[2]
t = Checker("test_version")

# The Python package.
t.check(craterkit.__version__ == expected, f"craterkit.__version__ {craterkit.__version__} != {expected}")

# The plugin, as ParaView's plugin manager reports it.
simple = load_plugin()
from paraview import servermanager  # noqa: E402 (after pvbatch's set-up)

info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
versions = {info.GetPluginName(i): info.GetPluginVersion(i) for i in range(info.GetNumberOfPlugins())
            if info.GetPluginLoaded(i)}
t.check(versions.get("CraterKit") == expected, f"plugin manager: CraterKit {versions.get('CraterKit')}")
t.check(craterkit.plugin_version() == expected, f"craterkit.plugin_version() {craterkit.plugin_version()}")

# Beside the plugin: the versions load_plugin checks before loading.
plugin = craterkit.plugin_path()
build = json.load(open(os.path.join(os.path.dirname(plugin), "craterkit-build.json")))
running = f"{servermanager.vtkSMProxyManager.GetVersionMajor()}.{servermanager.vtkSMProxyManager.GetVersionMinor()}"
t.check(build["craterkit_version"] == expected, f"craterkit-build.json: {build}")
t.check(build["paraview_version"] == running, f"craterkit-build.json: ParaView {build['paraview_version']}, running {running}")

# A report.
out = tempfile.mkdtemp(prefix="craterkit-version-")
write_report(out, "version check", "none.png", {"example": "version_check", "value": 1.5})
report = json.load(open(os.path.join(out, "report.json")))
t.check(list(report)[:3] == ["example", "craterkit_version", "git_commit"], f"report.json keys {list(report)}")
t.check(report["craterkit_version"] == expected, f"report.json craterkit_version {report['craterkit_version']}")
t.check(report["value"] == 1.5, "report.json lost an entry")
commit = report["git_commit"]
if os.path.isdir(os.path.join(source_dir, ".git")) and craterkit.SOURCE_ROOT:
    t.check(isinstance(commit, str) and re.fullmatch(r"[0-9a-f]{4,40}(-dirty)?", commit) is not None,
            f"report.json git_commit {commit!r} in a git clone")
else:
    t.check(commit is None, f"report.json git_commit {commit!r} outside a git clone")
md = open(os.path.join(out, "report.md")).read().splitlines()
t.check(md[0] == "# CraterKit: version check" and md[2].startswith(f"CraterKit {expected}"),
        f"report.md begins {md[:3]}")
t.check(not any("craterkit_version" in line for line in md), "report.md's table got the version")

# A checkpoint's header: bytes 24-55 name the CraterKit that wrote it
# (Solvers/common/CheckpointFormat.h).
if os.path.isfile(os.path.join(source_dir, "Solvers", "common", "CheckpointFormat.h")):
    path = os.path.join(out, "tiny.ckdem")
    bed = simple.GranularBed(Packing="HCP", Container="Box", BoxSize=[0.6, 0.6, 0.3],
                             ParticleRadius=0.1, SurfaceHeight=0.0)
    dem = simple.DEMIntegrator(Input=bed, SurfaceGravity=[0.0, 0.0, -9.81], EndTime=0.002,
                               OutputInterval=0.002, CheckpointFile=path, CheckpointInterval=2)
    dem.UpdatePipeline(0.002)
    t.check(os.path.isfile(path), "no checkpoint written")
    if os.path.isfile(path):
        head = open(path, "rb").read(72)
        t.check(head[:8] == b"CRATERKT", f"checkpoint magic {head[:8]!r}")
        writer = head[24:56].rstrip(b"\0").decode("ascii", "replace")
        t.check(writer == f"CraterKit {expected}", f"checkpoint writer {writer!r}")
else:
    print("no Solvers/common/CheckpointFormat.h: the checkpoint header was not checked")

# The release files.
citation = open(os.path.join(source_dir, "CITATION.cff")).read()
m = re.search(r"^version:\s*\"?([^\"\s]+)", citation, re.M)
t.check(m is not None and m.group(1) == expected, f"CITATION.cff version {m.group(1) if m else None}")
changelog = open(os.path.join(source_dir, "CHANGELOG.md")).read()
t.check(f"## [{expected}]" in changelog, f"CHANGELOG.md has no section [{expected}]")

# load_plugin refuses, naming both versions, a plugin built for another ParaView or of another
# CraterKit version (a stand-in plugin folder: only its craterkit-build.json is read).
fake = tempfile.mkdtemp(prefix="craterkit-fake-plugin-")
fake_plugin = os.path.join(fake, "CraterKit.so")
open(fake_plugin, "w").close()
for changed, names in (({"paraview_version": "4.2"}, ["ParaView 4.2", f"ParaView {running}"]),
                       ({"craterkit_version": "0.0.1"}, ["version 0.0.1", f"version {expected}"])):
    with open(os.path.join(fake, "craterkit-build.json"), "w") as f:
        json.dump(dict(build, **changed), f)
    try:
        craterkit._check_build(fake_plugin)
        message = None
    except SystemExit as stop:
        message = str(stop.code)
    t.check(message is not None and all(n in message for n in names),
            f"no refusal naming {names}: {message!r}")

code = t.close()
if code == 0:
    shutil.rmtree(out)
    shutil.rmtree(fake)
sys.exit(code)

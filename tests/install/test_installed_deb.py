#!/usr/bin/env python3
"""The installed Debian package, as a user meets it (skipped, exit 77, unless the package
craterkit is installed: apt install ./build/craterkit_<version>_amd64.deb). With no
PV_PLUGIN_PATH, PYTHONPATH or CRATERKIT_* in the environment:
  - pvpython: `import craterkit` is the installed package of VERSION, craterkit.load_plugin()
    loads /usr/lib/<multiarch>/paraview-5.11/plugins/CraterKit/CraterKit.so and makes a bed;
  - craterkit-pvbatch runs an installed example (--help);
  - ParaView's GUI (under xvfb-run, with a fresh HOME) lists CraterKit in its plugin manager,
    from /usr/bin/paraview.conf and craterkit.plugins.xml, not loaded (auto-load off), and
    loads it from there as VERSION.

Usage: test_installed_deb.py VERSION
"""

import os
import shutil
import subprocess
import sys
import tempfile

version = sys.argv[1]
status = subprocess.run(["dpkg-query", "-W", "-f=${Status} ${Version}", "craterkit"],
                        capture_output=True, text=True).stdout
if not status.startswith("install ok installed"):
    print("the package craterkit is not installed: skipped")
    sys.exit(77)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"FAIL: {message}", flush=True)


tmp = tempfile.mkdtemp(prefix="craterkit-deb-")
env = {k: v for k, v in os.environ.items()
       if k not in ("PV_PLUGIN_PATH", "PYTHONPATH", "PV_PLUGIN_CONFIG_FILE") and not k.startswith("CRATERKIT_")}
env.update(HOME=tmp, OMP_NUM_THREADS="1")
check(status.split()[-1] == version, f"installed craterkit is {status.split()[-1]}, not {version}")

script = os.path.join(tmp, "load.py")
with open(script, "w") as f:
    f.write("""import os, craterkit
simple = craterkit.load_plugin()
bed = simple.GranularBed(Packing="HCP", Container="Box", BoxSize=[1.0, 1.0, 0.5], ParticleRadius=0.1)
print("file", craterkit.__file__)
print("version", craterkit.__version__, craterkit.plugin_version())
print("plugin", os.path.realpath(craterkit.plugin_path()))
print("points", craterkit.fetch(bed).GetNumberOfPoints())
""")
done = subprocess.run(["pvpython", script], capture_output=True, text=True, env=env, cwd=tmp)
lines = dict(line.split(" ", 1) for line in done.stdout.splitlines() if " " in line)
print(done.stdout.strip())
check(done.returncode == 0, f"pvpython load.py exited {done.returncode}:\n{done.stderr}")
check(lines.get("file", "").startswith("/usr/lib/python3/dist-packages/craterkit/"), f"craterkit from {lines.get('file')}")
check(lines.get("version") == f"{version} {version}", f"versions (package, plugin): {lines.get('version')}")
check(lines.get("plugin", "").startswith("/usr/lib/") and "/paraview-5.11/plugins/CraterKit/CraterKit.so" in lines.get("plugin", ""),
      f"plugin {lines.get('plugin')}")
check(int(lines.get("points", "0")) > 10, f"bed points {lines.get('points')}")

done = subprocess.run(["craterkit-pvbatch", "/usr/share/craterkit/examples/bed_impact.py", "--help"],
                      capture_output=True, text=True, env=env, cwd=tmp)
check(done.returncode == 0 and "usage:" in done.stdout, f"craterkit-pvbatch --help:\n{done.stderr}")

if shutil.which("xvfb-run") and shutil.which("paraview"):
    out = os.path.join(tmp, "gui.txt")
    gui = os.path.join(tmp, "gui.py")
    with open(gui, "w") as f:
        f.write(f"""from paraview import servermanager
info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
rows = [(info.GetPluginName(i), info.GetPluginFileName(i), info.GetPluginLoaded(i))
        for i in range(info.GetNumberOfPlugins())]
loaded = ""
for name, path, _ in rows:
    if name == "CraterKit":  # what Load Selected in Tools > Manage Plugins does
        from paraview.simple import LoadPlugin
        LoadPlugin(path, remote=False)
        info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
        loaded = [info.GetPluginVersion(i) for i in range(info.GetNumberOfPlugins())
                  if info.GetPluginName(i) == "CraterKit" and info.GetPluginLoaded(i)]
with open({out!r}, "w") as f:
    for name, path, was_loaded in rows:
        f.write("%s|%s|%d|%s\\n" % (name, path, was_loaded, loaded if name == "CraterKit" else ""))
""")
    done = subprocess.run(["xvfb-run", "-a", "paraview", f"--script={gui}", "--exit"],
                          capture_output=True, text=True, env=env, cwd=tmp, timeout=300)
    rows = [line.split("|") for line in open(out).read().splitlines()] if os.path.isfile(out) else []
    mine = [r for r in rows if r[0] == "CraterKit"]
    print("GUI plugin list:", rows)
    check(len(mine) == 1, f"the GUI's plugin manager does not list CraterKit: {rows}\n{done.stderr[-2000:]}")
    if mine:
        check(mine[0][1].endswith("/paraview-5.11/plugins/CraterKit/CraterKit.so"), f"GUI: {mine[0][1]}")
        check(mine[0][2] == "0", "the GUI loaded CraterKit by itself (auto-load should be off)")
        check(mine[0][3] == str([version]), f"the GUI loaded CraterKit as version {mine[0][3]}")
else:
    print("no xvfb-run or paraview: the GUI was not checked")

if failures:
    print(f"installed package test: {len(failures)} failed; kept {tmp}")
    sys.exit(1)
shutil.rmtree(tmp)
print("installed package test: all passed")

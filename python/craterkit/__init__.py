"""CraterKit helpers for pvbatch and pvpython scripts.

    from craterkit import load_plugin
    simple = load_plugin()          # paraview.simple with the CraterKit proxies
    bed = simple.GranularBed(Packing='HCP')

Run scripts through scripts/pvbatch (installed: craterkit-pvbatch), which finds the plugin and
sets up headless rendering. `craterkit.__version__` is CraterKit's version.
"""

import glob
import json
import os
import re

__all__ = ["__version__", "load_plugin", "plugin_path", "fetch", "fetch_stage", "field_value",
           "impactor_depth", "print_progress"]

try:  # written into an installed package only (cmake --install, the Debian package)
    from . import _version as _installed
except ImportError:
    _installed = None

_HERE = os.path.dirname(os.path.abspath(__file__))
# The source tree this package is in (python/craterkit/ -> the root); None when installed.
SOURCE_ROOT = None if _installed else os.path.dirname(os.path.dirname(_HERE))


def _source_version():
    """The VERSION of project() in the source tree's top-level CMakeLists.txt, the one place
    the version is written; "unknown" if that file cannot be read."""
    try:
        with open(os.path.join(SOURCE_ROOT, "CMakeLists.txt")) as f:
            match = re.search(r"^\s*project\(\s*CraterKit\s+VERSION\s+([0-9][0-9.]*)", f.read(), re.M)
    except OSError:
        match = None
    return match.group(1) if match else "unknown"


__version__ = _installed.__version__ if _installed else _source_version()


def resource_path(name):
    """Where this package finds NAME: "materials" (the folder of *.cfg material files),
    "run-lammps" (the script that runs a LAMMPS deck) or "plugin" (CraterKit.so; None in the
    source tree, where scripts/pvbatch names the build's). Installed: relative to the package
    (its _version.py); in the source tree: data/materials and scripts/run-lammps."""
    if _installed:
        relative = {"materials": _installed.MATERIALS, "run-lammps": _installed.RUN_LAMMPS,
                    "plugin": _installed.PLUGIN}[name]
        return os.path.normpath(os.path.join(_HERE, relative))
    return {"materials": os.path.join(SOURCE_ROOT, "data", "materials"),
            "run-lammps": os.path.join(SOURCE_ROOT, "scripts", "run-lammps"),
            "plugin": None}[name]


def plugin_path():
    """Path of CraterKit.so: $CRATERKIT_PLUGIN, else the first match on $PV_PLUGIN_PATH, else
    (an installed package) the plugin installed with this package."""
    path = os.environ.get("CRATERKIT_PLUGIN")
    if path and os.path.isfile(path):
        return path
    for folder in os.environ.get("PV_PLUGIN_PATH", "").split(os.pathsep):
        hits = glob.glob(os.path.join(folder, "**", "CraterKit.so"), recursive=True) if folder else []
        if hits:
            return hits[0]
    path = resource_path("plugin")
    if path and os.path.isfile(path):
        return path
    raise RuntimeError(
        "CraterKit plugin not found: run the script through scripts/pvbatch (installed: "
        "craterkit-pvbatch), or set CRATERKIT_PLUGIN to the path of CraterKit.so")


def _paraview_version():
    """The running ParaView's "major.minor"."""
    from paraview import servermanager
    manager = servermanager.vtkSMProxyManager
    return f"{manager.GetVersionMajor()}.{manager.GetVersionMinor()}"


def _check_build(path):
    """Before loading the plugin at PATH: stops, naming both versions, when the ParaView
    running is not the one the plugin was built for, or when the plugin is another CraterKit
    version than this package (craterkit-build.json beside the plugin; none: no check)."""
    info_path = os.path.join(os.path.dirname(path), "craterkit-build.json")
    try:
        with open(info_path) as f:
            info = json.load(f)
    except (OSError, ValueError):
        return
    built, running = info.get("paraview_version"), _paraview_version()
    if built and built != running:
        raise SystemExit(
            f"error: the CraterKit plugin {path} was built for ParaView {built}, but this is "
            f"ParaView {running}: run it with ParaView {built}, or build CraterKit against "
            f"ParaView {running}")
    plugin_version = info.get("craterkit_version")
    if plugin_version and plugin_version != __version__:
        raise SystemExit(_version_mismatch(path, plugin_version))


def _version_mismatch(path, plugin_version):
    return (f"error: the CraterKit plugin {path} is version {plugin_version}, but the Python "
            f"package craterkit ({_HERE}) is version {__version__}: use the plugin and the "
            f"package of one build or one installation")


def _loaded_plugin():
    """(version, file) of the loaded CraterKit plugin as ParaView reports them, or None."""
    from paraview import servermanager
    info = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager().GetLocalInformation()
    for i in range(info.GetNumberOfPlugins()):
        if info.GetPluginName(i) == "CraterKit" and info.GetPluginLoaded(i):
            return info.GetPluginVersion(i), info.GetPluginFileName(i)
    return None


def plugin_version():
    """The version ParaView reports for the loaded CraterKit plugin (Tools > Manage Plugins
    shows the same), or None when it is not loaded."""
    loaded = _loaded_plugin()
    return loaded[0] if loaded else None


def load_plugin():
    """Loads the plugin once and returns paraview.simple with its proxies defined. Stops with a
    message naming both versions when the plugin was built for another ParaView or is another
    CraterKit version than this package."""
    from paraview import simple
    if not hasattr(simple, "GranularBed"):
        path = plugin_path()
        _check_build(path)
        simple.LoadPlugin(path, remote=False, ns=vars(simple))
    if not hasattr(simple, "GranularBed"):
        raise RuntimeError("CraterKit plugin loaded but defines no GranularBed source")
    loaded = _loaded_plugin()
    if loaded and loaded[0] != __version__:
        raise SystemExit(_version_mismatch(loaded[1], loaded[0]))
    return simple


def fetch(proxy, port=0):
    """The VTK data object of a proxy's output port, updated."""
    from paraview import servermanager
    proxy.UpdatePipeline()
    return servermanager.Fetch(proxy, idx=port)


def print_progress(proxy, label, every=0.1, out=None):
    """Prints `label: 40 % (85 s)` each time the progress a proxy's algorithm reports (what
    ParaView's progress bar shows) passes another `every`; returns the observer's tag. For
    long stages of a pvbatch script (an SPH stage or a bed settling for many minutes)."""
    import sys
    import time
    if not every > 0.0:
        raise ValueError(f"print_progress: every must be positive, not {every}")
    algorithm = proxy.GetClientSideObject()
    state = {"next": every, "start": None, "last": 0.0, "printed": None}
    stream = out or sys.stdout

    def observe(obj, _event):
        fraction = obj.GetProgress()
        if state["start"] is None or fraction < state["last"] - 0.25:  # a new update began
            state["start"], state["next"], state["printed"] = time.time(), every, None
        state["last"] = fraction
        if fraction >= state["next"] and fraction < 1.0:
            percent = f"{100.0 * fraction:.0f}"
            if percent != state["printed"]:
                print(f"      {label}: {percent} % ({time.time() - state['start']:.0f} s)", file=stream, flush=True)
                state["printed"] = percent
            while state["next"] <= fraction:
                state["next"] += every

    return algorithm.AddObserver("ProgressEvent", observe)


def fetch_stage(proxy, stage, time=None):
    """Updates one stage of a pipeline (at `time`, if given) and returns its data; a stage that
    produced no particles ends the script with a message naming it (VTK's error above says why)."""
    import sys
    if time is not None:
        proxy.UpdatePipeline(time)
    data = fetch(proxy)
    if data.GetNumberOfPoints() == 0:
        print(f"error: the {stage} failed; see the message above", file=sys.stderr)
        raise SystemExit(1)
    return data


def field_value(data, name, default=None):
    """First value of a field-data array (number or string), or default if absent."""
    fd = data.GetFieldData()
    array = fd.GetAbstractArray(name)
    if array is None or array.GetNumberOfTuples() == 0:
        return default
    if array.IsA("vtkStringArray"):
        return array.GetValue(0)
    if array.GetNumberOfComponents() > 1:
        return [array.GetComponent(0, k) for k in range(array.GetNumberOfComponents())]
    return array.GetTuple1(0)


def impactor_depth(data):
    """How deep below the surface (the SurfaceHeight field; 0 without it) an SPH state's
    impactor material (Material 0) is: {"centre_of_mass_m", "deepest_m", "speed_m_s" (its mean
    speed)}, all None when the state has no impactor particles. The crater forms around the
    impactor's track (benchmarks/README.md, "What sets the depth")."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pd = data.GetPointData()
    mine = vtk_to_numpy(pd.GetArray("Material")) == 0
    if not mine.any():
        return {"centre_of_mass_m": None, "deepest_m": None, "speed_m_s": None}
    z = vtk_to_numpy(data.GetPoints().GetData())[mine, 2] - field_value(data, "SurfaceHeight", 0.0)
    m = vtk_to_numpy(pd.GetArray("Mass"))[mine]
    v = vtk_to_numpy(pd.GetArray("Velocity"))[mine]
    return {"centre_of_mass_m": -float(np.average(z, weights=m)), "deepest_m": -float(z.min()),
            "speed_m_s": float(np.linalg.norm(v, axis=1).mean())}


def material_value(name, key, default=None):
    """A number from a material file (rho0, distention, ...) of the folder the SPH filter reads
    by default: $CRATERKIT_MATERIALS, else the installed materials or the source tree's
    data/materials. A missing file, or a missing key without a default, ends the script with a
    message naming it."""
    folder = os.environ.get("CRATERKIT_MATERIALS") or resource_path("materials")
    path = os.path.join(folder, name + ".cfg")
    if not os.path.isfile(path):
        raise SystemExit(f"error: no material file {path}")
    with open(path) as f:
        for line in f:
            k, _, value = line.split("#")[0].partition("=")
            if k.strip() == key:
                return float(value)
    if default is None:
        raise SystemExit(f"error: {path} has no {key}")
    return default


def property_settings(parser, items):
    """The `--set PROPERTY=VALUE` items of an example's command line as keyword arguments for
    a proxy: each value an int if it reads as one (BlockStepLevels=7), else a float, else the
    string (MaterialDirectory=...); a malformed item is refused through parser.error."""
    settings = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            parser.error(f"--set {item}: expected PROPERTY=VALUE")
        for kind in (int, float, str):
            try:
                settings[key] = kind(value)
                break
            except ValueError:
                continue
    return settings

"""CraterKit helpers for pvbatch and pvpython scripts.

    from craterkit import load_plugin
    simple = load_plugin()          # paraview.simple with the CraterKit proxies
    bed = simple.GranularBed(Packing='HCP')

Run scripts through scripts/pvbatch, which finds the plugin and sets up headless rendering.
"""

import glob
import os

__all__ = ["load_plugin", "plugin_path", "fetch", "fetch_stage", "field_value", "impactor_depth", "print_progress"]


def plugin_path():
    """Path of CraterKit.so: $CRATERKIT_PLUGIN, else the first match on $PV_PLUGIN_PATH."""
    path = os.environ.get("CRATERKIT_PLUGIN")
    if path and os.path.isfile(path):
        return path
    for folder in os.environ.get("PV_PLUGIN_PATH", "").split(os.pathsep):
        hits = glob.glob(os.path.join(folder, "**", "CraterKit.so"), recursive=True)
        if hits:
            return hits[0]
    raise RuntimeError(
        "CraterKit plugin not found: run the script through scripts/pvbatch, "
        "or set CRATERKIT_PLUGIN to the path of CraterKit.so")


def load_plugin():
    """Loads the plugin once and returns paraview.simple with its proxies defined."""
    from paraview import simple
    if not hasattr(simple, "GranularBed"):
        simple.LoadPlugin(plugin_path(), remote=False, ns=vars(simple))
    if not hasattr(simple, "GranularBed"):
        raise RuntimeError("CraterKit plugin loaded but defines no GranularBed source")
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
    """A number from a material file under data/materials (rho0, distention, ...); a missing
    file, or a missing key without a default, ends the script with a message naming it."""
    folder = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                          "data", "materials")
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

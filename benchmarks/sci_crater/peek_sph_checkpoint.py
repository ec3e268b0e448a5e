"""Measures the crater in an SPHImpact checkpoint (.cksph) while its run goes on: writes the
state (without the container's particles) as a VTP file and prints the crater's diameter, depth,
rim diameter and rim height (CraterProfile against the surface at z = 0) and how deep the
impactor's material (Material 0) is. For long runs such as the SCI impact at Ryugu's gravity,
whose SPH stage takes hours before it hands off.

    scripts/pvbatch benchmarks/sci_crater/peek_sph_checkpoint.py CHECKPOINT [OUT.vtp]

The checkpoint is read by the plugin's own reader (the one ParaView opens .cksph files with);
the container's particles (Material 2) are left out.
"""

import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from craterkit import fetch, field_value, load_plugin  # noqa: E402


def read_checkpoint(simple, path):
    """The checkpoint's particles as numpy arrays, with its time and step count."""
    if not os.path.isfile(path):
        sys.exit(f"{path}: no such file")
    try:
        data = fetch(simple.OpenDataFile(path))
    except RuntimeError as e:
        sys.exit(f"{path}: {e}")
    if data is None or data.GetNumberOfPoints() == 0:
        sys.exit(f"{path}: not a readable SPH checkpoint (see the message above)")
    pd = data.GetPointData()
    out = {"x": vtk_to_numpy(data.GetPoints().GetData())}
    for key, name in (("v", "Velocity"), ("mass", "Mass"), ("rho", "Density"), ("h", "SmoothingLength"),
                      ("distention", "Distention"), ("material", "Material")):
        a = pd.GetArray(name)
        if a is None:
            sys.exit(f"{path}: the checkpoint reader gave no {name} array")
        out[key] = vtk_to_numpy(a)
    out["time"] = field_value(data, "Time")
    out["step"] = int(field_value(data, "TimeStep"))  # the step count
    return out


def as_polydata(c, keep):
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(c["x"][keep]), deep=1))
    pd.SetPoints(pts)
    verts = vtkCellArray()
    for i in range(int(keep.sum())):
        verts.InsertNextCell(1)
        verts.InsertCellPoint(i)
    pd.SetVerts(verts)
    for name, key in (("Velocity", "v"), ("Mass", "mass"), ("Density", "rho"), ("SmoothingLength", "h"),
                      ("Distention", "distention"), ("Material", "material")):
        a = numpy_to_vtk(np.ascontiguousarray(c[key][keep]), deep=1)
        a.SetName(name)
        pd.GetPointData().AddArray(a)
    return pd


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    simple = load_plugin()
    c = read_checkpoint(simple, argv[0])
    out = argv[1] if len(argv) > 1 else os.path.splitext(argv[0])[0] + "_peek.vtp"
    keep = c["material"] != 2
    w = vtkXMLPolyDataWriter()
    w.SetFileName(out)
    w.SetInputData(as_polydata(c, keep))
    if not w.Write():
        sys.exit(f"{out}: cannot write")
    profile = simple.CraterProfile(Input=simple.XMLPolyDataReader(FileName=[out]), SurfaceFromInput=0,
                                   SurfaceHeight=0.0)
    profile.UpdatePipeline()
    fd = fetch(profile).GetFieldData()
    value = lambda name: fd.GetArray(name).GetValue(0) if fd.GetArray(name) else float("nan")  # noqa: E731
    imp = c["material"] == 0
    depth = -float(np.average(c["x"][imp, 2], weights=c["mass"][imp])) if imp.any() else float("nan")
    speed = float(np.linalg.norm(c["v"][imp], axis=1).mean()) if imp.any() else float("nan")
    print(f"t = {c['time']:.6g} s, step {c['step']}, {int(keep.sum())} particles "
          f"(written to {out})")
    print(f"crater diameter {value('CraterDiameter'):.4g} m, depth {value('CraterDepth'):.4g} m, rim diameter "
          f"{value('RimDiameter'):.4g} m, rim height {value('RimHeight'):.4g} m; impactor's centre of mass "
          f"{depth:.4g} m deep, moving at {speed:.3g} m/s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

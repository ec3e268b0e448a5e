"""FragmentAnalysis through ParaView on hand-built particles read from a LAMMPS dump: ten
touching spheres in a row and five separate ones flying along +z: six fragments, F = 6/15,
the fragment table, the FragmentId array, the cloud's length, extent and front speed, and the
ejecta statistics."""

import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_fragment_analysis")

rows = [(0.2 * i, 0.0, 0.0, 0.0) for i in range(10)]           # a touching row (r = 0.1)
rows += [(0.0, 0.5 * k, 2.0 + k, 3.0 + k) for k in range(5)]     # separate, flying up at 3..7 m/s
path = os.path.join(tempfile.mkdtemp(), "frag.dump")
with open(path, "w") as f:
    f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(rows)}\nITEM: BOX BOUNDS ff ff ff\n-1 3\n-1 3\n-1 7\n")
    f.write("ITEM: ATOMS id type x y z vx vy vz radius mass\n")
    for k, (x, y, z, vz) in enumerate(rows):
        f.write(f"{k + 1} 1 {x} {y} {z} 0 0 {vz} 0.1 1.0\n")

frag = simple.FragmentAnalysis(Input=simple.OpenDataFile(path), CloudAxis=[0, 0, 1], CloudStart=1.0)
out = fetch(frag, port=0)
table = fetch(frag, port=1)
ids = vtk_to_numpy(out.GetPointData().GetArray("FragmentId"))
t.check(field_value(out, "FragmentCount") == 6, f"fragment count {field_value(out, 'FragmentCount')}")
t.check(abs(field_value(out, "Fragmentation") - 0.4) < 1e-12, "fragmentation is not 6/15")
t.check(table.GetNumberOfRows() == 6 and table.GetColumnByName("Mass").GetValue(0) == 10.0,
        "fragment table wrong (heaviest first, mass 10)")
row_ids = {int(ids[i]) for i in range(out.GetNumberOfPoints()) if out.GetPoint(i)[2] == 0.0}
t.check(row_ids == {0}, f"the row is not fragment 0: {row_ids}")
t.check(field_value(out, "CloudParticles") == 5 and abs(field_value(out, "CloudAxialLength") - 4.0) < 1e-9,
        "cloud particles or axial length wrong")
t.check(abs(field_value(out, "CloudRadialExtent") - 4.0) < 1e-9 and abs(field_value(out, "CloudFrontSpeed") - 7.0) < 1e-9,
        "cloud radial extent or front speed wrong")
ejecta = fetch(frag, port=2)
t.check(field_value(out, "EjectaCount") == 5 and abs(field_value(out, "MeanEjectionAngle") - 90.0) < 1e-9,
        "the five rising particles are not the ejecta, or their angle is not 90 degrees")
t.check(ejecta.GetNumberOfRows() == 5 and ejecta.GetColumnByName("MassAbove").GetValue(4) == 5.0,
        "ejecta table wrong")
with captured_vtk_messages() as log:
    bad = fetch(simple.FragmentAnalysis(Input=simple.Sphere()))
t.check(bad.GetNumberOfPoints() == 0 and "Radius" in log["text"], f"missing arrays not reported: {log['text'][:300]!r}")
sys.exit(t.close())

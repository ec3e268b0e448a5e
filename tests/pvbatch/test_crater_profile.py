"""CraterProfile through ParaView on a synthetic crater of particles (a paraboloid bowl of
radius 2 m and depth 0.6 m in a bed of 5 cm spheres, written as a LAMMPS dump and read back):
the measured diameter and depth within one particle diameter, the profile table, the
section slab, and errors for input without sizes."""

import math
import os
import sys
import tempfile

import numpy as np

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_crater_profile")

rp, Rc, depth = 0.05, 2.0, 0.6
g = np.arange(-4.0 + rp, 4.0, 2 * rp)
X, Y = np.meshgrid(g, g, indexing="ij")
R = np.hypot(X, Y)
top = np.where(R < Rc, -depth * (1 - (R / Rc) ** 2), 0.0)
rows = []
for (i, j), tz in np.ndenumerate(top):
    if R[i, j] > 4.0:
        continue
    for z in np.arange(-1.0 + rp, tz - rp + 1e-9, 2 * rp):
        rows.append((X[i, j], Y[i, j], z))
pts = np.array(rows)
path = os.path.join(tempfile.mkdtemp(), "crater.dump")
with open(path, "w") as f:
    f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(pts)}\nITEM: BOX BOUNDS ff ff ff\n-4 4\n-4 4\n-1 1\n")
    f.write("ITEM: ATOMS id type x y z radius mass\n")
    for k, (x, y, z) in enumerate(pts):
        f.write(f"{k + 1} 1 {x:.6f} {y:.6f} {z:.6f} {rp} 1.0\n")

reader = simple.OpenDataFile(path)
prof = simple.CraterProfile(Input=reader, SurfaceFromInput=0, SurfaceHeight=0.0, MaxRadius=3.8)
table = fetch(prof, port=0)
section = fetch(prof, port=1)
d = field_value(table, "CraterDiameter")
h = field_value(table, "CraterDepth")
t.check(d is not None and abs(d - 2 * Rc) < 2 * rp, f"diameter {d} (expected {2 * Rc} within {2 * rp})")
t.check(h is not None and abs(h - depth) < 2 * rp, f"depth {h} (expected {depth})")
t.check(table.GetNumberOfRows() > 5 and table.GetColumnByName("Height") is not None, "no profile table")
t.check(0 < section.GetNumberOfPoints() < len(pts) and section.GetPointData().GetArray("Radius") is not None,
        "section slab missing or without arrays")
ys = [section.GetPoint(i)[1] for i in range(section.GetNumberOfPoints())]
t.check(max(abs(y) for y in ys) <= 4 * rp + 1e-9, "section slab wider than two diameters")
t.check(field_value(section, "CraterDiameter") == d, "summary missing on the section output")

# The cross-section picture with the measured lines (headless).
from craterkit.cross_section import crater_measures, render_cross_section  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy as v2n  # noqa: E402
measures = crater_measures(prof)
t.check(abs(measures["diameter"] - d) < 1e-12 and measures["found"], "crater_measures does not read the summary")
png = os.path.join(tempfile.mkdtemp(), "section.png")
render_cross_section(reader, png, resolution=(480, 270), measures=measures, label="synthetic crater")
image = vtkPNGReader()
image.SetFileName(png)
image.Update()
pixels = v2n(image.GetOutput().GetPointData().GetScalars()).astype(int)
red = ((pixels[:, 0] > 180) & (pixels[:, 1] < 80) & (pixels[:, 2] < 80)).sum()
blue = ((pixels[:, 2] > 180) & (pixels[:, 0] < 80) & (pixels[:, 1] < 120)).sum()
green = ((pixels[:, 1] > 120) & (pixels[:, 0] < 80) & (pixels[:, 2] < 100)).sum()
# This crater has no raised rim: the rim line (blue) lies on the diameter line (red).
t.check(red + blue > 50 and green > 20, f"measured lines not drawn ({red} red, {blue} blue, {green} green pixels)")

with captured_vtk_messages() as log:
    bad = fetch(simple.CraterProfile(Input=simple.Sphere()), port=0)
t.check(bad.GetNumberOfRows() == 0 and "Radius" in log["text"], f"missing sizes not reported: {log['text'][:300]!r}")
sys.exit(t.close())

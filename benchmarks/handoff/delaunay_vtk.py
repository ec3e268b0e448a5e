"""vtkDelaunay3D with the same alpha on the same lattice as ck_handoff_bench's compact set
(run with scripts/pvbatch): prints its time.   delaunay_vtk.py N_SPH ALPHA_RADIUS"""
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkDelaunay3D

n_sph, alpha = float(sys.argv[1]), float(sys.argv[2])
R = 1.0
dx = (2.0 / 3.0 * np.pi * R ** 3 / n_sph) ** (1.0 / 3.0)
n = int(R / dx) + 1
i, j, k = np.meshgrid(np.arange(-n, n), np.arange(-n, n), np.arange(0, n), indexing="ij")
x = np.stack([(i + 0.5) * dx, (j + 0.5) * dx, -(k + 0.5) * dx], axis=-1).reshape(-1, 3)
r = np.linalg.norm(x, axis=1)
x = x[r <= R]
r = np.linalg.norm(x, axis=1)
speed = (0.25 / r) ** 3 * np.sqrt(1.0 + ((1.0 - x[:, 2] ** 2 / r ** 2) ** 0.5 / (1.0 - x[:, 2] / r)) ** 2)
x = x[speed <= 1.0]  # the compact set (Z = 3, 1 m/s limit)
points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
poly = vtkPolyData()
poly.SetPoints(points)
d = vtkDelaunay3D()
d.SetInputData(poly)
d.SetAlpha(alpha)
d.AlphaTetsOn()
d.AlphaTrisOff()
d.AlphaLinesOff()
d.AlphaVertsOff()
start = time.time()
d.Update()
took = time.time() - start
print(f"vtkDelaunay3D: {len(x)} points, alpha {alpha:.4g} m: {took:.2f} s, {d.GetOutput().GetNumberOfCells()} tetrahedra",
      flush=True)

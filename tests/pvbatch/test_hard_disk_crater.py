"""HardDiskCrater through ParaView: advertised frame times, three outputs, energy and
momentum of an elastic run, the deterministic restart for an earlier frame, presets, and
clear errors for bad input."""

import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_hard_disk_crater")

small = dict(Width=0.4, GroundDepth=0.2, Headroom=0.15, DiskRadius=0.005, AreaFraction=0.7,
             ImpactorRadius=0.02, ImpactSpeed=10.0, FrameInterval=0.002, EndTime=0.02,
             TracerFraction=0.1)
src = simple.HardDiskCrater(**small)
times = list(src.TimestepValues)
t.check(len(times) == 11 and abs(times[-1] - 0.02) < 1e-12, f"advertised times {times}")


def state(time, port=0):
    src.UpdatePipeline(time)
    return fetch(src, port)


d0 = state(0.0)
n = d0.GetNumberOfPoints()
material = vtk_to_numpy(d0.GetPointData().GetArray("Material"))
t.check(n > 500 and (material == 1).sum() == 1, f"{n} disks, impactor count {(material == 1).sum()}")
z = vtk_to_numpy(d0.GetPoints().GetData())[:, 2]
t.check(z[material == 0].max() <= 0.2 + 1e-12, "ground above its depth")
e0 = field_value(d0, "KineticEnergy")
t.check(abs(e0 - 0.5 * fetch(src).GetPointData().GetArray("Mass").GetRange()[1] * 100.0) < 1e-9 * e0,
        "initial energy is not the impactor's")
p0 = np.array(d0.GetFieldData().GetArray("TotalMomentum").GetTuple3(0))

d1 = state(0.01)
t.check(abs(field_value(d1, "Time") - 0.01) < 1e-15, "frame time")
t.check(field_value(d1, "PairCollisions") > 100, "no collisions")
e1 = field_value(d1, "KineticEnergy")
t.check(abs(e1 - e0) < 1e-9 * e0, f"elastic run lost energy: {e0} -> {e1}")
t.check(field_value(d1, "ShockFrontRadius") > 0.03, "the disturbance did not spread")
x1 = vtk_to_numpy(d1.GetPoints().GetData()).copy()
paths = state(0.01, 1)
t.check(paths.GetNumberOfCells() > 10, "no tracer paths")
t.check(paths.GetCell(0).GetNumberOfPoints() == 6, "tracer path should hold frames 0..5")
outline = state(0.01, 2)
t.check(outline.GetNumberOfPoints() == 20, f"outline bins {outline.GetNumberOfPoints()}")
t.check(field_value(d1, "CraterDepth") > 0.0, "no crater depth")

state(0.02)
x1b = vtk_to_numpy(state(0.01).GetPoints().GetData())  # earlier frame: deterministic restart
t.check(np.array_equal(x1, x1b), "restarting for an earlier frame gave a different state")

for k, name in enumerate(["Ball pit", "Dense sand", "Clump impactor"], start=1):
    preset = simple.HardDiskCrater(Preset=k, FrameInterval=0.001, EndTime=0.001)
    preset.UpdatePipeline(0.0)
    out = fetch(preset)
    mats = vtk_to_numpy(out.GetPointData().GetArray("Material"))
    t.check(out.GetNumberOfPoints() > 1000, f"preset {name} made {out.GetNumberOfPoints()} disks")
    if name == "Clump impactor":
        t.check((mats == 1).sum() > 10, "the clump has too few disks")

with captured_vtk_messages() as log:
    bad = simple.HardDiskCrater(AreaFraction=0.9)
    out = fetch(bad)
t.check(out.GetNumberOfPoints() == 0 and "jamming" in log["text"], f"bad AreaFraction: {log['text']!r}")
with captured_vtk_messages() as log:
    bad = simple.HardDiskCrater(FrameInterval=0.0)
    out = fetch(bad)
t.check(out.GetNumberOfPoints() == 0 and "FrameInterval" in log["text"], f"zero frame interval: {log['text']!r}")

sys.exit(t.close())

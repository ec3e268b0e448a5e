"""DEMIntegrator through ParaView: the time protocol (advertised times, forward, backward,
restart from input or from kept snapshots gives identical states), the impactor, checkpoint
and resume, and clear errors for bad input."""

import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_dem_integrator")


def positions(proxy, time):
    proxy.UpdatePipeline(time)
    data = fetch(proxy)
    return vtk_to_numpy(data.GetPoints().GetData()).copy(), data


bed = simple.GranularBed(Packing="HCP", Container="Box", BoxSize=[2.0, 2.0, 1.0],
                         ParticleRadius=0.1, SurfaceHeight=0.0)
common = dict(Input=bed, SurfaceGravity=[0.0, 0.0, -9.81], EndTime=0.3, OutputInterval=0.1,
              StaticFriction=0.5, MaxExpectedSpeed=2.0)
dem = simple.DEMIntegrator(AddImpactor=1, ImpactorRadius=0.15, ImpactSpeed=2.0, ImpactorDensity=4000.0,
                           **common)
times = list(dem.TimestepValues)
t.check(len(times) == 4 and abs(times[-1] - 0.3) < 1e-12, f"advertised times {times}")

x0, d0 = positions(dem, 0.0)
n_bed = fetch(bed).GetNumberOfPoints()
t.check(d0.GetNumberOfPoints() == n_bed + 1, "the impactor was not added")
material = vtk_to_numpy(d0.GetPointData().GetArray("Material"))
velocity = vtk_to_numpy(d0.GetPointData().GetArray("Velocity"))
ids = vtk_to_numpy(d0.GetPointData().GetArray("Id"))
bed_ids = vtk_to_numpy(fetch(bed).GetPointData().GetArray("Id"))
# The DEM orders particles along a space-filling curve; identity is carried by Id.
t.check(sorted(ids.tolist()) == sorted(bed_ids.tolist() + [bed_ids.max() + 1]), "ids not preserved")
imp = np.flatnonzero(material == 1)
t.check(len(imp) == 1, "expected exactly one impactor (Material 1)")
t.check(abs(velocity[imp[0]][2] + 2.0) < 1e-12, "impactor velocity")
t.check(x0[imp[0]][2] > 0.15, "impactor not above the surface")

xa, da = positions(dem, 0.2)
t.check(abs(field_value(da, "Time") - 0.2) < 2 * field_value(da, "TimeStep"), "time 0.2 not reached")
t.check(np.abs(xa - x0).max() > 0.01, "nothing moved")
t.check(field_value(da, "Contacts") > 10, "no contacts")
xb, _ = positions(dem, 0.3)
xc, _ = positions(dem, 0.2)  # backwards: from the kept snapshot at 0.2
t.check(np.array_equal(xa, xc), "going back to 0.2 gave a different state")
xd, _ = positions(dem, 0.1)  # backwards past the snapshots: restart from the input
xe, _ = positions(dem, 0.2)
t.check(np.array_equal(xa, xe), "restarting from the input gave a different state at 0.2")

# Checkpoint every few steps, then resume in a new filter from the file.
folder = tempfile.mkdtemp()
path = os.path.join(folder, "run.ckdem")
writer = simple.DEMIntegrator(AddImpactor=1, ImpactorRadius=0.15, ImpactSpeed=2.0,
                              ImpactorDensity=4000.0, CheckpointFile=path, CheckpointInterval=50,
                              **common)
xw, dw = positions(writer, 0.2)
t.check(os.path.isfile(path), "no checkpoint written")
t.check(np.array_equal(xw, xa), "checkpointing changed the run")
steps_w = field_value(dw, "Step")
resumed = simple.DEMIntegrator(AddImpactor=1, ImpactorRadius=0.15, ImpactSpeed=2.0,
                               ImpactorDensity=4000.0, CheckpointFile=path, ResumeFromCheckpoint=1,
                               CheckpointInterval=10**9, **common)
xr, dr = positions(resumed, 0.3)
t.check(np.array_equal(xr, xb), "the run resumed from its checkpoint differs at 0.3")

# Bad input gives an error naming the problem.
with captured_vtk_messages() as log:
    plain = simple.Sphere()
    bad = simple.DEMIntegrator(Input=simple.ExtractSurface(Input=plain))
    out = fetch(bad)
t.check(out.GetNumberOfPoints() == 0 and "Radius" in log["text"],
        f"missing Radius array not reported: {log['text'][:200]!r}")
with captured_vtk_messages() as log:
    bad = simple.DEMIntegrator(Input=bed, TimeStep=1.0, NormalStiffness=1e6)
    out = fetch(bad)
t.check(out.GetNumberOfPoints() == 0 and "stability" in log["text"],
        f"unstable time step not reported: {log['text'][:200]!r}")
with captured_vtk_messages() as log:
    bad = simple.DEMIntegrator(Input=bed, NormalRestitution=1.5)
    out = fetch(bad)
t.check(out.GetNumberOfPoints() == 0 and "NormalRestitution" in log["text"],
        f"bad restitution not reported: {log['text'][:200]!r}")
sys.exit(t.close())

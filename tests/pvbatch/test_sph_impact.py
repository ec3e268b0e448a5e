"""SPHImpact through ParaView: the SCI-like source at a small size, its output arrays and
time protocol (forward, backward from a kept snapshot gives the same state), conservation
read from field data, checkpoint and resume, and clear errors for bad input."""

import io
import os
import re
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin, print_progress
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_sph_impact")

small = dict(ParticlesAcrossImpactor=3, TargetRadius=0.15, EndTime=4e-5, OutputInterval=2e-5)
sph = simple.SPHImpact(**small)
times = list(sph.TimestepValues)
t.check(len(times) == 3 and abs(times[-1] - 4e-5) < 1e-15, f"advertised times {times}")


def state(proxy, time):
    proxy.UpdatePipeline(time)
    data = fetch(proxy)
    return data, vtk_to_numpy(data.GetPoints().GetData()).copy()


d0, x0 = state(sph, 0.0)
n = d0.GetNumberOfPoints()
pd = d0.GetPointData()
for name, comps in [("Velocity", 3), ("Density", 1), ("Mass", 1), ("Pressure", 1), ("InternalEnergy", 1),
                    ("Distention", 1), ("Damage", 1), ("DeviatoricStress", 6), ("SmoothingLength", 1),
                    ("Material", 1), ("Id", 1)]:
    array = pd.GetArray(name)
    t.check(array is not None and array.GetNumberOfComponents() == comps and array.GetNumberOfTuples() == n,
            f"array {name} missing or wrong shape")
material = vtk_to_numpy(pd.GetArray("Material"))
mass = vtk_to_numpy(pd.GetArray("Mass"))
velocity = vtk_to_numpy(pd.GetArray("Velocity"))
t.check(abs(mass[material == 0].sum() - 2.0) < 1e-12, "impactor mass is not the default 2 kg")
t.check(np.allclose(velocity[material == 0], [0.0, 0.0, -2000.0]), "impactor not moving down at 2 km/s")
density = vtk_to_numpy(pd.GetArray("Density"))
t.check(np.allclose(density[material == 1], 1190.0, rtol=1e-3), "target bulk density is not 1190 kg/m3")
t.check(np.allclose(vtk_to_numpy(pd.GetArray("Distention"))[material == 1], 2700.0 / 1190.0, rtol=1e-3),
        "target distention is not 2700/1190")
p0 = fetch(sph).GetFieldData().GetArray("TotalMomentum").GetTuple3(0)
E0 = field_value(d0, "TotalEnergy")

d1, x1 = state(sph, 2e-5)
t.check(abs(field_value(d1, "Time") - 2e-5) < 1e-15, "time 2e-5 not reached exactly")
t.check(np.abs(x1 - x0).max() > 1e-3, "nothing moved")
d2, x2 = state(sph, 4e-5)
p2 = d2.GetFieldData().GetArray("TotalMomentum").GetTuple3(0)
mtot = mass.sum()
expected_pz = p0[2] - mtot * 1.5e-4 * 4e-5
t.check(abs(p2[2] - expected_pz) < 1e-10 * 4000.0 and abs(p2[0]) < 1e-10 * 4000.0,
        f"momentum not conserved: {p2} vs {expected_pz}")
E2 = field_value(d2, "TotalEnergy")
t.check(abs(E2 - E0) < 0.01 * E0, f"energy changed by {(E2 - E0) / E0:.3e}")
pressure = vtk_to_numpy(d2.GetPointData().GetArray("Pressure"))
t.check(pressure.max() > 1e8, f"no shock: largest pressure {pressure.max():.3g} Pa")
_, x1b = state(sph, 2e-5)  # backwards: from the kept snapshot
t.check(np.array_equal(x1, x1b), "going back to 2e-5 gave a different state")

folder = tempfile.mkdtemp()
path = os.path.join(folder, "run.cksph")
writer = simple.SPHImpact(CheckpointFile=path, CheckpointInterval=5, **small)
_, xw = state(writer, 2e-5)
t.check(os.path.isfile(path), "no checkpoint written")
t.check(np.array_equal(xw, x1), "checkpointing changed the run")
# The checkpoint opens in ParaView like any particle file.
ck = fetch(simple.OpenDataFile(path))
ckx = vtk_to_numpy(ck.GetPoints().GetData())
t.check(np.array_equal(ckx, xw) and abs(field_value(ck, "Time") - 2e-5) < 1e-15,
        "the SPH checkpoint read back differs from the state it holds")
t.check(all(ck.GetPointData().GetArray(a) is not None for a in ("Velocity", "Mass", "Distention", "DeviatoricStress")),
        "the SPH checkpoint reader lacks arrays")
resumed = simple.SPHImpact(CheckpointFile=path, ResumeFromCheckpoint=1, **small)
_, xr = state(resumed, 4e-5)
t.check(np.abs(xr - x2).max() < 1e-9, f"the resumed run differs by {np.abs(xr - x2).max():.3g} m")

# Progress as a script sees it: rising percentages, one line per tenth, while the run goes.
printed = io.StringIO()
watched = simple.SPHImpact(**small)
print_progress(watched, "SPH", out=printed)
watched.UpdatePipeline(4e-5)
percents = [int(m) for m in re.findall(r"SPH: (\d+) %", printed.getvalue())]
t.check(len(percents) >= 5 and all(b // 10 > a // 10 for a, b in zip(percents, percents[1:])),
        f"progress lines not one per tenth, rising: {printed.getvalue()!r}")

with captured_vtk_messages() as log:
    out = fetch(simple.SPHImpact(ImpactorMaterial="unobtainium", **small))
t.check(out.GetNumberOfPoints() == 0 and "unobtainium" in log["text"] and "copper" in log["text"],
        f"unknown material not reported: {log['text'][:300]!r}")
with captured_vtk_messages() as log:
    out = fetch(simple.SPHImpact(ImpactAngle=95.0, **small))
t.check(out.GetNumberOfPoints() == 0 and "ImpactAngle" in log["text"],
        f"bad angle not reported: {log['text'][:300]!r}")
with captured_vtk_messages() as log:
    out = fetch(simple.SPHImpact(ParticlesAcrossImpactor=500, TargetRadius=0.15))
t.check(out.GetNumberOfPoints() == 0 and "memory" in log["text"],
        f"oversized resolution not reported: {log['text'][:300]!r}")
sys.exit(t.close())

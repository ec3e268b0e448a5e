"""BondedImpact through ParaView: the Watson & Steinhauser 2017 source at a small size, its
output arrays, momentum conserved (from the arrays), energies and debris-cloud measures in field
data, the time protocol (an earlier time gives the state it gave the first time), checkpoint and
resume, and bad properties refused with an error naming them."""

import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_bonded_impact")

small = dict(ParticleCount=1500, PlateWidthRatio=2.5, EndTime=3e-6, OutputInterval=1e-6)
source = simple.BondedImpact(**small)
times = list(source.TimestepValues)
t.check(len(times) == 4 and abs(times[-1] - 3e-6) < 1e-18, f"advertised times {times}")


def state(proxy, time):
    proxy.UpdatePipeline(time)
    data = fetch(proxy)
    pd = data.GetPointData()
    x = vtk_to_numpy(data.GetPoints().GetData()).copy()
    v = vtk_to_numpy(pd.GetArray("Velocity")).copy()
    return data, x, v


d0, x0, v0 = state(source, 0.0)
n = d0.GetNumberOfPoints()
pd = d0.GetPointData()
for name, comps in [("Velocity", 3), ("Radius", 1), ("Mass", 1), ("Density", 1), ("Material", 1),
                    ("Id", 1), ("BondCount", 1), ("FragmentId", 1)]:
    array = pd.GetArray(name)
    t.check(array is not None and array.GetNumberOfComponents() == comps
            and array.GetNumberOfTuples() == n, f"array {name} missing or wrong shape")
mass = vtk_to_numpy(pd.GetArray("Mass"))
material = vtk_to_numpy(pd.GetArray("Material"))
bonds = vtk_to_numpy(pd.GetArray("BondCount"))
sphere = np.pi / 6 * 9.53e-3 ** 3 * 2700.0
t.check(abs(mass[material == 0].sum() - sphere) < 1e-9 * sphere,
        f"projectile mass {mass[material == 0].sum():.6g} kg, not the 9.53 mm Al sphere's")
t.check(abs(v0[material == 0, 0].mean() - 6700.0) < 1e-6, "projectile not flying at 6.7 km/s")
t.check(bonds.max() == 6 and field_value(d0, "BrokenBonds") == 0, "lattice bonds not formed")
p_start = (mass[:, None] * v0).sum(axis=0)
E_start = field_value(d0, "TotalEnergy")

_, x1, v1 = state(source, 1e-6)
d3, x3, v3 = state(source, 3e-6)
t.check(abs(field_value(d3, "Time") - 3e-6) < field_value(d3, "TimeStep"), "3 us not reached")
p_end = (vtk_to_numpy(d3.GetPointData().GetArray("Mass"))[:, None] * v3).sum(axis=0)
scale = np.abs(p_start).max()
t.check(np.abs(p_end - p_start).max() < 1e-10 * scale,
        f"momentum not conserved: {p_start} -> {p_end}")
for name in ("KineticEnergy", "RepulsiveEnergy", "BondEnergy", "DissipatedEnergy",
             "Fragmentation", "DebrisCloudAxialLength", "DebrisCloudRadialExtent",
             "DebrisCloudRatio", "AxialVelocityRatio", "Step", "BrokenBonds"):
    t.check(d3.GetFieldData().GetArray(name) is not None, f"field {name} missing")
parts = sum(field_value(d3, k) for k in ("KineticEnergy", "RepulsiveEnergy", "BondEnergy",
                                         "DissipatedEnergy"))
E_end = field_value(d3, "TotalEnergy")
t.check(abs(parts - E_end) < 1e-12 * E_end, "TotalEnergy is not the sum of its parts")
t.check(abs(E_end - E_start) < 1e-3 * E_start, f"energy changed by {(E_end - E_start) / E_start:.3e}")
t.check(field_value(d3, "BrokenBonds") > 0 and field_value(d3, "RepulsiveEnergy") > 0,
        "no impact: no broken bonds or no repulsion at 3 us")
print(f"{n} particles, {int(field_value(d3, 'Step'))} steps, broken bonds "
      f"{int(field_value(d3, 'BrokenBonds'))}, F {field_value(d3, 'Fragmentation'):.3f}, "
      f"energy error {(E_end - E_start) / E_start:.2e}", flush=True)

_, x1b, v1b = state(source, 1e-6)  # backwards: from the kept snapshot
t.check(np.array_equal(x1, x1b) and np.array_equal(v1, v1b),
        "going back to 1 us gave a different state")
_, x0b, _ = state(source, 0.0)
t.check(np.array_equal(x0, x0b), "going back to 0 gave a different state")

folder = tempfile.mkdtemp()
path = os.path.join(folder, "run.ckbonded")
writer = simple.BondedImpact(CheckpointFile=path, CheckpointInterval=50, **small)
_, xw, _ = state(writer, 1e-6)
t.check(os.path.isfile(path), "no checkpoint written")
t.check(np.array_equal(xw, x1), "checkpointing changed the run")
resumed = simple.BondedImpact(CheckpointFile=path, ResumeFromCheckpoint=1, **small)
_, xr, vr = state(resumed, 3e-6)
t.check(np.array_equal(xr, x3) and np.array_equal(vr, v3), "the resumed run is not bit-identical")


def refused(prop, value):
    with captured_vtk_messages() as log:
        out = fetch(simple.BondedImpact(**dict(small, **{prop: value})))
    t.check(out.GetNumberOfPoints() == 0 and prop in log["text"],
            f"bad {prop} = {value} not reported by name: {log['text'][:300]!r}")


refused("ThicknessRatio", 0.0)
refused("ImpactSpeed", -1.0)
refused("CutoffRatio", 1.0)
refused("EndTime", -1.0)
refused("ParticleCount", 1e13)
sys.exit(t.close())

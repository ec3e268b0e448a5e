"""GranularBed through ParaView: arrays and field data of the data model, geometry checked
against brute-force oracles, bad input reported as an error with an empty output."""

import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_granular_bed")

for packing, container in (("RCP", "Bowl"), ("HCP", "Box"), ("RCP", "Box"), ("HCP", "Bowl")):
    bed = simple.GranularBed(Packing=packing, Container=container, ContainerRadius=4.0,
                             BoxSize=[5.0, 4.0, 3.0], SurfaceHeight=-0.2, ParticleRadius=0.4,
                             ParticleDensity=1800.0, RandomSeed=3)
    data = fetch(bed)
    tag = f"{packing}/{container}"
    n = data.GetNumberOfPoints()
    t.check(n > 20, f"{tag}: only {n} particles")
    t.check(data.GetNumberOfVerts() == n, f"{tag}: one vertex cell per particle")
    pd = data.GetPointData()
    for name, comps, cls in (("Velocity", 3, "vtkDoubleArray"), ("AngularVelocity", 3, "vtkDoubleArray"),
                             ("Radius", 1, "vtkDoubleArray"), ("Mass", 1, "vtkDoubleArray"),
                             ("Density", 1, "vtkDoubleArray"), ("Material", 1, "vtkIntArray"),
                             ("Id", 1, "vtkTypeInt64Array")):
        a = pd.GetArray(name)
        t.check(a is not None and a.GetNumberOfComponents() == comps and a.IsA(cls),
                f"{tag}: array {name} missing or not {cls} with {comps} components")
    x = vtk_to_numpy(data.GetPoints().GetData())
    r = vtk_to_numpy(pd.GetArray("Radius"))
    m = vtk_to_numpy(pd.GetArray("Mass"))
    ids = vtk_to_numpy(pd.GetArray("Id"))
    t.check(len(set(ids.tolist())) == n, f"{tag}: ids not unique")
    t.check(np.allclose(m, 1800.0 * 4.0 / 3.0 * np.pi * r ** 3), f"{tag}: mass != density x volume")
    # Brute-force overlap oracle.
    d = np.sqrt(((x[:, None, :] - x[None, :, :]) ** 2).sum(-1)) + np.eye(n) * 1e9
    worst = ((r[:, None] + r[None, :]) - d).max() / r.min()
    t.check(worst <= 1e-9, f"{tag}: particles overlap by {worst:.3g} radii")
    # Containment.
    tol = 1e-9
    t.check((x[:, 2] + r <= -0.2 + tol).all(), f"{tag}: a particle is above the surface")
    if container == "Bowl":
        t.check((np.linalg.norm(x, axis=1) + r <= 4.0 + tol).all(), f"{tag}: outside the bowl")
    else:
        t.check((np.abs(x[:, 0]) + r <= 2.5 + tol).all() and (np.abs(x[:, 1]) + r <= 2.0 + tol).all()
                and (x[:, 2] - r >= -3.0 - tol).all(), f"{tag}: outside the box")
    t.check(field_value(data, "Packing") == packing, f"{tag}: field Packing")
    t.check(field_value(data, "ContainerType") == container, f"{tag}: field ContainerType")
    t.check(field_value(data, "NumberOfParticles") == n, f"{tag}: field NumberOfParticles")
    t.check(abs(field_value(data, "SurfaceHeight") + 0.2) < 1e-12, f"{tag}: field SurfaceHeight")
    simple.Delete(bed)

# The bed is reproducible from its seed and changes with it.
a = vtk_to_numpy(fetch(simple.GranularBed(ContainerRadius=4.0, RandomSeed=5)).GetPoints().GetData()).copy()
b = vtk_to_numpy(fetch(simple.GranularBed(ContainerRadius=4.0, RandomSeed=5)).GetPoints().GetData()).copy()
c = vtk_to_numpy(fetch(simple.GranularBed(ContainerRadius=4.0, RandomSeed=6)).GetPoints().GetData()).copy()
t.check(np.array_equal(a, b), "same seed gave different beds")
t.check(a.shape != c.shape or not np.array_equal(a, c), "different seeds gave the same bed")

# Bad input: a clear error naming the problem, and an empty output, never a crash.
bad_inputs = [
    (dict(ParticleRadius=-1.0), "ParticleRadius"),
    (dict(ParticleRadius=float("nan")), "ParticleRadius"),
    (dict(SizeDistribution="Uniform", MinRadius=0.5, MaxRadius=0.2), "MaxRadius"),
    (dict(ContainerRadius=0.3), "bowl"),
    (dict(Container="Box", BoxSize=[0.5, 5.0, 5.0]), "box"),
    (dict(ParticleRadius=0.05, MaxParticles=1000), "MaxParticles"),
    (dict(Packing="HCP", SizeDistribution="PowerLaw"), "Monodisperse"),
    (dict(PackingFraction=0.9), "PackingFraction"),
]
for props, word in bad_inputs:
    with captured_vtk_messages() as log:
        bed = simple.GranularBed(**props)
        data = fetch(bed)
    t.check(data.GetNumberOfPoints() == 0, f"{props}: output not empty after an error")
    t.check("invalid input" in log["text"] and word in log["text"],
            f"{props}: error text does not name '{word}': {log['text'][:200]!r}")
    simple.Delete(bed)

sys.exit(t.close())

"""End to end through ParaView: SPHImpact (small) -> ImpactHandoff with a small GranularBed ->
DEMIntegrator steps. The hand-off's output carries the SPH totals of linear and angular
momentum, the alpha shape comes out as a surface, the DEM runs from it, and bad input is
named."""

import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_impact_handoff")

sph = simple.SPHImpact(ParticlesAcrossImpactor=3, TargetRadius=0.25, EndTime=4e-5, OutputInterval=2e-5)
bed = simple.GranularBed(Packing="HCP", Container="Bowl", ContainerRadius=0.3, ParticleRadius=0.015,
                         SurfaceHeight=0.0)
hand = simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=100.0, DropEjectaLandingOutside=0)
out = fetch(hand)
n = out.GetNumberOfPoints()
origin = vtk_to_numpy(out.GetPointData().GetArray("Origin"))
t.check(n > 100 and (origin == 0).sum() > 100 and (origin == 1).sum() > 0,
        f"expected kept bed and ejecta particles, got {n} ({(origin == 1).sum()} ejecta)")

sph.UpdatePipeline(4e-5)
s = fetch(sph)
sv = vtk_to_numpy(s.GetPointData().GetArray("Velocity"))
sm = vtk_to_numpy(s.GetPointData().GetArray("Mass"))
sx = vtk_to_numpy(s.GetPoints().GetData())
P_sph = (sm[:, None] * sv).sum(axis=0)
L_sph = (sm[:, None] * np.cross(sx, sv)).sum(axis=0)

pd = out.GetPointData()
v = vtk_to_numpy(pd.GetArray("Velocity"))
w = vtk_to_numpy(pd.GetArray("AngularVelocity"))
m = vtk_to_numpy(pd.GetArray("Mass"))
r = vtk_to_numpy(pd.GetArray("Radius"))
x = vtk_to_numpy(out.GetPoints().GetData())
P = (m[:, None] * v).sum(axis=0)
L = (m[:, None] * np.cross(x, v)).sum(axis=0) + ((0.4 * m * r * r)[:, None] * w).sum(axis=0)
scale = (sm * np.linalg.norm(sv, axis=1)).sum()
t.check(np.linalg.norm(P - P_sph) < 1e-10 * scale, f"momentum not carried over: {P} vs {P_sph}")
t.check(np.linalg.norm(L - L_sph) < 1e-10 * scale * 0.25, f"angular momentum not carried over: {L} vs {L_sph}")
fd = out.GetFieldData()
t.check(abs(field_value(out, "Time") - 4e-5) < 1e-15, "the hand-off time is not the SPH input's last step")
ratio = field_value(out, "CompactMassRatio")
t.check(ratio is not None and ratio > 0.0, "no compact mass ratio in field data")
t.check(fd.GetAbstractArray("ContainerType") is not None, "the bed's container did not pass through")

# Dropped ejecta: no particles for them, no bed particle evicted to make room for them (placed
# ejecta may take a bed particle's place), and what they carry is reported.
hand.EjectaParticles = "Dropped"
dropped = fetch(hand)
dorigin = vtk_to_numpy(dropped.GetPointData().GetArray("Origin"))
t.check((dorigin == 1).sum() == 0 and (dorigin == 0).sum() >= (origin == 0).sum(),
        f"Dropped kept {(dorigin == 1).sum()} ejecta or changed the bed ({(dorigin == 0).sum()} vs {(origin == 0).sum()})")
ejecta_mass = field_value(dropped, "SPHEjectaMass")
sph_fast = sm[np.linalg.norm(sv, axis=1) > 100.0].sum()
t.check(ejecta_mass is not None and abs(ejecta_mass - sph_fast) < 1e-9 * sph_fast,
        f"dropped ejecta mass {ejecta_mass} is not the SPH mass faster than the limit {sph_fast}")
dm = vtk_to_numpy(dropped.GetPointData().GetArray("Mass"))
dv = vtk_to_numpy(dropped.GetPointData().GetArray("Velocity"))
P_fast = (sm[:, None] * sv)[np.linalg.norm(sv, axis=1) > 100.0].sum(axis=0)
t.check(np.linalg.norm((dm[:, None] * dv).sum(axis=0) - (P_sph - P_fast)) < 1e-10 * scale,
        "with the ejecta dropped, the particles do not carry the compact material's momentum")
hand.EjectaParticles = "OnePerSPHParticle"

# Ejecta and curtain coming down outside the bowl (radius 0.3 m) leave the domain: the count
# agrees with their ballistic flights computed here under the SPH state's gravity, and the
# particles plus what escaped carry the SPH momentum.
hand.DropEjectaLandingOutside = 1
esc = fetch(hand)
g = -s.GetFieldData().GetArray("Gravity").GetTuple3(0)[2]
alpha = field_value(esc, "AlphaRadius")
flying = (np.linalg.norm(sv, axis=1) > 100.0) | (sx[:, 2] > alpha)
up = np.maximum(sx[:, 2], 0.0)
t_land = (sv[:, 2] + np.sqrt(sv[:, 2] ** 2 + 2.0 * g * up)) / g
land = sx[:, :2] + sv[:, :2] * t_land[:, None]
outside = flying & (np.hypot(land[:, 0], land[:, 1]) > 0.3)
t.check(outside.sum() > 0 and field_value(esc, "EscapedCount") == outside.sum(),
        f"{field_value(esc, 'EscapedCount')} escaped, ballistic flights give {outside.sum()}")
em = vtk_to_numpy(esc.GetPointData().GetArray("Mass"))
ev = vtk_to_numpy(esc.GetPointData().GetArray("Velocity"))
P_esc = np.array(esc.GetFieldData().GetArray("SPHEscapedMomentum").GetTuple3(0))
t.check(np.linalg.norm(P_esc - (sm[:, None] * sv)[outside].sum(axis=0)) < 1e-10 * scale,
        "the escaped momentum is not that of the SPH particles landing outside")
t.check(np.linalg.norm((em[:, None] * ev).sum(axis=0) + P_esc - P_sph) < 1e-10 * scale,
        "particles and escaped material do not carry the SPH momentum")
hand.DropEjectaLandingOutside = 0

surface = fetch(hand, port=1)
t.check(surface.GetNumberOfCells() > 100, f"alpha-shape surface has {surface.GetNumberOfCells()} triangles")

# Two DEM steps (about 5 ns each): momentum changes only by gravity and the few wall contacts.
dem = simple.DEMIntegrator(Input=hand, MaxExpectedSpeed=2000.0, EndTime=4e-5 + 1e-8, OutputInterval=1e-8)
dem.UpdatePipeline(4e-5 + 1e-8)
d = fetch(dem)
steps = field_value(d, "Step")
Pd = np.array(d.GetFieldData().GetArray("TotalMomentum").GetTuple3(0))
t.check(d.GetNumberOfPoints() == n and steps is not None and steps >= 1, f"the DEM did not step ({steps})")
t.check(np.linalg.norm(Pd - P) < 1e-3 * scale, f"DEM momentum drifted: {Pd} vs {P}")

with captured_vtk_messages() as log:
    bad = fetch(simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=1e-9))
t.check(bad.GetNumberOfPoints() == 0 and "no compact material" in log["text"],
        f"empty compact set not reported: {log['text'][:300]!r}")
with captured_vtk_messages() as log:
    bad = fetch(simple.ImpactHandoff(Input=simple.Sphere(), Bed=bed))
t.check(bad.GetNumberOfPoints() == 0 and "Velocity" in log["text"],
        f"missing Velocity not reported: {log['text'][:300]!r}")
sys.exit(t.close())

"""examples/sci_crater_small.pvsm, the ParaView state of the small SCI pipeline (written by
tests/gui/make_sci_crater_small_state.py), loaded with LoadState as a user's File > Load State
would: the pipeline and its connections are there, the views colour what they should, the file
names no path of the machine it was written on; then the pipeline is run to the state's time
and its data checked:

- no particle is lost between the hand-off and the DEM stage's last output;
- the hand-off carries the compact SPH material's momentum over (bed + curtain = compact, to
  1e-10 of the momenta involved), compact + ejecta = the SPH total, and the DEM particles with
  what escaped the bowl carry the compact momentum (both to 1e-9), as examples/sci_crater.py's
  test checks at its size;
- the bed came to rest: its kinetic energy at the end is below half of the hand-off's;
- the crater is found, its diameter within 0.35 + 2 r / D_pi of the pi-scaling diameter D_pi
  (the example's criterion, 35 %, widened by one grain diameter 2 r, which is the profile's
  resolution: the crater here is a few grains across, 4.8 grain diameters in the run of
  2026-12-07, whose figures the test prints), its depth 0.15-0.3 of its diameter
  give or take a grain radius (the example's test: simple craters in granular targets);
- the DEM stiffness follows examples/sci_crater.py's rule (the speed it is chosen for is at least
  1.5 times the fastest particle's after the hand-off) and the bed was settled in the same law.

Usage: scripts/pvbatch tests/pvbatch/test_state_file.py SOURCE_DIR [STATE.pvsm]
"""

import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin, sci
from craterkit.testing import Checker

source_dir = sys.argv[1]
state = sys.argv[2] if len(sys.argv) > 2 else os.path.join(source_dir, "examples", "sci_crater_small.pvsm")
t = Checker("test_state_file")
text = open(state).read()
paths = sorted(set(re.findall(r'value="(/[^"]+)"', text)))  # "/" alone is a block selector
t.check(not paths and os.path.abspath(source_dir) not in text, f"the state names absolute paths: {paths}")

simple = load_plugin()
simple.LoadState(state)
names = ["GranularBed", "SPHImpact", "ImpactHandoff", "DEMIntegrator", "CraterProfile", "FragmentAnalysis"]
found = {name: simple.FindSource(name) for name in names}
missing = [name for name, proxy in found.items() if proxy is None]
t.check(not missing, f"the state lacks {missing}")
if missing:
    sys.exit(t.close())
bed, sph, hand, dem, profile, fragments = (found[name] for name in names)
t.check(hand.Input.GetXMLName() == "SPHImpact" and hand.Bed.GetXMLName() == "GranularBed" and
        dem.Input.GetXMLName() == "ImpactHandoff" and profile.Input.GetXMLName() == "DEMIntegrator" and
        fragments.Input.GetXMLName() == "DEMIntegrator", "the pipeline's connections differ")

# The views: the DEM particles and the cross-section (CraterProfile's second output, the slab)
# shown coloured by height with a colour bar each, and the profile's table in a chart.
views = simple.GetViews()
t.check(sorted(v.GetXMLName() for v in views) == ["RenderView", "RenderView", "XYChartView"],
        f"views in the state: {[v.GetXMLName() for v in views]}")
for name, upstream, port in (("Particle height", "DEMIntegrator", 0), ("Cross-section height", "CraterProfile", 1)):
    source = simple.FindSource(name)
    shown = [(v, r) for v in views if v.GetXMLName() == "RenderView" for r in v.Representations
             if source is not None and r.GetProperty("Input") is not None and r.Input is not None
             and r.Input.SMProxy == source.SMProxy and r.Visibility]
    upstream_port = getattr(source.Input, "Port", 0) if source is not None else None
    t.check(source is not None and source.Input.GetXMLName() == upstream and upstream_port == port and
            len(shown) == 1 and shown[0][1].ColorArrayName[1] == "Height" and
            simple.GetScalarBar(shown[0][1].LookupTable, shown[0][0]).Visibility == 1,
            f"{name}: not {upstream}'s output {port} shown coloured by height with a colour bar")

# Run the pipeline to the state's time: the DEM stage's last output.
scene = simple.GetAnimationScene()
times = list(dem.TimestepValues)
end = times[-1]
t.check(abs(scene.AnimationTime - end) <= 1e-12 * end, f"the state opens at {scene.AnimationTime} s, not {end} s")

# The scales from the state's own SPH properties (examples/sci_crater.py's rules).
g = sph.SurfaceGravity
sc = sci.scales(g, sph.ImpactorMass, sph.ImpactSpeed, sph.ImpactorMaterial, sph.TargetMaterial, sph.TargetPorosity)
d0 = fetch(hand)
t0 = field_value(d0, "Time")
sph.UpdatePipeline(t0)
sph_data = fetch(sph)
dem.UpdatePipeline(end)
dem_data = fetch(dem)
profile.UpdatePipeline(end)
prof = fetch(profile)
slab = fetch(profile, 1)
fragments.UpdatePipeline(end)
frag = fetch(fragments)

n0, n = d0.GetNumberOfPoints(), dem_data.GetNumberOfPoints()
t.check(n0 > 500 and n == n0, f"{n0} particles after the hand-off, {n} at the end")
t.check(abs(field_value(dem_data, "Time") - end) <= field_value(dem_data, "TimeStep"),
        f"the DEM stage ended at {field_value(dem_data, 'Time')} s, not {end} s")


def vec(data, name):
    return np.array(field_value(data, name))


def totals(data, surface_grain=None):
    pd = data.GetPointData()
    m = vtk_to_numpy(pd.GetArray("Mass"))
    v = vtk_to_numpy(pd.GetArray("Velocity"))
    ke = 0.5 * m * (v * v).sum(axis=1)
    momentum = (m[:, None] * v).sum(axis=0)
    if surface_grain is not None:  # the bed: below one grain diameter above the surface
        ke = ke[vtk_to_numpy(data.GetPoints().GetData())[:, 2] <= surface_grain]
    return momentum, float(ke.sum()), float(np.linalg.norm(v, axis=1).max())


compact = vec(d0, "SPHCompactMomentum")
sph_total = np.array(field_value(sph_data, "TotalMomentum"))
scale = np.linalg.norm(sph_total) + np.linalg.norm(vec(d0, "SPHEjectaMomentum")) + 1.0
t.check(np.allclose(vec(d0, "DEMMappedMomentum") + vec(d0, "SPHCurtainMomentum"), compact, rtol=0, atol=1e-10 * scale),
        "the compact SPH material's momentum is not carried over")
t.check(np.allclose(compact + vec(d0, "SPHEjectaMomentum"), sph_total, rtol=0, atol=1e-9 * scale),
        f"compact {compact} and ejecta momentum do not add up to the SPH total {sph_total}")
p0, _, vmax0 = totals(d0)
t.check(np.allclose(p0 + vec(d0, "SPHEscapedMomentum"), compact, rtol=0, atol=1e-9 * scale),
        f"the DEM particles {p0} and the escaped material do not carry the compact momentum {compact}")
grain = float(np.mean(vtk_to_numpy(fetch(bed).GetPointData().GetArray("Radius"))))
_, ke0, _ = totals(d0, 2.0 * grain)
_, ke_end, _ = totals(dem_data, 2.0 * grain)
t.check(ke_end < 0.5 * ke0, f"the bed did not come to rest: kinetic energy {ke0:.3g} J -> {ke_end:.3g} J")
# The DEM stiffness: examples/sci_crater.py's rule (1.5 times the fastest particle after the
# hand-off, at least half of sqrt(g D_pi)) gives the speed the state's bed was settled for.
t.check(1.5 * vmax0 <= dem.MaxExpectedSpeed and abs(dem.MaxExpectedSpeed - sci.dem_stiffness_speed(vmax0, sc))
        <= 1e-9 * dem.MaxExpectedSpeed and bed.DEMMaxExpectedSpeed == dem.MaxExpectedSpeed and
        bed.DEMMaxOverlap == dem.MaxOverlap,
        f"fastest particle after the hand-off {vmax0:.3g} m/s; the DEM stiffness is for {dem.MaxExpectedSpeed:.3g} "
        f"m/s and {dem.MaxOverlap} overlap, the bed's for {bed.DEMMaxExpectedSpeed:.3g} m/s and {bed.DEMMaxOverlap}")

# The crater against pi-scaling.
diameter, depth = field_value(prof, "CraterDiameter"), field_value(prof, "CraterDepth")
tolerance = 0.35 + 2.0 * grain / sc.d_pi
ratio = diameter / sc.d_pi if diameter else 0.0
t.check(field_value(prof, "CraterFound") == 1 and abs(ratio - 1.0) <= tolerance,
        f"crater diameter {diameter} m = {ratio:.3f} of pi-scaling {sc.d_pi:.4g} m (tolerance {tolerance:.3f})")
t.check(depth is not None and diameter and 0.15 * diameter - grain <= depth <= 0.3 * diameter + grain,
        f"crater depth {depth} m for a diameter of {diameter} m and grains of radius {grain:.3g} m")
y = vtk_to_numpy(slab.GetPoints().GetData())[:, 1] if slab.GetNumberOfPoints() else np.array([np.inf])
t.check(slab.GetNumberOfPoints() > 20 and np.abs(y).max() <= 4.0 * grain * (1 + 1e-9),
        f"the slab: {slab.GetNumberOfPoints()} particles, |y| up to {np.abs(y).max():.3g} m")
t.check((field_value(frag, "FragmentCount") or 0) >= 1 and field_value(frag, "LargestMassFraction") > 0.5,
        f"FragmentAnalysis: {field_value(frag, 'FragmentCount')} fragments, largest "
        f"{field_value(frag, 'LargestMassFraction')} of the mass")
print(f"crater diameter {diameter:.4g} m = {ratio:.3f} of pi-scaling {sc.d_pi:.4g} m, depth {depth:.3g} m; "
      f"{n} DEM particles of radius {grain:.3g} m; bed kinetic energy {ke0:.3g} J -> {ke_end:.3g} J")
sys.exit(t.close())

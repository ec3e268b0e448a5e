"""How steep a crater wall the SCI bed holds: conical pits of a chosen wall slope are cut into
the bed of the SCI validation (the same GranularBed, bowl and grains as `slow.sci_crater_ryugu`:
30,000 RCP grains in a bowl of radius 1.05 D_pi at Ryugu's gravity) and DEMIntegrator runs
each with the default contact coefficients and no velocities, as the crater's DEM stage does
after the hand-off. For each pit and output time the CraterProfile measures are printed: depth,
diameter, the mean slope atan(depth / radius) and the wall's slope (least-squares fit of the
profile between 25 % and 75 % of the radius), with the crater's radius, or the cut's where no
rim rises back to the surface, with the bed's kinetic energy per grain
in units of m g r (the heap test calls a bed at rest below 1e-3).

A wall that stands steeper than the grains' 30-degree angle of repose keeps its cut slope; one
that fails slumps towards it. Times are in units of sqrt(D_pi / g) (311 s at Ryugu's gravity);
the SCI crater's DEM stage runs 1.5 of them.

    scripts/pvbatch benchmarks/sci_crater/wall_stability.py --slopes 30 35 40 45
    scripts/pvbatch benchmarks/sci_crater/wall_stability.py --settling-friction 0.6  # a looser bed

Writes OUTPUT_DIR/wall_stability.json (one record per pit and time) and a cross-section of
each pit at its last time.
"""

import argparse
import json
import math
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkObject, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from craterkit import fetch, fetch_stage, field_value, load_plugin, material_value, print_progress
from craterkit.cross_section import crater_measures, render_cross_section
from craterkit.scaling import crater_diameter, formation_time

SCI_IMPACT = {"mass": 2.0, "speed": 2000.0, "impactor": "copper", "target": "regolith"}
RCP_PACKING = 0.60  # as examples/sci_crater.py: the grain density that gives the target's bulk density


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slopes", type=float, nargs="+", default=[30.0, 35.0, 40.0, 45.0],
                   help="the pits' cut wall slopes, degrees")
    p.add_argument("--pit-diameter", type=float, default=13.8,
                   help="m at the surface (the suite's crater: 13.8 m)")
    p.add_argument("--particles", type=int, default=30000, help="bed grains requested (the suite's 30,000)")
    p.add_argument("--gravity", type=float, default=1.5e-4, help="m/s^2")
    p.add_argument("--settling-friction", type=float, default=0.1,
                   help="the bed's friction while it settles (GranularBed's SettlingFriction; 0.1 the default, "
                        "more gives a looser bed)")
    p.add_argument("--static-friction", type=float, default=0.6, help="the DEM's sliding friction")
    p.add_argument("--rolling-friction", type=float, default=0.35, help="the DEM's rolling friction")
    p.add_argument("--dem-time", type=float, default=3.0, help="in units of sqrt(D_pi / g)")
    p.add_argument("--frames", type=int, default=4, help="outputs, evenly spaced over --dem-time")
    p.add_argument("--output-dir", default="results/wall_stability")
    args = p.parse_args(argv)
    if any(not 0.0 < s < 90.0 for s in args.slopes):
        p.error("--slopes: each slope must lie between 0 and 90 degrees")
    if not args.pit_diameter > 0.0 or not args.particles > 0 or not args.gravity > 0.0:
        p.error("--pit-diameter, --particles and --gravity must be positive")
    if not 0.0 <= args.settling_friction <= 2.0:
        p.error("--settling-friction must lie in [0, 2]")
    if args.static_friction < 0.0 or args.rolling_friction < 0.0:
        p.error("--static-friction and --rolling-friction must not be negative")
    if not args.dem_time > 0.0 or not args.frames > 0:
        p.error("--dem-time and --frames must be positive")
    return args


def cut_pit(bed, surface, radius, slope):
    """A copy of the bed without the grains whose centre lies above the cone of the given wall
    slope (degrees) and surface radius around the z axis; its field data kept."""
    x = vtk_to_numpy(bed.GetPoints().GetData())
    rho = np.hypot(x[:, 0], x[:, 1])
    cone = surface - np.maximum(radius - rho, 0.0) * math.tan(math.radians(slope))
    keep = np.flatnonzero(x[:, 2] <= cone)
    out = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x[keep]), deep=1))
    out.SetPoints(points)
    verts = vtkCellArray()
    for i in range(len(keep)):
        verts.InsertNextCell(1)
        verts.InsertCellPoint(i)
    out.SetVerts(verts)
    pd = bed.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(k)
        if a is None:
            continue
        copy = numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(a)[keep]), deep=1, array_type=a.GetDataType())
        copy.SetName(a.GetName())
        out.GetPointData().AddArray(copy)
    out.GetFieldData().ShallowCopy(bed.GetFieldData())
    return out, len(x) - len(keep)


def wall_slope(profile_data, radius):
    """Degrees: the least-squares slope of the profile h(r) between 25 % and 75 % of radius."""
    rd = profile_data.GetRowData()
    r = vtk_to_numpy(rd.GetArray("Radius"))
    h = vtk_to_numpy(rd.GetArray("Height"))
    use = (r >= 0.25 * radius) & (r <= 0.75 * radius) & np.isfinite(h)
    if use.sum() < 2:
        return float("nan")
    return math.degrees(math.atan(np.polyfit(r[use], h[use], 1)[0]))


class Scene:
    """The SCI set-up's scales and its settled bed: D_pi, sqrt(D_pi/g), the grain radius, the bed's
    data, its surface (the mean height of its profile, as examples/sci_crater.py measures
    against) and packing fraction."""

    def __init__(self, simple, args):
        rho_imp = material_value(SCI_IMPACT["impactor"], "rho0")
        target = SCI_IMPACT["target"]
        rho_bulk = material_value(target, "rho0") / material_value(target, "distention")
        self.d_pi = crater_diameter(SCI_IMPACT["mass"], SCI_IMPACT["speed"], rho_imp, rho_bulk, args.gravity)
        self.t_scale = formation_time(self.d_pi, args.gravity)
        bowl = 1.05 * self.d_pi
        self.grain = bowl * (RCP_PACKING / (2.0 * args.particles)) ** (1.0 / 3.0)
        print(f"D_pi {self.d_pi:.3g} m, sqrt(D_pi/g) {self.t_scale:.3g} s; bowl radius {bowl:.3g} m, grain radius "
              f"{self.grain:.3g} m, pit diameter {args.pit_diameter:.3g} m "
              f"({args.pit_diameter / (2 * self.grain):.0f} grain diameters)", flush=True)
        start = time.time()
        bed = simple.GranularBed(Packing="RCP", Container="Bowl", ContainerRadius=bowl, ParticleRadius=self.grain,
                                 SurfaceHeight=0.0, ParticleDensity=rho_bulk / RCP_PACKING,
                                 SettlingGravity=args.gravity, SettlingFriction=args.settling_friction,
                                 MaxParticles=max(10 * args.particles, 100000))
        print_progress(bed, "bed")
        self.bed = fetch_stage(bed, "bed")
        vtkObject.GlobalWarningDisplayOff()  # a flat bed has no crater: CraterProfile would say so
        heights = fetch(simple.CraterProfile(Input=bed)).GetRowData().GetArray("Height")
        vtkObject.GlobalWarningDisplayOn()
        self.surface = float(np.nanmean(vtk_to_numpy(heights)))
        self.phi = field_value(self.bed, "BulkPackingFraction")
        print(f"bed: {self.bed.GetNumberOfPoints()} grains, packing fraction {self.phi:.3f}, surface at "
              f"{self.surface:.3g} m, {time.time() - start:.0f} s", flush=True)


def kinetic_energy_per_mgr(data, gravity, grain):
    """The particles' kinetic energy over N m g r (m their mean mass, r the bed's grain radius)."""
    mass = vtk_to_numpy(data.GetPointData().GetArray("Mass"))
    v = vtk_to_numpy(data.GetPointData().GetArray("Velocity"))
    return 0.5 * float((mass * (v * v).sum(axis=1)).sum()) / (len(mass) * float(mass.mean()) * gravity * grain)


def run_pit(simple, args, scene, slope, records):
    """Cuts one pit, runs the DEM from rest to each output time and appends a record per time."""
    radius = 0.5 * args.pit_diameter
    pit, removed = cut_pit(scene.bed, scene.surface, radius, slope)
    source = simple.TrivialProducer()
    source.GetClientSideObject().SetOutput(pit)
    cut_profile = simple.CraterProfile(Input=source, SurfaceFromInput=0, SurfaceHeight=scene.surface)
    cut = crater_measures(cut_profile)
    cut_wall = wall_slope(fetch(cut_profile), radius)
    print(f"pit cut at {slope:g} deg: {removed} grains removed, depth {cut['depth']:.3g} m, wall slope "
          f"{cut_wall:.1f} deg", flush=True)
    t0 = field_value(pit, "Time", 0.0)
    fractions = [args.dem_time * (k + 1) / args.frames for k in range(args.frames)]
    frames = [t0 + f * scene.t_scale for f in fractions]
    dem = simple.DEMIntegrator(Input=source, Container="FromInput", GravityModel="Uniform",
                               SurfaceGravity=[0.0, 0.0, -args.gravity],
                               MaxExpectedSpeed=0.5 * math.sqrt(args.gravity * scene.d_pi),
                               StaticFriction=args.static_friction, RollingFriction=args.rolling_friction,
                               EndTime=frames[-1], OutputInterval=frames[0] - t0, KeptStates=0,
                               CheckpointFile=os.path.join(args.output_dir, f"pit{slope:g}.ckdem"))
    profile = simple.CraterProfile(Input=dem, SurfaceFromInput=0, SurfaceHeight=scene.surface)
    start = time.time()
    for f, t in zip(fractions, frames):
        data = fetch_stage(dem, f"DEM of the {slope:g}-degree pit", t)
        m = crater_measures(profile, t)
        r = 0.5 * m["diameter"] if m["found"] else radius
        rec = {"cut_slope_deg": slope, "time_over_scale": f, "time_s": t, "depth_m": m["depth"],
               "diameter_m": m["diameter"] if m["found"] else 0.0, "rim_diameter_m": m["rim_diameter"],
               "mean_slope_deg": math.degrees(math.atan(m["depth"] / r)),
               "wall_slope_deg": wall_slope(fetch(profile), r),
               "kinetic_energy_per_mgr": kinetic_energy_per_mgr(data, args.gravity, scene.grain),
               "cut_depth_m": cut["depth"], "cut_wall_slope_deg": cut_wall, "grains_removed": removed,
               "grain_radius_m": scene.grain, "bed_packing_fraction": scene.phi,
               "settling_friction": args.settling_friction, "static_friction": args.static_friction,
               "rolling_friction": args.rolling_friction, "wall_seconds": round(time.time() - start, 1)}
        records.append(rec)
        width = f"{rec['diameter_m']:.3g} m" if m["found"] else "not found (no rim rises to the surface)"
        print(f"  {slope:g} deg, t = {f:g} sqrt(D/g) ({t:.4g} s): depth {rec['depth_m']:.3g} m, diameter {width}, "
              f"mean slope {rec['mean_slope_deg']:.1f} deg, wall slope {rec['wall_slope_deg']:.1f} deg, kinetic "
              f"energy {rec['kinetic_energy_per_mgr']:.2g} m g r per grain ({rec['wall_seconds']:.0f} s)", flush=True)
        path = os.path.join(args.output_dir, "wall_stability.json")
        with open(path + ".part", "w") as out:  # replaced whole: a killed run leaves the last one
            json.dump(records, out, indent=1)
        os.replace(path + ".part", path)
    render_cross_section(dem, os.path.join(args.output_dir, f"pit{slope:g}.png"), surface_height=scene.surface,
                         label=f"pit cut at {slope:g} deg, t = {args.dem_time:g} sqrt(D/g)",
                         measures=crater_measures(profile, frames[-1]))
    for proxy in (profile, dem, cut_profile, source):
        simple.Delete(proxy)


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    simple = load_plugin()
    scene = Scene(simple, args)
    records = []
    for slope in args.slopes:
        run_pit(simple, args, scene, slope, records)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

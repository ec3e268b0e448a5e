"""How steep a crater wall the SCI bed holds: conical pits of a chosen wall slope are cut into
a bed made as the SCI validation's (`slow.sci_crater_ryugu`: 30,000 RCP grains requested, a
bowl of radius 1.05 D_pi at Ryugu's gravity), and DEMIntegrator runs each from rest with the
default contact coefficients and contacts as stiff as the crater's DEM stage's (they are set
for the fastest expected speed, --max-expected-speed).

The cut removes the grains whose centre lies above the cone; what is measured is the cut
pit's own profile. For the cut and each output time the script prints, from CraterProfile:
  - depth: the crater's depth as the SCI validation measures it (radial bins 2.5 grain
    diameters wide, so the lowest bin lies above the cone's apex);
  - wall slope: the least-squares slope of a finer profile (one grain diameter per bin)
    between 25 % and 75 % of the cut's radius;
  - mean slope: atan(depth / the cut's radius);
  - the bed's translational kinetic energy per grain in units of m g r (the heap test calls a
    bed at rest below 1e-3 of it, rotation included).
A wall that stands keeps its cut slope; one that fails slumps and the pit's depth falls. Times
are in units of sqrt(D_pi / g) (311 s at Ryugu's gravity); the SCI crater's DEM stage runs 1.5
of them.

    scripts/pvbatch benchmarks/sci_crater/wall_stability.py --slopes 30 35 40 45
    scripts/pvbatch benchmarks/sci_crater/wall_stability.py --slopes 35 40 --rolling-friction 0
    scripts/pvbatch benchmarks/sci_crater/wall_stability.py --slopes 35 40 --packing Loose --particles 6000

The bed rests in the pits' own contact law (GranularBed's DEMMaxExpectedSpeed is
--max-expected-speed). --packing Loose makes GranularBed's loose bed, its grain density
rho_bulk / craterkit.sci.PACKING_FRACTION["Loose"].

Writes OUTPUT_DIR/wall_stability.json (one record per pit and time, rewritten after each) and a
cross-section of each pit at its last time (pitSLOPE.png). --resume keeps the pits the file
already holds whole from a run of the same set-up (frictions, contacts, bed, pit, gravity) and
runs the others; the file keeps the records of other set-ups. Without --resume it is replaced.
"""

import argparse
import json
import math
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from craterkit import fetch_stage, field_value, load_plugin, sci
from craterkit.cross_section import crater_measures, render_cross_section
# The speed the SCI crater's DEM stage at Ryugu's gravity sets its contacts for: 1.5 times the
# fastest grain after the hand-off (report.json's dem_max_expected_speed_m_s).
CRATER_STAGE_SPEED = 0.0663

def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--slopes", type=float, nargs="+", default=[30.0, 35.0, 40.0, 45.0],
                   help="the pits' cut wall slopes, degrees")
    p.add_argument("--pit-diameter", type=float, default=13.8, help="m at the surface (the suite's crater: 13.8 m)")
    p.add_argument("--particles", type=int, default=30000, help="bed grains requested (the suite's 30,000)")
    p.add_argument("--gravity", type=float, default=1.5e-4, help="m/s^2")
    p.add_argument("--packing", choices=["RCP", "Loose"], default="RCP", help="the bed's GranularBed Packing")
    p.add_argument("--settling-friction", type=float, default=0.1,
                   help="the bed's friction while it settles (GranularBed's SettlingFriction)")
    p.add_argument("--static-friction", type=float, default=0.6, help="the DEM's sliding friction")
    p.add_argument("--rolling-friction", type=float, default=0.35, help="the DEM's rolling friction")
    p.add_argument("--max-expected-speed", type=float, default=CRATER_STAGE_SPEED,
                   help="m/s, the speed the contacts are stiffened for (DEMIntegrator's MaxExpectedSpeed; "
                        f"the crater's DEM stage at Ryugu's gravity: {CRATER_STAGE_SPEED})")
    p.add_argument("--dem-time", type=float, default=3.0, help="in units of sqrt(D_pi / g)")
    p.add_argument("--frames", type=int, default=4, help="outputs, evenly spaced over --dem-time")
    p.add_argument("--resume", action="store_true", help="keep the pits OUTPUT_DIR/wall_stability.json holds")
    p.add_argument("--output-dir", default="results/wall_stability")
    args = p.parse_args(argv)
    if any(not 0.0 < s < 90.0 for s in args.slopes):
        p.error("--slopes: each slope must lie between 0 and 90 degrees")
    for name in ("pit_diameter", "gravity", "max_expected_speed", "dem_time"):
        value = getattr(args, name)
        if not (math.isfinite(value) and value > 0.0):
            p.error(f"--{name.replace('_', '-')} must be positive and finite, not {value}")
    for name in ("particles", "frames"):
        if getattr(args, name) <= 0:
            p.error(f"--{name} must be positive, not {getattr(args, name)}")
    for name in ("settling_friction", "static_friction", "rolling_friction"):
        value = getattr(args, name)
        if not 0.0 <= value <= 2.0:  # also refuses NaN
            p.error(f"--{name.replace('_', '-')} must lie in [0, 2], not {value}")
    return args


class SciBed:
    """The SCI set-up's scales and a bed made as the validation's: D_pi, sqrt(D_pi / g), the
    grain radius (all known before the plugin is loaded: a pit wider than the bowl is refused
    first), then with `build` the bed, its surface (the mean height of its profile, which the
    SCI example measures the crater against) and its packing fraction."""

    def __init__(self, args):
        self.sc = sci.scales(args.gravity)
        self.d_pi, self.t_scale, self.bowl = self.sc.d_pi, self.sc.t_scale, self.sc.bowl_radius
        if args.pit_diameter >= 2.0 * self.bowl:
            print(f"error: --pit-diameter {args.pit_diameter:g} m does not fit the bowl ({2 * self.bowl:.3g} m across)",
                  file=sys.stderr)
            raise SystemExit(2)
        self.grain = self.sc.grain_radius(args.particles, args.packing)

    def build(self, simple, args):
        print(f"D_pi {self.d_pi:.3g} m, sqrt(D_pi/g) {self.t_scale:.3g} s; bowl radius {self.bowl:.3g} m, grain "
              f"radius {self.grain:.3g} m, pit diameter {args.pit_diameter:.3g} m "
              f"({args.pit_diameter / (2 * self.grain):.0f} grain diameters)", flush=True)
        start = time.time()
        _, self.data, self.surface, _ = sci.bed_stage(simple, self.sc, args.packing, args.particles, heading="",
                                                      SettlingFriction=args.settling_friction,
                                                      dem_speed=args.max_expected_speed)
        self.packing = field_value(self.data, "BulkPackingFraction")
        print(f"bed: {self.data.GetNumberOfPoints()} {args.packing} grains, packing fraction {self.packing:.3f}, "
              f"coordination number {field_value(self.data, 'CoordinationNumber'):.2f}, surface at "
              f"{self.surface:.3g} m, {time.time() - start:.0f} s", flush=True)


def cut_pit(bed, surface, radius, slope):
    """A copy of the bed without the grains whose centre lies above the cone of the given wall
    slope (degrees) and surface radius around the z axis; its field data kept. Returns it and
    the number of grains removed."""
    x = vtk_to_numpy(bed.GetPoints().GetData())
    distance = np.hypot(x[:, 0], x[:, 1])  # from the pit's axis
    cone = surface - np.maximum(radius - distance, 0.0) * math.tan(math.radians(slope))
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


def wall_slope(fine_profile, radius):
    """Degrees: the least-squares slope of the profile h(r) between 25 % and 75 % of radius (None
    with fewer than three bins there)."""
    rows = fine_profile.GetRowData()
    r = vtk_to_numpy(rows.GetArray("Radius"))
    h = vtk_to_numpy(rows.GetArray("Height"))
    use = (r >= 0.25 * radius) & (r <= 0.75 * radius) & np.isfinite(h)
    if use.sum() < 3:
        return None
    return math.degrees(math.atan(np.polyfit(r[use], h[use], 1)[0]))


class Profiles:
    """The two CraterProfile filters on one source: the SCI validation's (the depth) and one with
    bins a grain diameter wide (the wall's slope)."""

    def __init__(self, simple, source, bed):
        self.crater = simple.CraterProfile(Input=source, SurfaceFromInput=0, SurfaceHeight=bed.surface)
        self.fine = simple.CraterProfile(Input=source, SurfaceFromInput=0, SurfaceHeight=bed.surface,
                                         MaxRadius=bed.bowl, RadialBins=int(math.ceil(bed.bowl / (2 * bed.grain))))

    def measure(self, radius, time=None):
        """depth (m), wall slope and mean slope (degrees) of the pit of the given cut radius."""
        from paraview import servermanager
        m = crater_measures(self.crater, time)
        if time is not None:
            self.fine.UpdatePipeline(time)
        else:
            self.fine.UpdatePipeline()
        fine = servermanager.Fetch(self.fine)  # as crater_measures: no second, timeless update
        return {"depth_m": m["depth"], "wall_slope_deg": wall_slope(fine, radius),
                "mean_slope_deg": None if m["depth"] is None else math.degrees(math.atan(m["depth"] / radius))}

    def delete(self, simple):
        simple.Delete(self.fine)
        simple.Delete(self.crater)


def kinetic_energy_per_mgr(data, gravity, grain):
    """The particles' translational kinetic energy over N m g r (m their mean mass, r the grain radius)."""
    mass = vtk_to_numpy(data.GetPointData().GetArray("Mass"))
    v = vtk_to_numpy(data.GetPointData().GetArray("Velocity"))
    return 0.5 * float((mass * (v * v).sum(axis=1)).sum()) / (len(mass) * float(mass.mean()) * gravity * grain)


def angle_text(value):
    return "none (too few bins)" if value is None else f"{value:.1f} deg"


def depth_text(value):
    return "none" if value is None else f"{value:.3g} m"


def write_records(path, records):
    """Rewrites the whole file through a temporary one, so that a killed run leaves the last
    complete file."""
    with open(path + ".part", "w") as out:
        json.dump(records, out, indent=1)
    os.replace(path + ".part", path)


def run_pit(simple, args, bed, slope):
    """Cuts one pit and runs the DEM from rest: its records, one per output time."""
    radius = 0.5 * args.pit_diameter
    pit, removed = cut_pit(bed.data, bed.surface, radius, slope)
    source = simple.TrivialProducer()
    source.GetClientSideObject().SetOutput(pit)
    cut_profiles = Profiles(simple, source, bed)
    cut = cut_profiles.measure(radius)
    cut_profiles.delete(simple)
    print(f"pit cut at {slope:g} deg: {removed} grains removed, depth {depth_text(cut['depth_m'])}, wall slope "
          f"{angle_text(cut['wall_slope_deg'])}", flush=True)
    t0 = field_value(pit, "Time", 0.0)
    fractions = [args.dem_time * (k + 1) / args.frames for k in range(args.frames)]
    frames = [t0 + f * bed.t_scale for f in fractions]
    dem = simple.DEMIntegrator(Input=source, Container="FromInput", GravityModel="Uniform",
                               SurfaceGravity=[0.0, 0.0, -args.gravity], MaxExpectedSpeed=args.max_expected_speed,
                               StaticFriction=args.static_friction, RollingFriction=args.rolling_friction,
                               EndTime=frames[-1], OutputInterval=frames[0] - t0, KeptStates=0)
    profiles = Profiles(simple, dem, bed)
    start, records = time.time(), []
    for f, t in zip(fractions, frames):
        data = fetch_stage(dem, f"DEM of the {slope:g}-degree pit", t)
        now = profiles.measure(radius, t)
        records.append(dict(cut_slope_deg=slope, time_over_scale=f, time_s=t, **now,
                            kinetic_energy_per_mgr=kinetic_energy_per_mgr(data, args.gravity, bed.grain),
                            cut_depth_m=cut["depth_m"], cut_wall_slope_deg=cut["wall_slope_deg"],
                            grains_removed=removed, grain_radius_m=bed.grain, bed_packing_fraction=bed.packing,
                            packing=args.packing,
                            settling_friction=args.settling_friction, static_friction=args.static_friction,
                            rolling_friction=args.rolling_friction, max_expected_speed=args.max_expected_speed,
                            particles_requested=args.particles, pit_diameter_m=args.pit_diameter, gravity=args.gravity,
                            wall_seconds=round(time.time() - start, 1)))
        print(f"  {slope:g} deg, t = {f:g} sqrt(D/g) ({t:.4g} s): depth {depth_text(now['depth_m'])}, wall slope "
              f"{angle_text(now['wall_slope_deg'])}, mean slope {angle_text(now['mean_slope_deg'])}, kinetic energy "
              f"{records[-1]['kinetic_energy_per_mgr']:.2g} m g r per grain ({time.time() - start:.0f} s)", flush=True)
    final = simple.ForceTime(Input=dem, ForcedTime=frames[-1], IgnorePipelineTime=1)
    render_cross_section(final, os.path.join(args.output_dir, f"pit{slope:g}.png"), surface_height=bed.surface,
                         label=f"pit cut at {slope:g} deg, t = {args.dem_time:g} sqrt(D/g)")
    profiles.delete(simple)
    for proxy in (final, dem, source):
        simple.Delete(proxy)
    return records


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    path = os.path.join(args.output_dir, "wall_stability.json")
    records = json.load(open(path)) if args.resume and os.path.isfile(path) else []
    same = {"packing": args.packing, "settling_friction": args.settling_friction, "static_friction": args.static_friction,
            "rolling_friction": args.rolling_friction, "max_expected_speed": args.max_expected_speed,
            "particles_requested": args.particles, "pit_diameter_m": args.pit_diameter, "gravity": args.gravity}
    # this run's set-up (records from before --packing are of RCP beds)
    mine = [all(r.get(k, "RCP" if k == "packing" else None) == v for k, v in same.items()) for r in records]
    whole = args.dem_time * (1 - 1e-9)
    done = {r["cut_slope_deg"] for r, m in zip(records, mine) if m and r["time_over_scale"] >= whole}
    # Other set-ups' records stay in the file; this set-up's unfinished pits are run again.
    records = [r for r, m in zip(records, mine) if not m or r["cut_slope_deg"] in done]
    bed = SciBed(args)
    simple = load_plugin()
    bed.build(simple, args)
    for slope in args.slopes:
        if slope in done:
            print(f"pit cut at {slope:g} deg: kept from {path}", flush=True)
            continue
        records += run_pit(simple, args, bed, slope)
        write_records(path, records)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

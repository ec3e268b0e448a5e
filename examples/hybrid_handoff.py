"""The hybrid pipeline at laboratory scale: SPHImpact -> ImpactHandoff -> DEMIntegrator ->
CraterProfile, rendered headless (after Figure 1 of Zhang et al., LPSC 2021: the velocity
field just before and just after the hand-off, side by side).

Defaults: the SCI-like impactor and target of SPHImpact, at a small size (a 0.25 m
hemisphere of regolith, 3 SPH particles across the impactor) handed off at 40 µs onto an HCP
bed of 1.5 cm spheres in a 0.3 m bowl, then a few DEM steps; it runs in under a minute on two
cores. Writes results/hybrid_handoff/{handoff.png, report.md, report.json}.

    scripts/pvbatch examples/hybrid_handoff.py --help
"""

import argparse
import os
import sys
import time

from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, fetch_stage, field_value, load_plugin
from craterkit.figures import handoff_figure
from craterkit.report import write_report


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--particles-across-impactor", type=int, default=3)
    p.add_argument("--target-radius", type=float, default=0.25, help="SPH target hemisphere, m")
    p.add_argument("--handoff-time", type=float, default=4e-5, help="s after contact")
    p.add_argument("--ejecta-speed-limit", type=float, default=100.0, help="m/s")
    p.add_argument("--bed-radius", type=float, default=0.3, help="bowl radius, m")
    p.add_argument("--particle-radius", type=float, default=0.015, help="bed particle radius, m")
    p.add_argument("--packing", choices=["HCP", "RCP"], default="HCP")
    p.add_argument("--dem-time", type=float, default=2e-5, help="DEM time after the hand-off, s")
    p.add_argument("--output-dir", default="results/hybrid_handoff")
    p.add_argument("--width", type=int, default=900, help="width of each panel in pixels")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    simple = load_plugin()
    timings = {}

    print("[1/4] SPH impact", flush=True)
    start = time.time()
    sph = simple.SPHImpact(ParticlesAcrossImpactor=args.particles_across_impactor,
                           TargetRadius=args.target_radius, EndTime=args.handoff_time,
                           OutputInterval=args.handoff_time)
    sph_data = fetch_stage(sph, "SPH run", args.handoff_time)
    timings["sph_s"] = round(time.time() - start, 2)
    print(f"      {sph_data.GetNumberOfPoints()} SPH particles to t = {field_value(sph_data, 'Time'):.2e} s, "
          f"{int(field_value(sph_data, 'Step'))} steps, {timings['sph_s']} s", flush=True)

    print(f"[2/4] {args.packing} bed and hand-off", flush=True)
    start = time.time()
    bed = simple.GranularBed(Packing=args.packing, Container="Bowl", ContainerRadius=args.bed_radius,
                             ParticleRadius=args.particle_radius, SurfaceHeight=0.0)
    # Every ejecta particle is kept (the container's walls stop it), so that the figure shows
    # the whole velocity field handed over; the SCI example lets what lands outside escape.
    hand = simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=args.ejecta_speed_limit,
                                DropEjectaLandingOutside=0)
    dem0 = fetch_stage(hand, "hand-off")
    timings["bed_and_handoff_s"] = round(time.time() - start, 2)
    fd = dem0.GetFieldData()
    vec = lambda name: list(fd.GetArray(name).GetTuple3(0))  # noqa: E731
    origin = vtk_to_numpy(dem0.GetPointData().GetArray("Origin"))
    print(f"      {int((origin == 0).sum())} bed + {int((origin == 1).sum())} ejecta particles, "
          f"{int(field_value(dem0, 'BedRemoved'))} carved, mass ratio {field_value(dem0, 'CompactMassRatio'):.3f}",
          flush=True)

    print("[3/4] DEM steps", flush=True)
    start = time.time()
    t0 = field_value(dem0, "Time")
    dem = simple.DEMIntegrator(Input=hand, MaxExpectedSpeed=2500.0, EndTime=t0 + args.dem_time,
                               OutputInterval=args.dem_time)
    dem_data = fetch_stage(dem, "DEM run", t0 + args.dem_time)
    timings["dem_s"] = round(time.time() - start, 2)
    profile = simple.CraterProfile(Input=dem)
    prof = fetch(profile)

    print("[4/4] pictures and report", flush=True)
    combined = handoff_figure(simple, sph, hand, args.handoff_time,
                              os.path.join(args.output_dir, "handoff.png"), args.width)

    report = {
        "example": "hybrid_handoff",
        "sph_particles": sph_data.GetNumberOfPoints(),
        "handoff_time_s": field_value(sph_data, "Time"),
        "bed_particles_kept": int((origin == 0).sum()),
        "ejecta_particles": int((origin == 1).sum()),
        "bed_carved": int(field_value(dem0, "BedRemoved")),
        "alpha_radius_m": field_value(dem0, "AlphaRadius"),
        "compact_mass_ratio_dem_to_sph": field_value(dem0, "CompactMassRatio"),
        "sph_compact_momentum": vec("SPHCompactMomentum"),
        "dem_mapped_momentum": vec("DEMMappedMomentum"),
        "sph_curtain_momentum": vec("SPHCurtainMomentum"),
        "sph_compact_angular_momentum": vec("SPHCompactAngularMomentum"),
        "dem_mapped_angular_momentum": vec("DEMMappedAngularMomentum"),
        "sph_ejecta_momentum": vec("SPHEjectaMomentum"),
        "dem_ejecta_momentum": vec("DEMEjectaMomentum"),
        "dem_end_time_s": field_value(dem_data, "Time"),
        "dem_steps": int(field_value(dem_data, "Step")),
        "dem_total_momentum": list(dem_data.GetFieldData().GetArray("TotalMomentum").GetTuple3(0)),
        "crater_found": bool(field_value(prof, "CraterFound")),
        "crater_depth_m": field_value(prof, "CraterDepth"),
        "seconds": timings,
        "image": os.path.basename(combined),
    }
    write_report(args.output_dir, "the SPH to DEM hand-off", os.path.basename(combined), report)
    print(f"wrote {combined}, report.md and report.json in {args.output_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

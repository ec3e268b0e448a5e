"""The Hayabusa2 SCI impact end to end (after Zhang et al., LPSC 2021): SPHImpact -> ImpactHandoff
onto a settled granular bed in a hemispherical bowl -> DEMIntegrator until the crater has settled
-> CraterProfile. Writes under --output-dir: figure1_handoff.png (the velocity field before and
after the hand-off), figure2_crater.png (the cross-section with its measures), profile.png, and
report.md / report.json (diameter, rim diameter and depth beside the SCI crater and the
Housen & Holsapple pi-scaling prediction, run times, conservation figures).

The SCI impactor (2 kg of copper at 2 km/s) and target (regolith, friction angle 30 degrees) are
the defaults. Every length follows from the run's pi-scaling diameter D and every time from
sqrt(D/g) (craterkit.sci.scales). The default gravity, 1000 m/s^2 (D = 1.0 m), runs in minutes.
At Ryugu's 1.5e-4 m/s^2 the example takes the validated set-up of slow.sci_ryugu_run (a graded
SPH target, hand-off at 29.5 s, 30,000 RCP grains: craterkit.sci.RYUGU_PRESET), each option
unless given; docs/validation.md gives its figures and cost. --dem-engine lammps runs the DEM
stage on LAMMPS (docs/lammps.md).

    scripts/pvbatch examples/sci_crater.py --help
    scripts/pvbatch examples/sci_crater.py --gravity 1.5e-4        # the SCI crater as validated
    scripts/pvbatch examples/sci_crater.py --dem-engine lammps --lammps-ranks 2
"""

import argparse
import math
import os
import sys
from types import SimpleNamespace

from craterkit import fetch, fetch_stage, field_value, load_plugin, sci
from craterkit.figures import handoff_figure, profile_plot
from craterkit.report import to_resolution, validation_summary, write_report

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    g = p.add_argument_group("impact")
    g.add_argument("--impactor-mass", type=float, default=2.0, help="kg")
    g.add_argument("--impactor-material", default="copper")
    g.add_argument("--impact-speed", type=float, default=2000.0, help="m/s")
    g.add_argument("--target-material", default="regolith")
    g.add_argument("--porosity", type=float, default=-1.0, help="target porosity; negative: the material's")
    g.add_argument("--friction-angle", type=float, default=30.0, help="degrees")
    g.add_argument("--cohesion", type=float, default=0.0,
                   help="the SPH target's Drucker-Prager cohesion in Pa (Ryugu's surface: below about 1.3 Pa, "
                        "Arakawa et al. 2020); the DEM bed stays cohesionless")
    g.add_argument("--gravity", type=float, default=1000.0,
                   help=f"surface gravity in m/s^2 (Ryugu: {sci.RYUGU_GRAVITY}); see the module help for the cost")
    g = p.add_argument_group("SPH stage")
    g.add_argument("--sph-resolution", type=int, default=2, help="SPH particles across the impactor")
    g.add_argument("--sph-target-radius", type=float, default=0.0,
                   help="SPH target hemisphere, m; 0: 0.8 x the predicted crater diameter D")
    g.add_argument("--sph-coarsening", type=float, default=1.0,
                   help="graded SPH target (SPHImpact's TargetCoarsening, experimental): the impactor's spacing "
                        "within four impactor radii, coarsening outwards up to this multiple of it; 1: uniform")
    g.add_argument("--handoff-time", type=float, default=0.0,
                   help="s after contact; 0: --handoff-fraction sqrt(D/g) for the predicted D")
    g.add_argument("--handoff-fraction", type=float, default=0.63,
                   help="the hand-off time in units of sqrt(D/g) where --handoff-time is not given: 0.63 "
                        "(20 ms at the default gravity) when the crater has mostly opened; about 0.1 "
                        "while it still grows, which leaves the growth to the DEM stage")
    g.add_argument("--late-stage-time", type=float, default=1e-3,
                   help="s; from then on the SPH solids use the late-stage scheme (a soft linear equation "
                        "of state, long steps: SPHImpact's LateStageTime); negative: never")
    g.add_argument("--stop-impactor", action="store_true",
                   help="at the late-stage switch, stop the impactor in the target's flow (SPHImpact's "
                        "StopImpactorAtLateStage): the soft late-stage target cannot stop a dense impactor")
    g.add_argument("--sph-block-steps", type=int, default=0,
                   help="individual power-of-two SPH time steps in the late stage, up to 2^L times the smallest "
                        "(SPHImpact's BlockStepLevels); 0: one step for all")
    g.add_argument("--late-stage-sound-speed", type=float, default=0.0,
                   help="m/s, of the late-stage scheme; 0: 10 sqrt(g D), ten times the crater's own speed scale")
    g.add_argument("--late-stage-initial-sound-speed", type=float, default=0.0,
                   help="m/s; above the late-stage sound speed, c starts here at the switch and falls as "
                        "(t / late-stage time)^-q to it, so that it stays above the crater's flow speeds "
                        "(SPHImpact's LateStageInitialSoundSpeed); 0: one switch")
    g.add_argument("--late-stage-sound-speed-exponent", type=float, default=0.6,
                   help="q of the falling late-stage sound speed (SPHImpact's LateStageSoundSpeedExponent)")
    g.add_argument("--late-stage-poisson-ratio", type=float, default=-1.0,
                   help="the Poisson ratio the target takes at the late-stage switch (SPHImpact's "
                        "LateStagePoissonRatio); negative: its own, which leaves the regolith almost no "
                        "shear modulus")
    g.add_argument("--sph-domain-radius", type=float, default=0.0,
                   help="m; SPH particles farther from the impact point fly ballistically (SPHImpact's "
                        "DomainRadius); 0: no limit")
    g.add_argument("--sph-state", default="",
                   help="hand off this saved SPH state (the sph_handoff.vtp an earlier run wrote) instead of "
                        "running the SPH stage; its time is the hand-off time")
    g.add_argument("--ejecta-speed-limit", type=float, default=0.0,
                   help="m/s; faster SPH material leaves as ejecta (dropped). 0: 1 m/s at Ryugu, "
                        "Froude-scaled to the run's gravity and predicted crater")
    g = p.add_argument_group("DEM stage")
    g.add_argument("--particles", type=int, default=6000, help="DEM bed particles (sets their radius)")
    g.add_argument("--packing", choices=["RCP", "HCP", "Loose"], default="RCP",
                   help="the bed: RCP (settled random), HCP (a lattice) or Loose (poured with high friction, the loosest)")
    g.add_argument("--rolling-friction", type=float, default=0.35,
                   help="the DEM stage's rolling friction (DEMIntegrator's RollingFriction; 0.35 with the "
                        "other defaults gives the 30 degree heap); the bed settles with the defaults")
    g.add_argument("--bed-radius", type=float, default=0.0,
                   help="hemispherical container radius, m; 0: 1.05 x the predicted crater diameter "
                        "(the SCI study's 15 m bowl for a 14.5 m crater)")
    g.add_argument("--dem-time", type=float, default=0.0,
                   help="DEM time after the hand-off, s; 0: 1.5 sqrt(D/g) for the predicted D")
    g.add_argument("--frames", type=int, default=6, help="DEM outputs (progress and the crater's growth)")
    g.add_argument("--max-overlap", type=float, default=0.01, help="allowed overlap, fraction of a radius")
    g.add_argument("--checkpoint", default="", help="DEM checkpoint file; default OUTPUT_DIR/dem.ckdem (the SPH stage's is OUTPUT_DIR/sph.cksph)")
    g.add_argument("--dem-engine", choices=["craterkit", "lammps"], default="craterkit",
                   help="lammps: the DEM stage as a LAMMPS deck written from the hand-off by LAMMPSDeckWriter "
                        "(OUTPUT_DIR/lammps), run by scripts/run-lammps with MPI and read back from its dump "
                        "(docs/lammps.md); the DEM checkpoint and --resume of the DEM stage do not apply")
    g.add_argument("--lammps-ranks", type=int, default=2, help="MPI ranks of the LAMMPS run")
    g.add_argument("--lammps-timeout", type=float, default=None,
                   help="seconds after which the LAMMPS run is stopped with its MPI ranks (0: no limit); "
                        "default: CRATERKIT_LAMMPS_TIMEOUT, else 3600")
    g.add_argument("--resume", action="store_true", help="continue from the checkpoints: the SPH stage (or its saved hand-off state) and the DEM stage")
    p.add_argument("--output-dir", default="results/sci_crater")
    p.add_argument("--width", type=int, default=900, help="width of each picture panel in pixels")
    p.add_argument("--no-preset", action="store_true",
                   help="at Ryugu's gravity, keep these defaults instead of the validated set-up "
                        f"(the preset: {' '.join(sci.RYUGU_PRESET)}, each unless given)")
    args = p.parse_args(argv)
    args.preset = []
    if args.gravity == sci.RYUGU_GRAVITY and not args.no_preset:
        args.preset = apply_preset(p, argv, args, sci.RYUGU_PRESET)
    for name in ("impactor_mass", "impact_speed", "gravity"):
        value = getattr(args, name)
        if not (value > 0.0 and math.isfinite(value)):
            p.error(f"--{name.replace('_', '-')} must be positive (got {value})")
    for name in ("ejecta_speed_limit", "bed_radius", "dem_time", "handoff_time", "sph_target_radius",
                 "late_stage_sound_speed", "late_stage_initial_sound_speed", "cohesion", "rolling_friction"):
        value = getattr(args, name)
        if not (value >= 0.0 and math.isfinite(value)):
            p.error(f"--{name.replace('_', '-')} must not be negative (got {value})")
    if not (args.late_stage_poisson_ratio < 0.5 and math.isfinite(args.late_stage_poisson_ratio)):
        p.error(f"--late-stage-poisson-ratio must be below 0.5 (got {args.late_stage_poisson_ratio})")
    if not (0.0 < args.late_stage_sound_speed_exponent <= 2.0):
        p.error(f"--late-stage-sound-speed-exponent must be in (0, 2] (got {args.late_stage_sound_speed_exponent})")
    if not (0.0 < args.handoff_fraction <= 10.0):
        p.error(f"--handoff-fraction must be in (0, 10] (got {args.handoff_fraction})")
    if not (0 <= args.sph_block_steps <= 12):
        p.error(f"--sph-block-steps must be in [0, 12] (got {args.sph_block_steps})")
    if not (1.0 <= args.sph_coarsening <= 100.0):
        p.error(f"--sph-coarsening must be in [1, 100] (got {args.sph_coarsening})")
    if args.particles < 200:
        p.error(f"--particles must be at least 200 (got {args.particles})")
    if args.frames < 1:
        p.error("--frames must be at least 1")
    if args.lammps_ranks < 1:
        p.error("--lammps-ranks must be at least 1")
    if args.lammps_timeout is not None and not (args.lammps_timeout >= 0.0 and math.isfinite(args.lammps_timeout)):
        p.error(f"--lammps-timeout must not be negative (got {args.lammps_timeout})")
    return args


def given_options(p, argv):
    """The options argv sets itself, as {dest: value}: argv parsed again with no defaults."""
    defaults = {a: a.default for a in p._actions}
    for a in defaults:
        a.default = argparse.SUPPRESS
    try:
        return vars(p.parse_args(argv))
    finally:
        for a, value in defaults.items():
            a.default = value


def apply_preset(p, argv, args, preset):
    """Sets each option of preset (command-line words) that argv does not set; a hand-off
    fraction the user gives keeps its meaning (the preset's hand-off time would override it).
    Returns the preset's words that were applied."""
    given = given_options(p, argv)
    applied = []
    for dest, value in given_options(p, preset).items():
        if dest in given or (dest == "handoff_time" and "handoff_fraction" in given):
            continue
        setattr(args, dest, value)
        applied += ["--" + dest.replace("_", "-"), str(value)]
    return applied


def main(argv):
    args = parse_args(argv)
    if args.preset:
        sci.say("Ryugu's gravity: the validated set-up of slow.sci_ryugu_run (docs/validation.md), "
                f"{' '.join(args.preset)}; --no-preset keeps the general defaults")
    out = args.output_dir
    sph_to_run = not (args.sph_state or (args.resume and os.path.isfile(os.path.join(out, "sph_handoff.vtp"))))
    if args.dem_engine == "lammps" and sph_to_run:  # lmp, mpirun and the deck's styles, before the SPH stage
        from craterkit.lammps import LammpsError, check_lammps
        try:
            check_lammps()
        except LammpsError as error:
            sys.exit(f"--dem-engine lammps: {error}")
    os.makedirs(out, exist_ok=True)
    simple = load_plugin()
    sc = sci.scales(args.gravity, args.impactor_mass, args.impact_speed, args.impactor_material,
                    args.target_material, args.porosity, args.sph_target_radius, args.handoff_time,
                    args.handoff_fraction, args.late_stage_sound_speed, args.bed_radius, args.dem_time,
                    args.ejecta_speed_limit)
    sci.say(f"pi-scaling crater diameter for this run: {sc.d_pi:.3g} m (Ryugu gravity: {sc.d_ryugu:.3g} m); SPH "
            f"target radius {sc.sph_target_radius:.3g} m, hand-off at {sc.handoff_time:.3g} s, late-stage sound "
            f"speed {sc.late_stage_sound_speed:.3g} m/s; bowl radius {sc.bowl_radius:.3g} m, DEM time {sc.dem_time:.3g} s")
    run = SimpleNamespace(seconds={})
    clock = sci.stopwatch()
    sph, run.sph_data, run.handoff_time = sci.sph_stage(simple, args, sc, out)
    run.seconds["sph"] = clock()
    run.sph_totals, run.impactor_depth = sci.sph_summary(run.sph_data, sc, args.impactor_mass, args.impact_speed,
                                                         run.seconds["sph"])
    clock = sci.stopwatch()
    rest_speed = sci.dem_stiffness_speed(0.0, sc)  # the bed rests in the DEM stage's law (its least stiffness)
    bed, run.bed_data, run.surface, run.grain_radius = sci.bed_stage(simple, sc, args.packing, args.particles,
                                                                     dem_speed=rest_speed, max_overlap=args.max_overlap)
    run.seconds["bed"] = clock()
    run.bed_phi = field_value(run.bed_data, "BulkPackingFraction")
    sci.say(f"      {run.bed_data.GetNumberOfPoints()} particles, packing fraction {run.bed_phi:.3f}, surface at "
            f"{run.surface:.3g} m, {run.seconds['bed']} s")
    clock = sci.stopwatch()
    hand, run.dem0 = sci.handoff_stage(simple, sph, bed, sc)
    run.seconds["handoff"] = clock()
    vmax, run.carved = sci.handoff_summary(simple, hand, run.dem0, sc, run.surface)

    run.max_speed = sci.dem_stiffness_speed(vmax, sc)
    if run.max_speed > rest_speed:
        sci.say(f"      the DEM stage is stiffer than the law the bed came to rest in ({rest_speed:.3g} m/s): its "
                f"overlaps relax by a fraction {1 - rest_speed ** 2 / run.max_speed ** 2:.2f} in its first steps")
    run.t0 = field_value(run.dem0, "Time")
    r_min = min(run.dem0.GetPointData().GetArray("Radius").GetRange())
    sci.say(f"[4/5] DEM to {run.t0 + sc.dem_time:.3g} s with {run.dem0.GetNumberOfPoints()} particles (stiffness "
            f"for {run.max_speed:.3g} m/s and the smallest grain, r = {r_min:.3g} m; the bed's {run.grain_radius:.3g} m)")
    clock = sci.stopwatch()
    props = sci.dem_properties(args, sc, run.t0, run.max_speed)
    dem, frames, lammps_dt = sci.dem_stage(simple, args, sc, hand, run.t0, props, out)
    profile, run.growth = sci.run_dem(simple, args, sc, dem, frames, run.surface, run.grain_radius, out, lammps_dt)
    run.seconds["dem"] = clock()
    run.dem_data = fetch_stage(dem, "DEM stage", frames[-1])
    run.measures = sci.measure(profile, frames[-1])

    sci.say("[5/5] pictures and report")
    run.images = figures(simple, args, sc, run, sph, hand, dem, profile, frames[-1])
    report = sci.report_entries(args, sc, run)
    write_report(out, "the SCI impact, SPH to DEM", run.images[1], report, about=sci.about(args, sc, run),
                 validation=validation_summary(os.path.join(ROOT, "results", "validation.md")),
                 resolution=sci.report_resolution(run))
    with open(os.path.join(out, "report.md"), "a") as f:
        f.write(f"\n![hand-off]({run.images[0]})\n\n![profile]({run.images[2]})\n")
    m = run.measures
    length = lambda value: to_resolution(value, run.grain_radius)  # noqa: E731  (to a grain radius)
    sci.say(f"crater diameter {length(m['diameter'])} m ({m['diameter'] / sc.d_pi:.2f} x pi-scaling "
            f"{sc.d_pi:.3g} m), rim diameter {length(m['rim_diameter'])} m, depth {length(m['depth'])} m "
            f"({length(m['depth_below_rim'])} m below the rim crest)" if m["found"] else
            "no crater below the original surface at the end of the DEM stage")
    sci.say(f"wrote {out}/report.md, report.json, {', '.join(run.images)}")
    return 0


def figures(simple, args, sc, run, sph, hand, dem, profile, t_end):
    """The hand-off figure, the crater's cross-section and its profile plot; returns their names."""
    from craterkit.cross_section import render_cross_section
    from vtkmodules.util.numpy_support import vtk_to_numpy
    out = args.output_dir
    figure1 = handoff_figure(simple, sph, hand, run.handoff_time, os.path.join(out, "figure1_handoff.png"), args.width)
    final = simple.ForceTime(Input=dem, ForcedTime=t_end, IgnorePipelineTime=1)
    render_cross_section(final, os.path.join(out, "figure2_crater.png"), color_by="Height",
                         surface_height=run.surface, resolution=(2 * args.width, int(args.width * 9 / 16)),
                         label=f"{args.packing}, r = {run.grain_radius:.3g} m, N = {run.dem_data.GetNumberOfPoints()}, "
                               f"g = {args.gravity:g} m/s^2, t = {t_end:.3g} s "
                               f"(ejecta above {0.5 * sc.bowl_radius:.3g} m not drawn)",
                         measures=run.measures, max_height=0.5 * sc.bowl_radius)
    table = fetch(profile)
    rows = table.GetRowData() if table.IsA("vtkTable") else None
    radius = vtk_to_numpy(rows.GetArray("Radius")) if rows else []
    heights = vtk_to_numpy(rows.GetArray("Height")) if rows else []
    reference = dict(sci.SCI_CRATER) if args.gravity == sci.RYUGU_GRAVITY else {"name": "pi-scaling", "diameter": sc.d_pi}
    plot = profile_plot(radius, heights, os.path.join(out, "profile.png"), run.measures, reference,
                        title=f"crater profile at t = {t_end:.3g} s")
    return [os.path.basename(figure1), "figure2_crater.png", plot]


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""The Hayabusa2 SCI impact end to end: SPHImpact -> ImpactHandoff (a settled granular bed in a
hemispherical container) -> DEMIntegrator until the crater has settled -> CraterProfile, after
Zhang et al. (LPSC 2021). Writes under --output-dir: the velocity field before and after the
hand-off side by side (figure1_handoff.png), the crater cross-section with its measures
(figure2_crater.png), the profile plot (profile.png), and report.md / report.json with the
measured diameter, rim diameter and depth next to the SCI crater and the Housen & Holsapple
(2011) pi-scaling prediction for the run's own parameters, run times and conservation figures.

The SCI impactor (2 kg of copper at 2 km/s, vertical) and target (regolith of 1190 kg/m^3,
friction angle 30 degrees, no cohesion) are the defaults, and every parameter is an option.

Every length is set from the pi-scaling diameter D of the run's own impact and every time from
sqrt(D/g): the SPH target is 0.8 D in radius, the SPH stage switches to the late-stage scheme
after 1 ms and runs until 0.63 sqrt(D/g), when the crater has mostly opened (the hand-off must
not come too early: a DEM bed handed the 1 ms state, where only a few grains move fast, makes no
crater). At that late hand-off the crater is the SPH stage's and the DEM stage lets its walls
settle, so the bed's packing changes little; handed off while the crater still grows
(--handoff-time about 0.1 sqrt(D/g)), the DEM stage grows it and an HCP bed gives the smaller,
shallower crater with the lower rim (benchmarks/README.md, "packing against the hand-off
time"). The bed fills a bowl of radius 1.05 D; the DEM runs 1.5 sqrt(D/g) more. Material whose
ballistic flight comes down outside the bowl leaves the domain at the hand-off, so the DEM
stiffness is set by the grains that stay. Gravity decides what a run costs: the SPH target
holds (0.8 D / impactor radius)^3 particles, and D grows as g^-0.17. The default fires the SCI
impactor at g = 1000 m/s^2 (D = 1.0 m: 20,000 SPH particles, about 4 minutes on two cores with
6,000 grains); at Ryugu's 1.5e-4 m/s^2 (D = 14.5 m) a uniform SPH target would need 6e7
particles, a graded one (--sph-coarsening 10: the impactor's spacing near the impact point,
ten times coarser beyond 40 impactor radii) 67,762, whose late stage runs at steps of about
9 ms from 10 s on to the hand-off at 196 s (about 2.2e4 steps; benchmarks/README.md, "At
Ryugu's gravity", gives the command and the measured pace).
In the gravity regime crater shape and D / D_pi would be the same at any gravity, and the
validation (benchmarks/sci_crater/run.py) reads the SCI crater off the scaled result. The
project's runs (slow.pi_scaling, docs/validation.md) give D / D_pi within 15 % at g = 1000, 10 and
Ryugu's gravity, but depth / D changes with g (0.19 at g = 1000, 0.26 at Ryugu's).

--dem-engine lammps hands the DEM stage to LAMMPS (same bed, same hand-off, the deck written by
LAMMPSDeckWriter with the properties DEMIntegrator gets here, run by scripts/run-lammps with MPI,
the dump read back by the LAMMPS dump reader and measured by CraterProfile; docs/lammps.md).

    scripts/pvbatch examples/sci_crater.py --help
    scripts/pvbatch examples/sci_crater.py --dem-engine lammps --lammps-ranks 2
"""

import argparse
import json
import math
import os
import re
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkObject

from craterkit import fetch, fetch_stage, field_value, impactor_depth, load_plugin, material_value, print_progress
from craterkit.cross_section import crater_measures, render_cross_section
from craterkit.figures import handoff_figure, profile_plot
from craterkit.report import validation_summary, write_report
from craterkit.scaling import crater_diameter, formation_time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RYUGU_GRAVITY = 1.5e-4  # m/s^2, GM/R^2 at the mean radius (docs/physics.md 4.1)
SCI_CRATER = {"name": "SCI", "diameter": 14.5, "rim_diameter": 18.0, "depth": 2.3}  # m, Zhang et al. 2021
# The ejecta speed limit of Zhang et al. at Ryugu (1 m/s, three escape speeds) in units of the
# crater's own speed scale sqrt(g D); other gravities use the same ratio (Froude scaling).
EJECTA_LIMIT_RATIO = 1.0 / math.sqrt(RYUGU_GRAVITY * SCI_CRATER["diameter"])
PACKING_FRACTION = {"RCP": 0.60, "HCP": 0.74}  # for the grain density giving the target's bulk density


def say(message):
    print(message, flush=True)


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
                   help=f"surface gravity in m/s^2 (Ryugu: {RYUGU_GRAVITY}); see the module help for the cost")
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
    g.add_argument("--sph-block-steps", type=int, default=0,
                   help="individual power-of-two SPH time steps in the late stage, up to 2^L times the smallest "
                        "(SPHImpact's BlockStepLevels); 0: one step for all")
    g.add_argument("--late-stage-sound-speed", type=float, default=0.0,
                   help="m/s, of the late-stage scheme; 0: 10 sqrt(g D), ten times the crater's own speed scale")
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
    g.add_argument("--packing", choices=["RCP", "HCP"], default="RCP")
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
    g.add_argument("--resume", action="store_true", help="continue from the checkpoints: the SPH stage (or its saved hand-off state) and the DEM stage")
    p.add_argument("--output-dir", default="results/sci_crater")
    p.add_argument("--width", type=int, default=900, help="width of each picture panel in pixels")
    args = p.parse_args(argv)
    for name in ("impactor_mass", "impact_speed", "gravity"):
        value = getattr(args, name)
        if not (value > 0.0 and math.isfinite(value)):
            p.error(f"--{name.replace('_', '-')} must be positive (got {value})")
    for name in ("ejecta_speed_limit", "bed_radius", "dem_time", "handoff_time", "sph_target_radius",
                 "late_stage_sound_speed", "cohesion", "rolling_friction"):
        value = getattr(args, name)
        if not (value >= 0.0 and math.isfinite(value)):
            p.error(f"--{name.replace('_', '-')} must not be negative (got {value})")
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
    return args


def saved_sph_state(simple, args):
    """The SPH state a run saved at its hand-off (sph_handoff.vtp), checked against this run's
    impact and gravity, which must be the same."""
    if not os.path.isfile(args.sph_state):
        sys.exit(f"--sph-state {args.sph_state}: no such file")
    say(f"[1/5] SPH state from {args.sph_state}")
    sph = simple.XMLPolyDataReader(FileName=[args.sph_state])
    data = fetch(sph)
    fd = data.GetFieldData()
    for name in ("Time", "ImpactSpeed", "Gravity", "ImpactorMaterial", "TargetRadius"):
        if fd.GetAbstractArray(name) is None:
            sys.exit(f"--sph-state {args.sph_state}: not an SPHImpact state (no {name} field)")
    gravity = abs(fd.GetArray("Gravity").GetTuple3(0)[2])
    if abs(gravity - args.gravity) > 1e-6 * args.gravity:
        sys.exit(f"--sph-state {args.sph_state}: its gravity is {gravity:g} m/s^2, this run's {args.gravity:g}")
    material = field_value(data, "ImpactorMaterial")
    if material != args.impactor_material:
        sys.exit(f"--sph-state {args.sph_state}: its impactor is {material}, this run's {args.impactor_material}")
    speed = field_value(data, "ImpactSpeed")
    if abs(speed - args.impact_speed) > 1e-6 * args.impact_speed:
        sys.exit(f"--sph-state {args.sph_state}: its impact speed is {speed:g} m/s, this run's {args.impact_speed:g}")
    mass = field_value(data, "ImpactorMass")
    if mass is not None and abs(mass - args.impactor_mass) > 1e-6 * args.impactor_mass:
        sys.exit(f"--sph-state {args.sph_state}: its impactor mass is {mass:g} kg, this run's {args.impactor_mass:g}")
    target = field_value(data, "TargetMaterial")
    if target is not None and target != args.target_material:
        sys.exit(f"--sph-state {args.sph_state}: its target is {target}, this run's {args.target_material}")
    for name, ours, what in (("FrictionAngle", args.friction_angle, "friction angle"),
                             ("Cohesion", args.cohesion, "target cohesion"),
                             ("TargetRadius", args.sph_target_radius, "SPH target radius"),
                             ("TargetCoarsening", args.sph_coarsening, "SPH target coarsening")):
        theirs = field_value(data, name)
        if theirs is not None and abs(theirs - ours) > 1e-6 * max(abs(ours), 1e-12):
            sys.exit(f"--sph-state {args.sph_state}: its {what} is {theirs:g}, this run's {ours:g}")
    time_saved = field_value(data, "Time")
    if args.handoff_given and abs(time_saved - args.handoff_time) > 1e-9 * args.handoff_time:
        sys.exit(f"--sph-state {args.sph_state}: it is at t = {time_saved:g} s, this run hands off at "
                 f"--handoff-time {args.handoff_time:g} s")
    return sph, data, time_saved


def lammps_stage(simple, args, hand, t0, props):
    """The DEM stage on LAMMPS: the hand-off written as a deck with DEMIntegrator's properties
    PROPS (so the same walls, gravity, stiffness and step), run with MPI, and its dump read back
    on the pipeline's clock (the deck counts time from the hand-off, t0). Returns the source of
    the DEM states, their times and the deck's step."""
    from craterkit.lammps import lammps_available, read_lammps_dump, run_lammps, write_lammps_deck
    if not lammps_available():
        sys.exit("--dem-engine lammps: LAMMPS (lmp) or mpirun is not installed (Debian: apt-get install lammps)")
    deck = os.path.join(args.output_dir, "lammps")
    write_lammps_deck(simple, hand, deck, **props)
    dt = float(re.search(r"^timestep (\S+)", open(os.path.join(deck, "in.craterkit")).read(), re.M).group(1))
    say(f"      LAMMPS deck {deck}/in.craterkit, time step {dt:.3g} s; running on {args.lammps_ranks} MPI ranks")
    try:
        dump = run_lammps(deck, args.lammps_ranks)
    except RuntimeError as error:
        sys.exit(f"--dem-engine lammps: {error}")
    reader, times = read_lammps_dump(simple, dump)
    return simple.TemporalShiftScale(Input=reader, PostShift=t0), [t0 + tau for tau in times], dt


def steps_of(data):
    """The step count of a DEM state: DEMIntegrator's Step field, or the LAMMPS dump's step
    (the reader's TimeStep field; DEMIntegrator's TimeStep is its step length)."""
    step = field_value(data, "Step")
    return int(step if step is not None else field_value(data, "TimeStep"))


def speeds(data):
    v = vtk_to_numpy(data.GetPointData().GetArray("Velocity"))
    return np.linalg.norm(v, axis=1)


def totals(data, grain_radius=None):
    """Mass, momentum and kinetic energy of a particle set; with grain_radius, also the kinetic
    energy of the bed (particles below one grain diameter above the original surface z = 0)
    apart from the ejecta in flight above it, and their number."""
    pd = data.GetPointData()
    m = vtk_to_numpy(pd.GetArray("Mass"))
    v = vtk_to_numpy(pd.GetArray("Velocity"))
    ke = 0.5 * m * (v * v).sum(axis=1)
    out = {"mass_kg": float(m.sum()), "momentum_kg_m_s": [float(x) for x in (m[:, None] * v).sum(axis=0)],
           "kinetic_energy_J": float(ke.sum())}
    if grain_radius is not None:
        flying = vtk_to_numpy(data.GetPoints().GetData())[:, 2] > 2.0 * grain_radius
        out["bed_kinetic_energy_J"] = float(ke[~flying].sum())
        out["ejecta_in_flight"] = int(flying.sum())
    return out


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    simple = load_plugin()
    seconds = {}
    report = {"example": "sci_crater"}

    rho_imp = material_value(args.impactor_material, "rho0")
    rho_matrix = material_value(args.target_material, "rho0")
    porosity = args.porosity if args.porosity >= 0.0 else \
        1.0 - 1.0 / material_value(args.target_material, "distention", 1.0)
    rho_bulk = rho_matrix * (1.0 - porosity)
    # The pi-scaling prediction for the run's own parameters sets the SPH target, the hand-off
    # time, the bowl, the DEM time and the ejecta limit unless they are given: every length
    # scales with D and every time with sqrt(D/g).
    d_pi = crater_diameter(args.impactor_mass, args.impact_speed, rho_imp, rho_bulk, args.gravity)
    d_sci = crater_diameter(args.impactor_mass, args.impact_speed, rho_imp, rho_bulk, RYUGU_GRAVITY)
    t_scale = formation_time(d_pi, args.gravity)
    args.sph_target_radius = args.sph_target_radius or 0.8 * d_pi
    args.handoff_given = args.handoff_time > 0.0
    args.handoff_time = args.handoff_time or args.handoff_fraction * t_scale
    args.late_stage_sound_speed = args.late_stage_sound_speed or 10.0 * math.sqrt(args.gravity * d_pi)
    bed_radius = args.bed_radius or 1.05 * d_pi
    dem_time = args.dem_time or 1.5 * t_scale
    v_lim = args.ejecta_speed_limit or EJECTA_LIMIT_RATIO * math.sqrt(args.gravity * d_pi)
    say(f"pi-scaling crater diameter for this run: {d_pi:.3g} m (Ryugu gravity: {d_sci:.3g} m); SPH target radius "
        f"{args.sph_target_radius:.3g} m, hand-off at {args.handoff_time:.3g} s, late-stage sound speed "
        f"{args.late_stage_sound_speed:.3g} m/s; bowl radius {bed_radius:.3g} m, DEM time {dem_time:.3g} s")
    start = time.time()
    saved_handoff = os.path.join(args.output_dir, "sph_handoff.vtp")
    if args.resume and not args.sph_state and os.path.isfile(saved_handoff):
        args.sph_state = saved_handoff  # this run's SPH stage is done
    if args.sph_state:
        sph, sph_data, args.handoff_time = saved_sph_state(simple, args)
    else:
        # The SPH stage checkpoints every 200 steps; --resume goes on from there. A run that
        # does not resume first removes what an earlier run in this folder left.
        sph_checkpoint = os.path.join(args.output_dir, "sph.cksph")
        sph_resume = args.resume and os.path.isfile(sph_checkpoint)
        if not args.resume:
            for stale in (sph_checkpoint, saved_handoff):
                if os.path.exists(stale):
                    os.remove(stale)
        sph = simple.SPHImpact(ImpactorMaterial=args.impactor_material, ImpactorMass=args.impactor_mass,
                               ImpactSpeed=args.impact_speed, TargetMaterial=args.target_material,
                               TargetPorosity=args.porosity, FrictionAngle=args.friction_angle, Cohesion=args.cohesion,
                               SurfaceGravity=args.gravity, ParticlesAcrossImpactor=args.sph_resolution,
                               TargetRadius=args.sph_target_radius, TargetCoarsening=args.sph_coarsening,
                               TargetContainer=1,
                               LateStageTime=args.late_stage_time, LateStageSoundSpeed=args.late_stage_sound_speed,
                               BlockStepLevels=args.sph_block_steps,
                               DomainRadius=args.sph_domain_radius,
                               EndTime=args.handoff_time, OutputInterval=args.handoff_time,
                               CheckpointFile=sph_checkpoint, CheckpointInterval=200,
                               ResumeFromCheckpoint=1 if sph_resume else 0)
        say(f"[1/5] SPH impact to {args.handoff_time:.2e} s" + (f" (resumed from {sph_checkpoint})" if sph_resume else ""))
        print_progress(sph, "SPH stage")
        sph_data = fetch_stage(sph, "SPH stage", args.handoff_time)
        # Saved so that other beds can be tried on the same SPH stage (--sph-state).
        state = simple.ForceTime(Input=sph, ForcedTime=args.handoff_time, IgnorePipelineTime=1)
        simple.XMLPolyDataWriter(Input=state, FileName=saved_handoff).UpdatePipeline(args.handoff_time)
    seconds["sph"] = round(time.time() - start, 1)
    phi = PACKING_FRACTION[args.packing]
    grain_radius = bed_radius * (phi / (2.0 * args.particles)) ** (1.0 / 3.0)
    sph_tot = totals(sph_data)
    s = speeds(sph_data)
    # The impactor's track at the hand-off: at g = 1000 and 100 it is 0.4 of D_pi and the
    # crater's floor lies at 0.6-0.9 of its depth (benchmarks/README.md, "What sets the depth").
    track = impactor_depth(sph_data)
    penetration = {k: None if track[k] is None else round(track[k], 4) for k in ("centre_of_mass_m", "deepest_m")}
    say(f"      {sph_data.GetNumberOfPoints()} SPH particles, {int(field_value(sph_data, 'Step'))} steps, "
        f"{seconds['sph']} s; kinetic energy {sph_tot['kinetic_energy_J']:.3g} J "
        f"({sph_tot['kinetic_energy_J'] / (0.5 * args.impactor_mass * args.impact_speed ** 2):.2%} of the impact's); "
        f"{int((s > v_lim).sum())} particles faster than the ejecta limit {v_lim:.3g} m/s; the impactor's "
        f"centre of mass {penetration['centre_of_mass_m']} m below the surface")

    say(f"[2/5] {args.packing} bed of about {args.particles} grains of radius {grain_radius:.3g} m settled at "
        f"g = {args.gravity:g} m/s^2")
    start = time.time()
    bed = simple.GranularBed(Packing=args.packing, Container="Bowl", ContainerRadius=bed_radius,
                             ParticleRadius=grain_radius, SurfaceHeight=0.0, ParticleDensity=rho_bulk / phi,
                             SettlingGravity=args.gravity, MaxParticles=max(10 * args.particles, 100000))
    print_progress(bed, "bed")
    bed_data = fetch_stage(bed, "bed")
    seconds["bed"] = round(time.time() - start, 1)
    bed_phi = field_value(bed_data, "BulkPackingFraction")
    # The pre-impact surface as the crater is measured against: the settled bed's own top (the
    # mean height of its profile), not the height it was trimmed at, which lies above the tops
    # of most surface grains.
    vtkObject.GlobalWarningDisplayOff()  # a flat bed has no crater: CraterProfile would say so
    bed_table = fetch(simple.CraterProfile(Input=bed))
    vtkObject.GlobalWarningDisplayOn()
    bed_heights = vtk_to_numpy(bed_table.GetRowData().GetArray("Height"))
    surface = float(np.nanmean(bed_heights))
    say(f"      {bed_data.GetNumberOfPoints()} particles, packing fraction {bed_phi:.3f}, surface at {surface:.3g} m, "
        f"{seconds['bed']} s")

    say(f"[3/5] hand-off (ejecta faster than {v_lim:.3g} m/s, and material coming down outside the bowl, leave "
        f"the domain)")
    start = time.time()
    hand = simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=v_lim, EjectaParticles="Dropped")
    dem0 = fetch_stage(hand, "hand-off")
    seconds["handoff"] = round(time.time() - start, 1)
    fd = dem0.GetFieldData()
    vec = lambda name: [float(x) for x in fd.GetArray(name).GetTuple3(0)]  # noqa: E731
    dem0_tot = totals(dem0, grain_radius)
    vmax_dem = float(speeds(dem0).max())
    # The bed takes over the compact material below the original surface; what lies above it
    # (the curtain) comes in as particles of its own.
    below_z = vec("SPHCompactMomentum")[2] - vec("SPHCurtainMomentum")[2]
    say(f"      {dem0.GetNumberOfPoints()} DEM particles, {int(field_value(dem0, 'BedRemoved'))} carved; "
        f"momentum (z) mapped onto the bed {vec('DEMMappedMomentum')[2]:.4g} kg m/s (the compact SPH material's "
        f"below the surface: {below_z:.4g}), in the curtain above it {vec('SPHCurtainMomentum')[2]:.4g}; "
        f"{int(field_value(dem0, 'CurtainCount'))} SPH particles above the surface, of which "
        f"{int(field_value(dem0, 'EscapedCount'))} ({field_value(dem0, 'SPHEscapedMass'):.3g} kg) land outside the bowl; "
        f"{int(field_value(dem0, 'LoneDroppedCount'))} lone curtain pieces lighter than half a grain "
        f"({field_value(dem0, 'SPHLoneDroppedMass'):.3g} kg) dropped; "
        f"fastest DEM particle {vmax_dem:.3g} m/s")

    at_handoff = crater_measures(simple.CraterProfile(Input=hand, SurfaceFromInput=0, SurfaceHeight=surface))
    if at_handoff["found"]:
        say(f"      crater carved at the hand-off: diameter {at_handoff['diameter']:.3g} m "
            f"({at_handoff['diameter'] / d_pi:.2f} of pi-scaling), depth {at_handoff['depth']:.3g} m")

    # The DEM stiffness is set for the fastest particle the hand-off produced, with a margin
    # (an overlap grows as the speed: 1.5 times faster gives 1.5 % of a radius, pkdgrav's
    # minor-warning level is 3 %); what comes down outside the bowl has left, so the fastest
    # are the bed's own grains and the curtain landing in the bowl. A bed nearly at rest gets
    # half the crater's speed scale sqrt(g D).
    max_speed = max(1.5 * vmax_dem, 0.5 * math.sqrt(args.gravity * d_pi))
    t0 = field_value(dem0, "Time")
    r_min = float(vtk_to_numpy(dem0.GetPointData().GetArray("Radius")).min())
    say(f"[4/5] DEM to {t0 + dem_time:.3g} s with {dem0.GetNumberOfPoints()} particles "
        f"(stiffness for {max_speed:.3g} m/s and the smallest grain, r = {r_min:.3g} m; the bed's {grain_radius:.3g} m)")
    checkpoint = args.checkpoint or os.path.join(args.output_dir, "dem.ckdem")
    frames = [t0 + dem_time * (k + 1) / args.frames for k in range(args.frames)]
    dem_props = dict(Container="FromInput", GravityModel="Uniform", SurfaceGravity=[0.0, 0.0, -args.gravity],
                     MaxExpectedSpeed=max_speed, MaxOverlap=args.max_overlap, EndTime=frames[-1],
                     OutputInterval=dem_time / args.frames, RollingFriction=args.rolling_friction)
    start = time.time()
    lammps_dt = None
    if args.dem_engine == "lammps":
        # The same set-up as DEMIntegrator's below; the frames are the dump's own times.
        dem, frames, lammps_dt = lammps_stage(simple, args, hand, t0, dem_props)
    else:
        dem = simple.DEMIntegrator(Input=hand, KeptStates=0, CheckpointFile=checkpoint, CheckpointInterval=20000,
                                   ResumeFromCheckpoint=1 if args.resume else 0, **dem_props)
    profile = simple.CraterProfile(Input=dem, SurfaceFromInput=0, SurfaceHeight=surface)
    # Each frame's measures are saved as it completes, and each requested frame leaves its
    # state in the checkpoint: --resume goes on from the first frame not yet done.
    growth_file = os.path.join(args.output_dir, "dem_growth.json")
    growth = []
    if args.resume and args.dem_engine == "craterkit" and os.path.exists(growth_file) and os.path.exists(checkpoint):
        growth = [g for g in json.load(open(growth_file)) if g["time_s"] <= frames[-1]]
        if growth:
            say(f"      resuming after t = {growth[-1]['time_s']:.4g} s ({len(growth)} frames done)")
    step_told = False
    for t in frames:
        if any(abs(g["time_s"] - t) <= 1e-9 * max(1.0, t) for g in growth):
            continue
        data = fetch_stage(dem, "DEM stage", t)
        if not step_told:
            # The integrator's own choice (chooseStiffnessAndStep), read from its output (the
            # deck holds the same choice).
            dt = lammps_dt or field_value(data, "TimeStep")
            say(f"      time step {dt:.3g} s: about {dem_time / dt:.3g} steps in all")
            step_told = True
        m = crater_measures(profile, t)
        now = totals(data, grain_radius)
        growth.append({"time_s": t, "diameter_m": m["diameter"] if m["found"] else 0.0, "depth_m": m["depth"],
                       "bed_kinetic_energy_J": now["bed_kinetic_energy_J"],
                       "ejecta_in_flight": now["ejecta_in_flight"]})
        say(f"      t = {t:.4g} s, {steps_of(data)} steps, {time.time() - start:.0f} s: "
            f"crater diameter {growth[-1]['diameter_m']:.3g} m, depth {m['depth']:.3g} m; bed kinetic energy "
            f"{now['bed_kinetic_energy_J']:.3g} J, {now['ejecta_in_flight']} ejecta in flight")
        with open(growth_file + ".part", "w") as f:  # replaced whole: a killed run leaves the last one
            json.dump(growth, f)
        os.replace(growth_file + ".part", growth_file)
    seconds["dem"] = round(time.time() - start, 1)
    dem_data = fetch_stage(dem, "DEM stage", frames[-1])
    measures = crater_measures(profile, frames[-1])

    say("[5/5] pictures and report")
    height = int(args.width * 9 / 16)
    figure1 = handoff_figure(simple, sph, hand, args.handoff_time,
                             os.path.join(args.output_dir, "figure1_handoff.png"), args.width)
    final = simple.ForceTime(Input=dem, ForcedTime=frames[-1], IgnorePipelineTime=1)
    figure2 = os.path.join(args.output_dir, "figure2_crater.png")
    render_cross_section(final, figure2, color_by="Height", surface_height=surface,
                         resolution=(2 * args.width, height),
                         label=f"{args.packing}, r = {grain_radius:.3g} m, N = {dem_data.GetNumberOfPoints()}, "
                               f"g = {args.gravity:g} m/s^2, t = {frames[-1]:.3g} s "
                               f"(ejecta above {0.5 * bed_radius:.3g} m not drawn)",
                         measures=measures, max_height=0.5 * bed_radius)
    table = fetch(profile)
    radius = vtk_to_numpy(table.GetRowData().GetArray("Radius")) if table.IsA("vtkTable") else []
    heights = vtk_to_numpy(table.GetRowData().GetArray("Height")) if table.IsA("vtkTable") else []
    reference = dict(SCI_CRATER) if args.gravity == RYUGU_GRAVITY else {"name": "pi-scaling", "diameter": d_pi}
    profile_png = profile_plot(radius, heights, os.path.join(args.output_dir, "profile.png"), measures, reference,
                               title=f"crater profile at t = {frames[-1]:.3g} s")

    dem_tot = totals(dem_data, grain_radius)
    found = measures["found"]
    report.update({
        "gravity_m_s2": args.gravity,
        "impactor": {"material": args.impactor_material, "mass_kg": args.impactor_mass,
                     "speed_m_s": args.impact_speed, "density_kg_m3": rho_imp},
        "target": {"material": args.target_material, "bulk_density_kg_m3": round(rho_bulk, 1),
                   "porosity": round(porosity, 4), "friction_angle_deg": args.friction_angle,
                   "dem_rolling_friction": args.rolling_friction,
                   "cohesion_pa": args.cohesion},
        "crater_diameter_m": measures["diameter"] if found else None,
        "rim_diameter_m": measures["rim_diameter"] if found else None,
        "crater_depth_m": measures["depth"] if found else None,
        "rim_height_m": measures["rim_height"] if found else None,
        "pi_scaling_diameter_m": round(d_pi, 4),
        "diameter_over_pi_scaling": round(measures["diameter"] / d_pi, 3) if found else None,
        "pi_scaling_diameter_at_ryugu_m": round(d_sci, 3),
        # Read at Ryugu's gravity by pi-scaling: D scales with D_pi, the shape stays.
        "scaled_to_ryugu_m": ({"diameter": d_sci * measures["diameter"] / d_pi,
                               "rim_diameter": d_sci * measures["rim_diameter"] / d_pi,
                               "depth": d_sci * measures["depth"] / d_pi} if found else None),
        "sci_crater_m": SCI_CRATER,
        "sph_particles": sph_data.GetNumberOfPoints(),
        "sph_resolution": args.sph_resolution,
        "sph_target_coarsening": args.sph_coarsening,
        "handoff_time_s": args.handoff_time,
        "impactor_depth_at_handoff_m": penetration,
        "ejecta_speed_limit_m_s": round(v_lim, 4),
        "sph_totals_at_handoff": sph_tot,
        "sph_ejecta_dropped": {"mass_kg": field_value(dem0, "SPHEjectaMass"), "momentum_kg_m_s": vec("SPHEjectaMomentum")},
        "sph_compact_momentum_kg_m_s": vec("SPHCompactMomentum"),
        "dem_mapped_momentum_kg_m_s": vec("DEMMappedMomentum"),
        "sph_curtain_momentum_kg_m_s": vec("SPHCurtainMomentum"),
        "sph_escaped": {"particles": int(field_value(dem0, "EscapedCount")), "mass_kg": field_value(dem0, "SPHEscapedMass"),
                        "momentum_kg_m_s": vec("SPHEscapedMomentum")},
        "sph_lone_pieces_dropped": {"pieces": int(field_value(dem0, "LoneDroppedCount")),
                                    "mass_kg": field_value(dem0, "SPHLoneDroppedMass"),
                                    "momentum_kg_m_s": vec("SPHLoneDroppedMomentum")},
        "curtain_particles": int(field_value(dem0, "CurtainCount")),
        "sph_compact_angular_momentum": vec("SPHCompactAngularMomentum"),
        "dem_mapped_angular_momentum": vec("DEMMappedAngularMomentum"),
        "compact_mass_ratio_dem_to_sph": field_value(dem0, "CompactMassRatio"),
        "packing": args.packing,
        "bed_particles": bed_data.GetNumberOfPoints(),
        "bed_packing_fraction": bed_phi,
        "bed_surface_m": round(surface, 5),
        "grain_radius_m": round(grain_radius, 5),
        "bowl_radius_m": round(bed_radius, 4),
        "bed_carved": int(field_value(dem0, "BedRemoved")),
        "crater_at_handoff": {"diameter_m": at_handoff["diameter"] if at_handoff["found"] else None,
                              "depth_m": at_handoff["depth"] if at_handoff["found"] else None,
                              "rim_diameter_m": at_handoff["rim_diameter"] if at_handoff["found"] else None},
        "dem_totals_after_handoff": dem0_tot,
        "dem_max_expected_speed_m_s": round(max_speed, 3),
        "dem_engine": args.dem_engine,
        "dem_end_time_s": field_value(dem_data, "Time") + (t0 if args.dem_engine == "lammps" else 0.0),
        "dem_steps": steps_of(dem_data),
        "dem_totals_at_end": dem_tot,
        "crater_growth": growth,
        "seconds": seconds,
        "images": [os.path.basename(figure1), os.path.basename(figure2), profile_png],
    })
    across = measures["diameter"] / (2.0 * grain_radius) if found else 0.0
    about = (f"**What this run is.** The SCI impactor ({args.impactor_mass:g} kg of {args.impactor_material} at "
             f"{args.impact_speed:g} m/s) into {args.target_material} under g = {args.gravity:g} m/s^2"
             + (" (Ryugu's gravity)" if args.gravity == RYUGU_GRAVITY else
                f", not Ryugu's {RYUGU_GRAVITY:g} m/s^2: the crater is {d_pi:.3g} m by pi-scaling instead of "
                f"{d_sci:.3g} m, so that the run fits minutes") +
             f". SPH stage: {sph_data.GetNumberOfPoints():,} particles; DEM bed: "
             f"{bed_data.GetNumberOfPoints():,} {args.packing} grains of radius {grain_radius:.3g} m"
             + (f", its DEM stage run by LAMMPS on {args.lammps_ranks} MPI ranks from the deck in lammps/. "
                if args.dem_engine == "lammps" else ". ")
             + (f"The crater is {measures['diameter']:.3g} m wide ({across:.0f} grain diameters) and "
                f"{measures['depth']:.3g} m deep ({measures['depth'] / (2.0 * grain_radius):.1f} grain diameters), "
                f"{measures['diameter'] / d_pi:.2f} of the pi-scaling diameter {d_pi:.3g} m; its depth is "
                f"{measures['depth'] / measures['diameter']:.2f} of its diameter (SCI crater: "
                f"{SCI_CRATER['depth'] / SCI_CRATER['diameter']:.2f})."
                if found else f"It leaves no crater below the original surface; pi-scaling predicts {d_pi:.3g} m.")
             + ("" if args.gravity == RYUGU_GRAVITY else
                " This is not a measurement of the SCI crater: the project's runs give D / D_pi within 15 % "
                "from g = 1000 to Ryugu's gravity, but depth / D changes with g (slow.pi_scaling, "
                "docs/validation.md); report.json's scaled_to_ryugu_m is that pi-scaling arithmetic.")
             + (" A crater a few grains across tests the pipeline, not the physics." if found and across < 20 else ""))
    table = os.path.join(ROOT, "results", "validation.md")
    write_report(args.output_dir, "the SCI impact, SPH to DEM", os.path.basename(figure2), report,
                 about=about, validation=validation_summary(table))
    with open(os.path.join(args.output_dir, "report.md"), "a") as f:
        f.write(f"\n![hand-off]({os.path.basename(figure1)})\n\n![profile]({profile_png})\n")
    if found:
        say(f"crater diameter {measures['diameter']:.3g} m ({measures['diameter'] / d_pi:.2f} x pi-scaling "
            f"{d_pi:.3g} m), rim diameter {measures['rim_diameter']:.3g} m, depth {measures['depth']:.3g} m")
    else:
        say("no crater below the original surface at the end of the DEM stage")
    say(f"wrote {args.output_dir}/report.md, report.json, {os.path.basename(figure1)}, "
        f"{os.path.basename(figure2)}, {profile_png}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

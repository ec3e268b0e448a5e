"""The Hayabusa2 SCI impact on Ryugu, one room for the case: the reference crater (each number
with its definition and source), Ryugu's gravity and the beds' packing fractions, `scales()`
(every length of a run from its pi-scaling diameter D_pi, every time from sqrt(D_pi / g)), one
builder per stage (SPH, bed, hand-off, DEM on CraterKit or on LAMMPS) and `measure()`.

    from craterkit import load_plugin, sci
    simple = load_plugin()
    sc = sci.scales(gravity=sci.RYUGU_GRAVITY)          # D_pi 14.5 m, hand-off time, bowl, ...
    bed = sci.bed_stage(simple, sc, packing="RCP", particles=30000)

examples/sci_crater.py runs the whole case; benchmarks/sci_crater/ and tests/slow/validate.py
import the reference and the set-ups from here. docs/validation.md compares the results.
"""

import math
import os
import sys
import time
from dataclasses import dataclass

from . import fetch, fetch_stage, field_value, material_value, print_progress
from .scaling import crater_diameter, formation_time

# --- the reference -------------------------------------------------------------------------

RYUGU_GRAVITY = 1.5e-4  # m/s^2, GM/R^2 at Ryugu's mean radius (docs/physics.md, section 4.1)

# The SCI crater on Ryugu (Arakawa et al. 2020, Science 368:67, as quoted by Zhang et al., LPSC
# 2021). "definition" says what each number measures; "source" whether it is read first-hand.
SCI_CRATER = {"name": "SCI", "diameter": 14.5, "rim_diameter": 18.0, "depth": 2.3}  # m
SCI_CRATER_DEFINITIONS = {
    "diameter": ("apparent diameter at the pre-impact surface level, azimuthal mean",
                 "Arakawa et al. 2020 as quoted by Zhang et al. 2021 (secondary)"),
    "rim_diameter": ("diameter of the rim crest, azimuthal mean (about 18 m)",
                     "Arakawa et al. 2020 as quoted by Zhang et al. 2021 (secondary)"),
    "depth": ("depth of the floor (about 2.3 m); whether below the pre-impact surface or below the "
              "rim crest is not stated by the quoting source", "Zhang et al. 2021 (secondary)"),
}

# The SCI impact: 2 kg of copper at 2 km/s, vertical, into regolith of friction angle 30 degrees.
SCI_IMPACT = {"mass": 2.0, "speed": 2000.0, "impactor": "copper", "target": "regolith",
              "friction_angle": 30.0}

# The beds' packing fractions, for the grain density that gives the target's bulk density
# (Loose: GranularBed's loose box bed measured 0.5796, BedAtRest.LooseBedIsLooserAndCarriesItsWeight).
PACKING_FRACTION = {"RCP": 0.60, "HCP": 0.74, "Loose": 0.58}

# The ejecta speed limit of Zhang et al. at Ryugu (1 m/s, three escape speeds) in units of the
# crater's own speed scale sqrt(g D); other gravities use the same ratio (Froude scaling).
EJECTA_LIMIT_RATIO = 1.0 / math.sqrt(RYUGU_GRAVITY * SCI_CRATER["diameter"])

# The validation's SPH stage at Ryugu's gravity, as examples/sci_crater.py options. The graded
# SPH target at coarsening 10 (coarse spacing 0.38 m), with individual
# time steps in its late stage (2^7 of the smallest at most) and partial list rebuilds, handed off
# at 29.5 s (0.095 sqrt(D_pi/g)) while the crater still grows, so that the DEM stage grows it (as in
# the hybrid method of Zhang et al. 2021). Up to about 40 s the SPH cavity is converged in the resolution (its floor
# within 0.13 m between coarsening 10 and 8); handed off at 0.63 sqrt(D_pi/g) (196 s, the example's
# default) the crater's depth was the SPH late stage's, which is not converged: the target under the
# floor dilates to 0.17-0.6 of its bulk density and rises by 1.3 m at coarsening 10 and 3.7 m at 8
# (docs/validation_history.md, "Depth and the SPH resolution", points 7, 8 and 12).
RYUGU_VALIDATION_STAGE = ["--sph-coarsening", "10", "--sph-domain-radius", "29", "--sph-target-radius", "11.6",
                          "--late-stage-sound-speed", "0.46637", "--sph-block-steps", "7",
                          "--handoff-time", "29.5"]
# examples/sci_crater.py at Ryugu's gravity: the validation's SPH stage and its bed (slow.sci_ryugu_run),
# each option unless the user gives it.
RYUGU_PRESET = RYUGU_VALIDATION_STAGE + ["--particles", "30000", "--packing", "RCP"]
# The same hand-off in units of sqrt(D_pi / g), for the runs at other gravities.
VALIDATION_HANDOFF_FRACTION = 0.095


def say(message):
    print(message, flush=True)


class expected_warnings:
    """A block whose VTK warnings are expected and not shown (a flat bed, or a crater still
    forming, has no crater rim: CraterProfile says so). ParaView prints warnings through VTK's
    logger, which vtkObject.GlobalWarningDisplayOff does not silence; its stderr verbosity does."""

    def __enter__(self):
        from vtkmodules.vtkCommonCore import vtkLogger
        self.saved = vtkLogger.GetCurrentVerbosityCutoff()
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)

    def __exit__(self, *exc):
        from vtkmodules.vtkCommonCore import vtkLogger
        vtkLogger.SetStderrVerbosity(self.saved)
        return False


# --- the scales ----------------------------------------------------------------------------

@dataclass
class Scales:
    """A run's scales: densities, the pi-scaling diameters, and the set-up they fix."""
    gravity: float
    rho_impactor: float
    rho_bulk: float
    porosity: float
    d_pi: float  # m, pi-scaling diameter of this run's impact
    d_ryugu: float  # m, the same impact's at Ryugu's gravity
    t_scale: float  # s, sqrt(D_pi / g)
    sph_target_radius: float
    handoff_time: float
    late_stage_sound_speed: float
    bowl_radius: float
    dem_time: float
    ejecta_limit: float

    def grain_radius(self, particles, packing):
        """The radius of grains of which PARTICLES fill the bowl at the packing's fraction."""
        return self.bowl_radius * (PACKING_FRACTION[packing] / (2.0 * particles)) ** (1.0 / 3.0)


def scales(gravity, mass=SCI_IMPACT["mass"], speed=SCI_IMPACT["speed"], impactor=SCI_IMPACT["impactor"],
           target=SCI_IMPACT["target"], porosity=-1.0, sph_target_radius=0.0, handoff_time=0.0,
           handoff_fraction=0.63, late_stage_sound_speed=0.0, bowl_radius=0.0, dem_time=0.0,
           ejecta_speed_limit=0.0):
    """The pi-scaling prediction D_pi for the impact sets every length not given (0): the SPH
    target 0.8 D_pi, the bowl 1.05 D_pi (the SCI study's 15 m bowl for a 14.5 m crater); and every
    time from sqrt(D_pi / g): the hand-off at HANDOFF_FRACTION of it, the DEM stage 1.5 of it; the
    late stage's sound speed is 10 sqrt(g D_pi) and the ejecta limit EJECTA_LIMIT_RATIO sqrt(g D_pi).
    A negative POROSITY takes the target material's."""
    rho_imp = material_value(impactor, "rho0")
    rho_matrix = material_value(target, "rho0")
    porosity = porosity if porosity >= 0.0 else 1.0 - 1.0 / material_value(target, "distention", 1.0)
    rho_bulk = rho_matrix * (1.0 - porosity)
    d_pi = crater_diameter(mass, speed, rho_imp, rho_bulk, gravity)
    t_scale = formation_time(d_pi, gravity)
    return Scales(gravity=gravity, rho_impactor=rho_imp, rho_bulk=rho_bulk, porosity=porosity, d_pi=d_pi,
                  d_ryugu=crater_diameter(mass, speed, rho_imp, rho_bulk, RYUGU_GRAVITY), t_scale=t_scale,
                  sph_target_radius=sph_target_radius or 0.8 * d_pi,
                  handoff_time=handoff_time or handoff_fraction * t_scale,
                  late_stage_sound_speed=late_stage_sound_speed or 10.0 * math.sqrt(gravity * d_pi),
                  bowl_radius=bowl_radius or 1.05 * d_pi, dem_time=dem_time or 1.5 * t_scale,
                  ejecta_limit=ejecta_speed_limit or EJECTA_LIMIT_RATIO * math.sqrt(gravity * d_pi))


# --- the stages ----------------------------------------------------------------------------

def sph_stage(simple, args, sc, output_dir):
    """The SPH stage to the hand-off, or the state an earlier run saved (--sph-state, or this
    run's own sph_handoff.vtp on --resume). The stage checkpoints every 200 steps into
    OUTPUT_DIR/sph.cksph and saves its hand-off state as sph_handoff.vtp, so that other beds can
    be tried on it. Returns the SPH proxy, its data at the hand-off and the hand-off time."""
    saved = os.path.join(output_dir, "sph_handoff.vtp")
    state = args.sph_state or (saved if args.resume and os.path.isfile(saved) else "")
    if state:
        return saved_sph_state(simple, args, sc, state)
    checkpoint = os.path.join(output_dir, "sph.cksph")
    resume = args.resume and os.path.isfile(checkpoint)
    if not args.resume:  # a fresh run removes what an earlier run in this folder left
        for stale in (checkpoint, saved):
            if os.path.exists(stale):
                os.remove(stale)
    t = sc.handoff_time
    sph = simple.SPHImpact(ImpactorMaterial=args.impactor_material, ImpactorMass=args.impactor_mass,
                           ImpactSpeed=args.impact_speed, TargetMaterial=args.target_material,
                           TargetPorosity=args.porosity, FrictionAngle=args.friction_angle, Cohesion=args.cohesion,
                           SurfaceGravity=args.gravity, ParticlesAcrossImpactor=args.sph_resolution,
                           TargetRadius=sc.sph_target_radius, TargetCoarsening=args.sph_coarsening,
                           TargetContainer=1, LateStageTime=args.late_stage_time,
                           StopImpactorAtLateStage=1 if args.stop_impactor else 0,
                           LateStageSoundSpeed=sc.late_stage_sound_speed,
                           LateStageInitialSoundSpeed=args.late_stage_initial_sound_speed,
                           LateStageSoundSpeedExponent=args.late_stage_sound_speed_exponent,
                           LateStagePoissonRatio=args.late_stage_poisson_ratio,
                           BlockStepLevels=args.sph_block_steps, DomainRadius=args.sph_domain_radius, EndTime=t, OutputInterval=t,
                           CheckpointFile=checkpoint, CheckpointInterval=200, ResumeFromCheckpoint=1 if resume else 0)
    say(f"[1/5] SPH impact to {t:.2e} s" + (f" (resumed from {checkpoint})" if resume else ""))
    print_progress(sph, "SPH stage")
    data = fetch_stage(sph, "SPH stage", t)
    at_handoff = simple.ForceTime(Input=sph, ForcedTime=t, IgnorePipelineTime=1)
    simple.XMLPolyDataWriter(Input=at_handoff, FileName=saved).UpdatePipeline(t)
    return sph, data, t


def saved_sph_state(simple, args, sc, path):
    """The SPH state a run saved at its hand-off (sph_handoff.vtp), checked against this run's
    impact, target and gravity, which must be the same."""
    if not os.path.isfile(path):
        sys.exit(f"--sph-state {path}: no such file")
    say(f"[1/5] SPH state from {path}")
    sph = simple.XMLPolyDataReader(FileName=[path])
    data = fetch(sph)
    for name in ("Time", "ImpactSpeed", "Gravity", "ImpactorMaterial", "TargetRadius"):
        if data.GetFieldData().GetAbstractArray(name) is None:
            sys.exit(f"--sph-state {path}: not an SPHImpact state (no {name} field)")
    gravity = abs(data.GetFieldData().GetArray("Gravity").GetTuple3(0)[2])
    if abs(gravity - args.gravity) > 1e-6 * args.gravity:
        sys.exit(f"--sph-state {path}: its gravity is {gravity:g} m/s^2, this run's {args.gravity:g}")
    for name, ours, what in (("ImpactorMaterial", args.impactor_material, "impactor"),
                             ("TargetMaterial", args.target_material, "target")):
        theirs = field_value(data, name)
        if theirs is not None and theirs != ours:
            sys.exit(f"--sph-state {path}: its {what} is {theirs}, this run's {ours}")
    for name, ours, what in (("ImpactSpeed", args.impact_speed, "impact speed"),
                             ("ImpactorMass", args.impactor_mass, "impactor mass"),
                             ("FrictionAngle", args.friction_angle, "friction angle"),
                             ("Cohesion", args.cohesion, "target cohesion"),
                             ("TargetRadius", sc.sph_target_radius, "SPH target radius"),
                             ("TargetCoarsening", args.sph_coarsening, "SPH target coarsening"),
                             ("StopImpactorAtLateStage", 1.0 if args.stop_impactor else 0.0,
                              "impactor stopped at the late-stage switch (--stop-impactor)"),
                             ("LateStagePoissonRatio", args.late_stage_poisson_ratio,
                              "late-stage Poisson ratio (--late-stage-poisson-ratio)")):
        theirs = field_value(data, name)
        if theirs is not None and abs(theirs - ours) > 1e-6 * max(abs(ours), 1e-12):
            sys.exit(f"--sph-state {path}: its {what} is {theirs:g}, this run's {ours:g}")
    saved_time = field_value(data, "Time")
    if args.handoff_time > 0.0 and abs(saved_time - args.handoff_time) > 1e-9 * args.handoff_time:
        sys.exit(f"--sph-state {path}: it is at t = {saved_time:g} s, this run hands off at "
                 f"--handoff-time {args.handoff_time:g} s")
    return sph, data, saved_time


def bed_stage(simple, sc, packing, particles, heading="[2/5] ", dem_speed=None, max_overlap=None, **properties):
    """A bed of about PARTICLES grains in the bowl, settled at the run's gravity, its grain density
    giving the target's bulk density, and at rest in the DEM stage's contact law (DEM_SPEED and
    MAX_OVERLAP: that stage's MaxExpectedSpeed and MaxOverlap; None: DEMIntegrator's defaults);
    PROPERTIES are further GranularBed properties. Returns the proxy, its data, the surface the
    crater is measured against (the settled bed's own top: the mean height of its profile, not
    the height it was trimmed at, which lies above the tops of most surface grains) and the grain
    radius."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    radius = sc.grain_radius(particles, packing)
    say(f"{heading}{packing} bed of about {particles} grains of radius {radius:.3g} m settled at "
        f"g = {sc.gravity:g} m/s^2")
    bed = simple.GranularBed(Packing=packing, Container="Bowl", ContainerRadius=sc.bowl_radius,
                             ParticleRadius=radius, SurfaceHeight=0.0,
                             ParticleDensity=sc.rho_bulk / PACKING_FRACTION[packing],
                             SettlingGravity=sc.gravity, MaxParticles=max(10 * particles, 100000), **properties)
    if dem_speed is not None:
        bed.DEMMaxExpectedSpeed = dem_speed
    if max_overlap is not None:
        bed.DEMMaxOverlap = max_overlap
    print_progress(bed, "bed")
    data = fetch_stage(bed, "bed")
    with expected_warnings():  # a flat bed has no crater: CraterProfile would say so
        table = fetch(simple.CraterProfile(Input=bed))
    surface = float(np.nanmean(vtk_to_numpy(table.GetRowData().GetArray("Height"))))
    return bed, data, surface, radius


def handoff_stage(simple, sph, bed, sc):
    """ImpactHandoff of the SPH state onto the bed: ejecta faster than the limit, and material
    coming down outside the bowl, leave the domain. Returns the proxy and its data."""
    say(f"[3/5] hand-off (ejecta faster than {sc.ejecta_limit:.3g} m/s, and material coming down outside the "
        f"bowl, leave the domain)")
    hand = simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=sc.ejecta_limit, EjectaParticles="Dropped")
    return hand, fetch_stage(hand, "hand-off")


def dem_properties(args, sc, t0, max_speed):
    """DEMIntegrator's properties for the DEM stage from T0 for sc.dem_time (LAMMPSDeckWriter
    takes the same, so both engines run one set-up)."""
    return dict(Container="FromInput", GravityModel="Uniform", SurfaceGravity=[0.0, 0.0, -args.gravity],
                MaxExpectedSpeed=max_speed, MaxOverlap=args.max_overlap, EndTime=t0 + sc.dem_time,
                OutputInterval=sc.dem_time / args.frames, RollingFriction=args.rolling_friction)


def dem_stage(simple, args, sc, hand, t0, props, output_dir):
    """The DEM stage's source on the chosen engine: DEMIntegrator with its checkpoint
    (OUTPUT_DIR/dem.ckdem unless --checkpoint), or LAMMPS. Returns the source, its output times and
    the LAMMPS deck's time step (None on CraterKit: the integrator reports its own)."""
    frames = [t0 + sc.dem_time * (k + 1) / args.frames for k in range(args.frames)]
    if args.dem_engine == "lammps":
        return lammps_stage(simple, args, hand, t0, props, output_dir)
    checkpoint = args.checkpoint or os.path.join(output_dir, "dem.ckdem")
    dem = simple.DEMIntegrator(Input=hand, KeptStates=0, CheckpointFile=checkpoint, CheckpointInterval=20000,
                               ResumeFromCheckpoint=1 if args.resume else 0, **props)
    return dem, frames, None


def lammps_stage(simple, args, hand, t0, props, output_dir):
    """The DEM stage on LAMMPS: the hand-off written as a deck with DEMIntegrator's properties
    PROPS (so the same walls, gravity, stiffness and step), run with MPI, and its dump read back
    on the pipeline's clock (the deck counts time from the hand-off, t0). Returns the source of
    the DEM states, their times and the deck's step. A failure (no LAMMPS or mpirun, a style this
    LAMMPS lacks, LAMMPS' own error, the time limit --lammps-timeout or CRATERKIT_LAMMPS_TIMEOUT,
    a dump cut short) ends the script with a message that names it, keeps the SPH stage's outputs
    and gives the command that runs the DEM stage again from them (--resume)."""
    import re
    import shlex
    from .lammps import LammpsTimeout, check_lammps, read_lammps_dump, run_lammps, write_lammps_deck
    deck = os.path.join(output_dir, "lammps")
    try:
        check_lammps()  # before the deck: lmp, mpirun and the styles every DEM deck uses
        write_lammps_deck(simple, hand, deck, **props)
        dt = float(re.search(r"^timestep (\S+)", open(os.path.join(deck, "in.craterkit")).read(), re.M).group(1))
        say(f"      LAMMPS deck {deck}/in.craterkit, time step {dt:.3g} s; running on {args.lammps_ranks} MPI ranks")
        dump = run_lammps(deck, args.lammps_ranks, timeout=getattr(args, "lammps_timeout", None))
        reader, times = read_lammps_dump(simple, dump)
    except RuntimeError as error:  # every LammpsError, and the deck writer's refusal
        if isinstance(error, LammpsTimeout) and hasattr(args, "lammps_timeout"):
            error = f"{error}\n(this script: --lammps-timeout SECONDS, 0: no limit)"

        def shown(path):  # relative to the working directory when below it
            relative = os.path.relpath(path)
            return path if relative.startswith("..") else relative

        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        pvbatch = os.path.join(root, "scripts", "pvbatch")
        pvbatch = shown(pvbatch) if os.path.isfile(pvbatch) else "craterkit-pvbatch"
        script = shown(os.path.abspath(sys.argv[0])) if sys.argv and sys.argv[0] else "examples/sci_crater.py"
        command = shlex.join([pvbatch, script] + [a for a in sys.argv[1:] if a != "--resume"] + ["--resume"])
        kept = [os.path.join(output_dir, name) for name in ("sph_handoff.vtp", "sph.cksph")
                if os.path.isfile(os.path.join(output_dir, name))]
        if args.sph_state:
            kept = f"The SPH state {args.sph_state} is untouched"
        elif kept:
            kept = f"The SPH stage's outputs are kept ({', '.join(kept)})"
        else:
            kept = "The SPH stage left no outputs to resume from"
        sys.exit(f"--dem-engine lammps: {error}\n{kept}; once the above is fixed, this runs the bed, the "
                 f"hand-off and the DEM stage again without the SPH stage:\n  {command}")
    return simple.TemporalShiftScale(Input=reader, PostShift=t0), [t0 + tau for tau in times], dt


# --- measures ------------------------------------------------------------------------------

def measure(profile, t=None):
    """The crater of a CraterProfile proxy at time T: diameter, rim diameter, rim height, depth,
    volume, surface and whether a crater was found (craterkit.cross_section.crater_measures)."""
    from .cross_section import crater_measures
    return crater_measures(profile, t)


def steps_of(data):
    """The step count of a DEM state: DEMIntegrator's Step field, or the LAMMPS dump's step
    (the reader's TimeStep field; DEMIntegrator's TimeStep is its step length)."""
    step = field_value(data, "Step")
    return int(step if step is not None else field_value(data, "TimeStep"))


def speeds(data):
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    return np.linalg.norm(vtk_to_numpy(data.GetPointData().GetArray("Velocity")), axis=1)


def totals(data, grain_radius=None):
    """Mass, momentum and kinetic energy of a particle set; with grain_radius, also the kinetic
    energy of the bed (particles below one grain diameter above the original surface z = 0)
    apart from the ejecta in flight above it, and their number."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
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


def field_vector(data, name):
    """A 3-vector of DATA's field data as a list of floats."""
    return [float(x) for x in data.GetFieldData().GetArray(name).GetTuple3(0)]


def stopwatch():
    """A function returning the seconds since this call, rounded to 0.1 s."""
    start = time.time()
    return lambda: round(time.time() - start, 1)


# --- the run's steps between the stages ------------------------------------------------------

def sph_summary(data, sc, impactor_mass, impact_speed, seconds):
    """Prints the SPH state at the hand-off; returns its totals and the impactor's depth (its
    track sets the crater's floor: benchmarks/README.md)."""
    from . import impactor_depth
    tot = totals(data)
    track = impactor_depth(data)
    depth = {k: None if track[k] is None else round(track[k], 4) for k in ("centre_of_mass_m", "deepest_m")}
    fast = int((speeds(data) > sc.ejecta_limit).sum())
    say(f"      {data.GetNumberOfPoints()} SPH particles, {int(field_value(data, 'Step'))} steps, {seconds} s; "
        f"kinetic energy {tot['kinetic_energy_J']:.3g} J "
        f"({tot['kinetic_energy_J'] / (0.5 * impactor_mass * impact_speed ** 2):.2%} of the impact's); "
        f"{fast} particles faster than the ejecta limit {sc.ejecta_limit:.3g} m/s; the impactor's "
        f"centre of mass {depth['centre_of_mass_m']} m below the surface")
    return tot, depth


def handoff_summary(simple, hand, dem0, sc, surface):
    """Prints what the hand-off did (momentum mapped, curtain, escaped and dropped material) and
    the crater it carved; returns the fastest DEM particle's speed and that crater's measures."""
    vmax = float(speeds(dem0).max())
    below_z = field_vector(dem0, "SPHCompactMomentum")[2] - field_vector(dem0, "SPHCurtainMomentum")[2]
    say(f"      {dem0.GetNumberOfPoints()} DEM particles, {int(field_value(dem0, 'BedRemoved'))} carved; "
        f"momentum (z) mapped onto the bed {field_vector(dem0, 'DEMMappedMomentum')[2]:.4g} kg m/s (the compact "
        f"SPH material's below the surface: {below_z:.4g}), in the curtain above it "
        f"{field_vector(dem0, 'SPHCurtainMomentum')[2]:.4g}; {int(field_value(dem0, 'CurtainCount'))} SPH "
        f"particles above the surface, of which {int(field_value(dem0, 'EscapedCount'))} "
        f"({field_value(dem0, 'SPHEscapedMass'):.3g} kg) land outside the bowl; "
        f"{int(field_value(dem0, 'LoneDroppedCount'))} lone curtain pieces lighter than half a grain "
        f"({field_value(dem0, 'SPHLoneDroppedMass'):.3g} kg) dropped; fastest DEM particle {vmax:.3g} m/s")
    with expected_warnings():  # a hand-off that carved no crater yet is no error
        carved = measure(simple.CraterProfile(Input=hand, SurfaceFromInput=0, SurfaceHeight=surface))
    if carved["found"]:
        say(f"      crater carved at the hand-off: diameter {carved['diameter']:.3g} m "
            f"({carved['diameter'] / sc.d_pi:.2f} of pi-scaling), depth {carved['depth']:.3g} m")
    else:
        say("      no crater carved below the surface at the hand-off yet")
    return vmax, carved


def dem_stiffness_speed(vmax_dem, sc):
    """The speed the DEM stiffness is set for: the fastest particle the hand-off produced with a
    margin (an overlap grows as the speed: 1.5 times faster gives 1.5 % of a radius, pkdgrav's
    minor-warning level is 3 %); what comes down outside the bowl has left, so the fastest are the
    bed's own grains and the curtain landing in the bowl. A bed nearly at rest gets half the
    crater's speed scale sqrt(g D)."""
    return max(1.5 * vmax_dem, 0.5 * math.sqrt(sc.gravity * sc.d_pi))


def run_dem(simple, args, sc, dem, frames, surface, grain_radius, output_dir, lammps_dt):
    """Runs the DEM stage frame by frame, printing the crater's growth. Each frame's measures are
    saved as it completes (OUTPUT_DIR/dem_growth.json), and each frame leaves its state in the
    checkpoint: --resume goes on from the first frame not yet done. Returns the CraterProfile
    proxy and the growth records."""
    import json
    profile = simple.CraterProfile(Input=dem, SurfaceFromInput=0, SurfaceHeight=surface)
    growth_file = os.path.join(output_dir, "dem_growth.json")
    checkpoint = args.checkpoint or os.path.join(output_dir, "dem.ckdem")
    growth = []
    if args.resume and args.dem_engine == "craterkit" and os.path.exists(growth_file) and os.path.exists(checkpoint):
        growth = [g for g in json.load(open(growth_file)) if g["time_s"] <= frames[-1]]
        if growth:
            say(f"      resuming after t = {growth[-1]['time_s']:.4g} s ({len(growth)} frames done)")
    clock, told = stopwatch(), False
    for t in frames:
        if any(abs(g["time_s"] - t) <= 1e-9 * max(1.0, t) for g in growth):
            continue
        data = fetch_stage(dem, "DEM stage", t)
        if not told:
            dt = lammps_dt or field_value(data, "TimeStep")  # the integrator's own choice
            say(f"      time step {dt:.3g} s: about {sc.dem_time / dt:.3g} steps in all")
            told = True
        with expected_warnings():  # no crater rim while the crater forms is expected
            m = measure(profile, t)
        now = totals(data, grain_radius)
        growth.append({"time_s": t, "diameter_m": m["diameter"] if m["found"] else 0.0, "depth_m": m["depth"],
                       "bed_kinetic_energy_J": now["bed_kinetic_energy_J"],
                       "ejecta_in_flight": now["ejecta_in_flight"]})
        crater = (f"crater diameter {growth[-1]['diameter_m']:.3g} m, depth {m['depth']:.3g} m" if m["found"]
                  else f"crater still forming (no rim yet), depth {m['depth']:.3g} m")
        say(f"      t = {t:.4g} s, {steps_of(data)} steps, {clock():.0f} s: {crater}; bed kinetic energy "
            f"{now['bed_kinetic_energy_J']:.3g} J, {now['ejecta_in_flight']} ejecta in flight")
        with open(growth_file + ".part", "w") as f:  # replaced whole: a killed run leaves the last one
            json.dump(growth, f)
        os.replace(growth_file + ".part", growth_file)
    return profile, growth


# --- the report ----------------------------------------------------------------------------

def report_entries(args, sc, run):
    """report.json's entries of one run. RUN holds the stages' results: sph_data, sph_totals,
    impactor_depth, handoff_time, dem0, carved, bed_data, bed_phi, surface, grain_radius,
    max_speed, dem_data, t0, measures, growth, seconds, images."""
    m, dem0, found = run.measures, run.dem0, run.measures["found"]
    carved = run.carved if run.carved["found"] else {}
    vec = lambda name: field_vector(dem0, name)  # noqa: E731
    scaled = ({"diameter": sc.d_ryugu * m["diameter"] / sc.d_pi,
               "rim_diameter": sc.d_ryugu * m["rim_diameter"] / sc.d_pi,
               "depth": sc.d_ryugu * m["depth"] / sc.d_pi} if found else None)
    return {
        "example": "sci_crater",
        "gravity_m_s2": args.gravity,
        "impactor": {"material": args.impactor_material, "mass_kg": args.impactor_mass,
                     "speed_m_s": args.impact_speed, "density_kg_m3": sc.rho_impactor},
        "target": {"material": args.target_material, "bulk_density_kg_m3": round(sc.rho_bulk, 1),
                   "porosity": round(sc.porosity, 4), "friction_angle_deg": args.friction_angle,
                   "dem_rolling_friction": args.rolling_friction, "cohesion_pa": args.cohesion},
        "crater_diameter_m": m["diameter"] if found else None,
        "rim_diameter_m": m["rim_diameter"] if found else None,
        "crater_depth_m": m["depth"] if found else None,
        "rim_height_m": m["rim_height"] if found else None,
        # The depth by the other definitions (CraterProfile): rim crest to floor, and the lowest
        # single bin (not averaged over azimuth) below the surface and below the rim crest.
        "crater_depth_below_rim_m": m.get("depth_below_rim") if found else None,
        "deepest_point_depth_m": m.get("deepest_depth") if found else None,
        "deepest_point_depth_below_rim_m": m.get("deepest_depth_below_rim") if found else None,
        "pi_scaling_diameter_m": round(sc.d_pi, 4),
        "diameter_over_pi_scaling": round(m["diameter"] / sc.d_pi, 3) if found else None,
        "pi_scaling_diameter_at_ryugu_m": round(sc.d_ryugu, 3),
        # Read at Ryugu's gravity by pi-scaling: D scales with D_pi, the shape stays.
        "scaled_to_ryugu_m": scaled,
        "sci_crater_m": SCI_CRATER,
        "sph_particles": run.sph_data.GetNumberOfPoints(),
        "sph_resolution": args.sph_resolution,
        "sph_target_coarsening": args.sph_coarsening,
        "handoff_time_s": run.handoff_time,
        # The late stage as asked, and the sound speed the SPH state had at the hand-off (its own
        # field: with --sph-state, the saved run's).
        "late_stage": {"time_s": args.late_stage_time, "sound_speed_m_s": sc.late_stage_sound_speed,
                       "initial_sound_speed_m_s": args.late_stage_initial_sound_speed,
                       "sound_speed_exponent": args.late_stage_sound_speed_exponent,
                       "poisson_ratio": args.late_stage_poisson_ratio,
                       "sound_speed_at_handoff_m_s": field_value(run.sph_data, "LateStageSoundSpeed")},
        "impactor_depth_at_handoff_m": run.impactor_depth,
        "ejecta_speed_limit_m_s": round(sc.ejecta_limit, 4),
        "sph_totals_at_handoff": run.sph_totals,
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
        "bed_particles": run.bed_data.GetNumberOfPoints(),
        "bed_packing_fraction": run.bed_phi,
        "bed_surface_m": round(run.surface, 5),
        "grain_radius_m": round(run.grain_radius, 5),
        "bowl_radius_m": round(sc.bowl_radius, 4),
        "bed_carved": int(field_value(dem0, "BedRemoved")),
        "crater_at_handoff": {"diameter_m": carved.get("diameter"), "depth_m": carved.get("depth"),
                              "rim_diameter_m": carved.get("rim_diameter")},
        "dem_totals_after_handoff": totals(dem0, run.grain_radius),
        "dem_max_expected_speed_m_s": round(run.max_speed, 3),
        "dem_engine": args.dem_engine,
        "dem_end_time_s": field_value(run.dem_data, "Time") + (run.t0 if args.dem_engine == "lammps" else 0.0),
        "dem_steps": steps_of(run.dem_data),
        "dem_totals_at_end": totals(run.dem_data, run.grain_radius),
        "crater_growth": run.growth,
        "seconds": run.seconds,
        "images": run.images,
    }


CRATER_LENGTHS = ("crater_diameter_m", "rim_diameter_m", "crater_depth_m", "rim_height_m",
                  "crater_depth_below_rim_m", "deepest_point_depth_m", "deepest_point_depth_below_rim_m")


def report_resolution(run):
    """The resolution of the report's crater lengths: the surface is the grains' tops, so each
    length is known to about a grain radius (report.md gives it to that decimal place)."""
    return {key: run.grain_radius for key in CRATER_LENGTHS}


def about(args, sc, run):
    """report.md's opening paragraph: what this run is, and what it is not."""
    from .report import to_resolution
    m, found, ryugu = run.measures, run.measures["found"], args.gravity == RYUGU_GRAVITY
    across = m["diameter"] / (2.0 * run.grain_radius) if found else 0.0
    length = lambda value: to_resolution(value, run.grain_radius)  # noqa: E731
    text = (f"**What this run is.** The SCI impactor ({args.impactor_mass:g} kg of {args.impactor_material} at "
            f"{args.impact_speed:g} m/s) into {args.target_material} under g = {args.gravity:g} m/s^2"
            + (" (Ryugu's gravity)" if ryugu else
               f", not Ryugu's {RYUGU_GRAVITY:g} m/s^2: the crater is {sc.d_pi:.3g} m by pi-scaling instead of "
               f"{sc.d_ryugu:.3g} m, so that the run fits minutes")
            + f". SPH stage: {run.sph_data.GetNumberOfPoints():,} particles; DEM bed: "
            f"{run.bed_data.GetNumberOfPoints():,} {args.packing} grains of radius {run.grain_radius:.3g} m"
            + (f", its DEM stage run by LAMMPS on {args.lammps_ranks} MPI ranks from the deck in lammps/. "
               if args.dem_engine == "lammps" else ". "))
    if found:
        text += (f"The crater is {length(m['diameter'])} m wide ({across:.0f} grain diameters) and "
                 f"{length(m['depth'])} m deep ({m['depth'] / (2.0 * run.grain_radius):.1f} grain diameters), "
                 f"{m['diameter'] / sc.d_pi:.2f} of the pi-scaling diameter {sc.d_pi:.3g} m; its depth is "
                 f"{m['depth'] / m['diameter']:.2f} of its diameter (SCI crater: "
                 f"{SCI_CRATER['depth'] / SCI_CRATER['diameter']:.2f}).")
    else:
        text += f"It leaves no crater below the original surface; pi-scaling predicts {sc.d_pi:.3g} m."
    if not ryugu:
        text += (" This is not a measurement of the SCI crater: the project's runs give D / D_pi within 15 % "
                 "from g = 1000 to Ryugu's gravity, but depth / D changes with g (slow.pi_scaling, "
                 "docs/validation.md); report.json's scaled_to_ryugu_m is that pi-scaling arithmetic.")
    if found and across < 20:
        text += " A crater a few grains across tests the pipeline, not the physics."
    return text

"""The small SCI pipeline: GranularBed -> SPHImpact -> ImpactHandoff (Input = SPHImpact, Bed =
GranularBed) -> DEMIntegrator -> CraterProfile and FragmentAnalysis, small enough to run in the
GUI test. Shared by the GUI test (gui_create_source.py, which builds it in the real ParaView
client) and by make_sci_crater_small_state.py (which saves it, coloured, as
examples/sci_crater_small.pvsm).

It is examples/sci_crater.py's pipeline, with that example's rules (craterkit.sci.scales: every
length from the pi-scaling diameter D_pi, every time from sqrt(D_pi / g)) and defaults but for
three settings that make it cheap:

- the SCI impactor (2 kg of copper) at 500 m/s instead of 2 km/s, under g = 1e5 m/s^2 instead of
  1000 m/s^2: D_pi = 0.286 m instead of 1.0 m. The SPH target's radius, 0.8 D_pi, is then 6
  lattice spacings at two particles across the impactor instead of 21, so it holds about 1/43 of
  the particles, and the SPH stage runs to the hand-off (0.63 sqrt(D_pi / g)) at 1.06 ms
  instead of 20 ms;
- 1,000 grains requested in the bowl instead of 1,500.

The crater is a few grains across (the grain radius is 0.07 D_pi): the pipeline tests the
software, not the physics (docs/validation.md holds the validation). pvbatch.state_file
asserts its crater's diameter against D_pi and prints the figures of its run.
"""

from craterkit import fetch, field_value, sci
from craterkit.cross_section import radius_splats

GRAVITY = 1.0e5  # m/s^2
IMPACT_SPEED = 500.0  # m/s; the SCI impactor's mass and materials are kept
BED_PARTICLES = 1000  # requested; the settled, trimmed bed holds fewer
LATE_STAGE_TIME = 1e-3  # s, examples/sci_crater.py's default
DEM_FRAMES = 2  # DEM outputs after the hand-off (examples/sci_crater.py: --frames)
MAX_OVERLAP = 0.01  # of a grain's radius, examples/sci_crater.py's default


def scales():
    """The run's scales (craterkit.sci.Scales) for GRAVITY and IMPACT_SPEED."""
    return sci.scales(GRAVITY, speed=IMPACT_SPEED)


def build(simple, sph_checkpoint="", dem_checkpoint=""):
    """Creates the pipeline's proxies and updates the bed (for its surface) and the hand-off (for
    its time, where the DEM stage starts). Returns a dict of the proxies by name, with "scales",
    "surface" (the settled bed's own top, which the crater is measured against), "handoff_time",
    "end_time", "grain_radius" and "max_handoff_speed" (of the fastest particle after the
    hand-off). Checkpoint files are optional (the GUI test opens them with the readers)."""
    sc = scales()
    radius = sc.grain_radius(BED_PARTICLES, "RCP")
    # The DEM stage's stiffness: examples/sci_crater.py's rule (craterkit.sci.dem_stiffness_speed)
    # is 1.5 times the fastest particle after the hand-off, at least half the crater's speed
    # scale sqrt(g D_pi); the bed is settled in that law (DEMMaxExpectedSpeed), so the speed is
    # fixed before the hand-off at that least value, and the tests check that 1.5 times the
    # fastest particle stays below it (the rule then gives the same speed).
    stiffness_speed = sci.dem_stiffness_speed(0.0, sc)
    bed = simple.GranularBed(Packing="RCP", Container="Bowl", ContainerRadius=sc.bowl_radius,
                             ParticleRadius=radius, SurfaceHeight=0.0,
                             ParticleDensity=sc.rho_bulk / sci.PACKING_FRACTION["RCP"],
                             SettlingGravity=GRAVITY, DEMMaxExpectedSpeed=stiffness_speed,
                             DEMMaxOverlap=MAX_OVERLAP)
    simple.RenameSource("GranularBed", bed)
    # The surface the crater is measured against: the settled bed's own top (the mean of its
    # profile), as craterkit.sci.bed_stage takes it; the helper profile is deleted again.
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np
    with sci.expected_warnings():  # a flat bed has no crater: CraterProfile says so
        helper = simple.CraterProfile(Input=bed)
        surface = float(np.nanmean(vtk_to_numpy(fetch(helper).GetRowData().GetArray("Height"))))
    simple.Delete(helper)

    t = sc.handoff_time
    sph = simple.SPHImpact(ImpactSpeed=IMPACT_SPEED, SurfaceGravity=GRAVITY, ParticlesAcrossImpactor=2,
                           TargetRadius=sc.sph_target_radius, TargetContainer=1,
                           LateStageTime=LATE_STAGE_TIME, LateStageSoundSpeed=sc.late_stage_sound_speed,
                           EndTime=t, OutputInterval=t, CheckpointFile=sph_checkpoint,
                           CheckpointInterval=100000 if sph_checkpoint else 0)
    simple.RenameSource("SPHImpact", sph)
    hand = simple.ImpactHandoff(Input=sph, Bed=bed, EjectaSpeedLimit=sc.ejecta_limit, EjectaParticles="Dropped")
    simple.RenameSource("ImpactHandoff", hand)
    dem0 = fetch(hand)
    vmax = float(np.linalg.norm(vtk_to_numpy(dem0.GetPointData().GetArray("Velocity")), axis=1).max())
    t0 = field_value(dem0, "Time")
    dem = simple.DEMIntegrator(Input=hand, Container="FromInput", GravityModel="Uniform",
                               SurfaceGravity=[0.0, 0.0, -GRAVITY],
                               MaxExpectedSpeed=stiffness_speed, MaxOverlap=MAX_OVERLAP,
                               RollingFriction=0.35, EndTime=t0 + sc.dem_time,
                               OutputInterval=sc.dem_time / DEM_FRAMES, KeptStates=4,
                               CheckpointFile=dem_checkpoint, CheckpointInterval=1000)
    simple.RenameSource("DEMIntegrator", dem)
    profile = simple.CraterProfile(Input=dem, SurfaceFromInput=0, SurfaceHeight=surface)
    simple.RenameSource("CraterProfile", profile)
    fragments = simple.FragmentAnalysis(Input=dem)
    simple.RenameSource("FragmentAnalysis", fragments)
    return {"bed": bed, "sph": sph, "hand": hand, "dem": dem, "profile": profile, "fragments": fragments,
            "scales": sc, "surface": surface, "handoff_time": t0, "end_time": t0 + sc.dem_time,
            "grain_radius": radius, "max_handoff_speed": vmax}


def show_cross_section(simple, p, view):
    """Shows in VIEW the cross-section of pipeline P (build's result): CraterProfile's slab
    through the axis as spheres of their radius, coloured by height, with a colour bar, on white,
    seen from -y with a parallel projection framing the bowl; the picture of the GUI test's
    baseline. Returns the display."""
    height = simple.Calculator(Input=simple.OutputPort(p["profile"], 1), ResultArrayName="Height",
                               Function="coordsZ")
    display = radius_splats(simple.Show(height, view))
    simple.ColorBy(display, ("POINTS", "Height"))
    lut = simple.GetColorTransferFunction("Height")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    # The colours span the top few grains (the crater is about a grain deep below the bed's
    # surface); the bowl's lower part is all dark.
    lut.RescaleTransferFunction(p["surface"] - 4.0 * p["grain_radius"], p["surface"] + 2.0 * p["grain_radius"])
    display.SetScalarBarVisibility(view, True)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    bar = simple.GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = "Height (m)", ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.WindowLocation = "Any Location"
    bar.HorizontalTitle = 1  # above the bar, inside the picture
    bar.Position = [0.88, 0.2]
    bar.ScalarBarLength = 0.6
    bar.RangeLabelFormat = "%.2f"
    bowl = p["scales"].bowl_radius
    simple.Render(view)  # a view's first render resets its camera: place it afterwards
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [0.22 * bowl, 0.0, -0.42 * bowl]
    view.CameraPosition = [0.22 * bowl, -5.0, -0.42 * bowl]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelScale = 0.72 * bowl  # at 16:9: the bowl, and the colour bar beside it
    return display

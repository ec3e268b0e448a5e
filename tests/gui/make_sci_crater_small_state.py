"""Writes examples/sci_crater_small.pvsm, the ParaView state of the small SCI pipeline
(sci_small.py): GranularBed -> SPHImpact -> ImpactHandoff -> DEMIntegrator -> CraterProfile and
FragmentAnalysis, in one layout of three views at the DEM stage's last time:

- left: the DEM particles as spheres of their radius seen from above, coloured by height, with
  a colour bar (the colour map spans the top few grains: the crater is about a grain deep);
- top right: the cross-section (CraterProfile's second output, the slab through the impact
  axis) seen from -y, coloured by height in the same colour map;
- bottom right: the crater's profile (CraterProfile's table: height against distance from the
  axis).

Run it again after a change to the pipeline, to the plugin's properties or to the solvers (the
state holds the settled bed's surface height and the hand-off's time as numbers):

    scripts/pvbatch tests/gui/make_sci_crater_small_state.py [OUTPUT.pvsm]

The state names no file (the pipeline reads none), so it opens anywhere the plugin is loaded:
File > Load State in the GUI, or simple.LoadState in a script (tests/pvbatch/test_state_file.py
loads it and checks the crater). Opening it runs the pipeline to the last time: pvbatch.state_file,
which does that, took 28 s on two cores shared with other jobs (2026-12-07,
`ctest --test-dir build -R pvbatch.state_file`).
"""

import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

from craterkit import load_plugin  # noqa: E402
from craterkit.cross_section import radius_splats  # noqa: E402
import sci_small  # noqa: E402

HEADER = """<!--
  CraterKit: the small SCI pipeline (GranularBed -> SPHImpact -> ImpactHandoff -> DEMIntegrator
  -> CraterProfile and FragmentAnalysis) at its last time, coloured, with the cross-section.
  Load it with File > Load State once the CraterKit plugin is loaded (Tools > Manage Plugins),
  or with paraview.simple.LoadState. Written by tests/gui/make_sci_crater_small_state.py (edit
  that, not this file); checked by tests/pvbatch/test_state_file.py.
-->
"""


def main(argv):
    output = argv[0] if argv else os.path.join(ROOT, "examples", "sci_crater_small.pvsm")
    simple = load_plugin()
    p = sci_small.build(simple)
    end = p["end_time"]

    layout = simple.CreateLayout("sci_crater_small")
    particles_view = simple.CreateView("RenderView")
    section_view = simple.CreateView("RenderView")
    profile_view = simple.CreateView("XYChartView")
    for view in (particles_view, section_view):
        view.OrientationAxesVisibility = 0
    simple.AssignViewToLayout(view=particles_view, layout=layout, hint=0)
    layout.SplitHorizontal(0, 0.55)
    simple.AssignViewToLayout(view=section_view, layout=layout, hint=2)
    layout.SplitVertical(2, 0.6)
    simple.AssignViewToLayout(view=profile_view, layout=layout, hint=6)

    # One colour map for both views: height, over the top few grains (the bed's surface, the
    # crater about a grain deep below it); the bowl's lower part is all dark.
    surface, grain = p["surface"], p["grain_radius"]
    heights = simple.GetColorTransferFunction("Height")
    heights.ApplyPreset("Viridis (matplotlib)", True)
    heights.AutomaticRescaleRangeMode = "Never"
    height_range = (surface - 4.0 * grain, surface + grain)
    bowl = p["scales"].bowl_radius

    # The DEM particles: spheres of their radius, coloured by height, seen from above.
    particle_height = simple.Calculator(Input=p["dem"], ResultArrayName="Height", Function="coordsZ")
    simple.RenameSource("Particle height", particle_height)
    shown = simple.Show(particle_height, particles_view)
    radius_splats(shown)
    simple.ColorBy(shown, ("POINTS", "Height"))
    shown.SetScalarBarVisibility(particles_view, True)
    colour_bar(simple.GetScalarBar(heights, particles_view), "Height (m)")
    particles_view.CameraPosition = [0.0, -1.6 * bowl, 3.0 * bowl]
    particles_view.CameraFocalPoint = [0.0, 0.0, -0.2 * bowl]
    particles_view.CameraViewUp = [0.0, 0.0, 1.0]

    # The cross-section: the slab through the axis (CraterProfile's second output), seen from -y.
    section_height = simple.Calculator(Input=simple.OutputPort(p["profile"], 1), ResultArrayName="Height",
                                       Function="coordsZ")
    simple.RenameSource("Cross-section height", section_height)
    shown = simple.Show(section_height, section_view)
    radius_splats(shown)
    simple.ColorBy(shown, ("POINTS", "Height"))
    shown.SetScalarBarVisibility(section_view, True)
    colour_bar(simple.GetScalarBar(heights, section_view), "Height (m)")
    section_view.CameraParallelProjection = 1
    section_view.CameraPosition = [0.2 * bowl, -10.0 * bowl, -0.4 * bowl]
    section_view.CameraFocalPoint = [0.2 * bowl, 0.0, -0.4 * bowl]
    section_view.CameraViewUp = [0.0, 0.0, 1.0]
    section_view.CameraParallelScale = 0.8 * bowl

    heights.RescaleTransferFunction(*height_range)  # after ColorBy, which sets the data's range

    # The profile: height against distance from the axis.
    chart = simple.Show(simple.OutputPort(p["profile"], 0), profile_view)
    chart.UseIndexForXAxis = 0
    chart.XArrayName = "Radius"
    chart.SeriesVisibility = ["Height"]
    profile_view.LeftAxisTitle = "Height (m)"
    profile_view.BottomAxisTitle = "Distance from the axis (m)"

    scene = simple.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = end
    simple.SetActiveView(particles_view)
    simple.SetActiveSource(p["dem"])
    for view in (particles_view, section_view, profile_view):
        simple.Render(view)

    simple.SaveState(output)
    text = open(output).read()
    text = text.replace("?>\n", "?>\n" + HEADER, 1) if text.startswith("<?xml") else HEADER + text
    with open(output, "w") as f:
        f.write(text)
    # A state names the files its readers read; this one must name no path on this machine.
    for place in (ROOT, "/tmp", os.path.expanduser("~")):
        if place and place != "/" and place in text:
            sys.exit(f"{output} holds the path {place}: a state to ship must not")
    paths = sorted(set(re.findall(r'value="(/[^"]+)"', text)))  # "/" alone is a block selector
    if paths:
        sys.exit(f"{output} holds absolute paths: {paths}")
    print(f"wrote {output}: crater pipeline at t = {end:.6g} s")
    # Release the views (and their OpenGL contexts) now, not at interpreter exit, when the X
    # connection of Xvfb may already be gone.
    for view in (particles_view, section_view, profile_view):
        simple.Delete(view)
    return 0


def colour_bar(bar, title):
    bar.Title, bar.ComponentTitle = title, ""
    bar.HorizontalTitle, bar.RangeLabelFormat = 1, "%.2f"


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

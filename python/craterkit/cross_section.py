"""Crater-style cross-sections rendered headless (after Figure 2 of Zhang et al., LPSC 2021).

A slab of particles |y| <= half_width through the impact axis, seen along +y with a parallel
projection, particles drawn as spheres of their true radius coloured by an array (height by
default), the original surface as a dashed horizontal line and the central axis as a dashed
vertical line; with `measures` (from `crater_measures`), the measured crater diameter, rim
diameter and depth as coloured lines with a legend.
"""

MEASURE_COLORS = {"diameter": [0.85, 0.1, 0.1], "rim": [0.1, 0.3, 0.9], "depth": [0.1, 0.6, 0.2]}


def crater_measures(profile, time=None):
    """The summary of a CraterProfile proxy as a dict (diameter, rim_diameter, rim_height,
    depth (below the original surface), depth_below_rim (rim crest to floor), deepest_depth and
    deepest_depth_below_rim (the lowest single bin, not averaged over azimuth), volume, surface,
    found), at `time` for a time-dependent input: without it the
    profile keeps the state it was first computed from, since a new time upstream does not
    modify the filter."""
    from paraview import servermanager
    if time is not None:
        profile.UpdatePipeline(time)
    data = servermanager.Fetch(profile)
    fd = data.GetFieldData()

    def value(name):
        array = fd.GetArray(name)
        return array.GetValue(0) if array is not None else None
    return {"diameter": value("CraterDiameter"), "rim_diameter": value("RimDiameter"),
            "rim_height": value("RimHeight"), "depth": value("CraterDepth"),
            "depth_below_rim": value("CraterDepthBelowRim"), "deepest_depth": value("DeepestPointDepth"),
            "deepest_depth_below_rim": value("DeepestPointDepthBelowRim"),
            "volume": value("ExcavatedVolume"), "surface": value("SurfaceHeight"),
            "found": bool(value("CraterFound"))}

from . import load_plugin


def _dashed_lines_script(x_min, x_max, z_min, z_max, surface, y, dash):
    # Runs inside a ProgrammableSource: builds dashed line segments as a vtkPolyData.
    return f"""
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
points, lines = vtkPoints(), vtkCellArray()
def dashes(a, b, fixed, horizontal):
    s = a
    while s < b:
        e = s + {dash} if s + {dash} < b else b
        p = (s, {y}, fixed) if horizontal else (fixed, {y}, s)
        q = (e, {y}, fixed) if horizontal else (fixed, {y}, e)
        i = points.InsertNextPoint(*p)
        j = points.InsertNextPoint(*q)
        lines.InsertNextCell(2)
        lines.InsertCellPoint(i)
        lines.InsertCellPoint(j)
        s += 2 * {dash}
dashes({x_min}, {x_max}, {surface}, True)
dashes({z_min}, {z_max}, 0.0, False)
out = self.GetPolyDataOutput()
out.SetPoints(points)
out.SetLines(lines)
"""


def render_cross_section(source, filename, half_width=None, color_by="Height",
                         surface_height=0.0, resolution=(1600, 900), label=None,
                         color_range=None, measures=None, max_height=None):
    """Renders the cross-section of a particle source to a PNG and returns the slab proxy.

    source: a CraterKit particle proxy (points with a Radius array).
    half_width: half thickness of the slab in m (default: twice the largest radius).
    color_by: point array to colour by; "Height" is z.
    max_height: leave out particles above this z (ejecta high in flight), so the view frames the crater.
    """
    simple = load_plugin()
    from paraview import servermanager
    data = servermanager.Fetch(source)
    radius = data.GetPointData().GetArray("Radius")
    rmax = radius.GetRange()[1] if radius is not None else 0.0
    if half_width is None:
        half_width = 2.0 * rmax
    bounds = data.GetBounds()

    height = simple.Calculator(Input=source, ResultArrayName="Height", Function="coordsZ")
    offset = simple.Calculator(Input=height, ResultArrayName="SlabDistance", Function="abs(coordsY)")
    slab = simple.Threshold(Input=offset, Scalars=["POINTS", "SlabDistance"])
    slab.LowerThreshold = 0.0
    slab.UpperThreshold = half_width
    if max_height is not None:
        slab = simple.Threshold(Input=slab, Scalars=["POINTS", "Height"])
        slab.LowerThreshold = bounds[4] - 1.0
        slab.UpperThreshold = max_height
        bounds = bounds[:5] + (min(bounds[5], max_height),)

    view = simple.CreateView("RenderView")
    view.ViewSize = list(resolution)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]

    # True sphere glyphs (not point sprites): they occlude and are occluded correctly by
    # the reference lines, and keep their radius in world units.
    display, lut = show_spheres(simple, slab, view, color_by, "Viridis (matplotlib)", (16, 12))
    if color_range is not None:
        lut.RescaleTransferFunction(*color_range)
    else:
        display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = {"Height": "Height (m)", "Speed": "Speed (m/s)"}.get(color_by, color_by)
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    # The title above the bar and the labels on its left, inside the picture: a vertical title
    # and labels to the right of a bar at the panel's edge are cut off in narrow panels.
    bar.HorizontalTitle = 1
    bar.TextPosition = "Ticks left/bottom, annotations right/top"
    bar.RangeLabelFormat = "%.3g"
    bar.Position = [0.9, 0.15]
    bar.ScalarBarLength = 0.6

    pad = 0.06 * (bounds[1] - bounds[0])
    lines = simple.ProgrammableSource()
    lines.OutputDataSetType = "vtkPolyData"
    lines.Script = _dashed_lines_script(
        bounds[0] - pad, bounds[1] + pad, bounds[4] - pad, bounds[5] + 0.5 * pad + rmax,
        surface_height, -0.5 * (bounds[1] - bounds[0]), 0.015 * (bounds[1] - bounds[0]))
    line_display = simple.Show(lines, view)
    line_display.ColorArrayName = ["POINTS", ""]
    line_display.AmbientColor = line_display.DiffuseColor = [0.1, 0.1, 0.1]
    line_display.LineWidth = 2.0

    if measures and measures.get("found"):
        # Measured dimensions: diameter at the surface (red), rim to rim at the rim's height
        # (blue), depth on the axis (green), drawn in front of the slab.
        z0 = measures.get("surface", surface_height) or 0.0
        y = -0.5 * (bounds[1] - bounds[0])
        segments = [
            ("diameter", [-0.5 * measures["diameter"], y, z0], [0.5 * measures["diameter"], y, z0]),
            ("rim", [-0.5 * measures["rim_diameter"], y, z0 + measures["rim_height"]],
             [0.5 * measures["rim_diameter"], y, z0 + measures["rim_height"]]),
            ("depth", [0.0, y, z0], [0.0, y, z0 - measures["depth"]]),
        ]
        for key, p1, p2 in segments:
            seg = simple.Line(Point1=p1, Point2=p2)
            seg_display = simple.Show(seg, view)
            seg_display.ColorArrayName = ["POINTS", ""]
            seg_display.AmbientColor = seg_display.DiffuseColor = MEASURE_COLORS[key]
            seg_display.LineWidth = 4.0
        legend = simple.Text(Text=(f"crater diameter {measures['diameter']:.2f} m (red)\n"
                                   f"rim diameter {measures['rim_diameter']:.2f} m (blue)\n"
                                   f"depth {measures['depth']:.2f} m (green)"))
        legend_display = simple.Show(legend, view)
        legend_display.WindowLocation = "Upper Left Corner"
        legend_display.FontSize = 20
        legend_display.Color = [0.1, 0.1, 0.1]

    if label:
        text = simple.Text(Text=label)
        text_display = simple.Show(text, view)
        text_display.WindowLocation = "Lower Left Corner"
        text_display.FontSize = 22
        text_display.Color = [0.1, 0.1, 0.1]

    simple.Render(view)  # the first render resets the camera: place it afterwards
    cx = 0.5 * (bounds[0] + bounds[1])
    cz = 0.5 * (bounds[4] + bounds[5])
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [cx, 0.0, cz]
    view.CameraPosition = [cx, -10.0 * (bounds[1] - bounds[0] + 1.0), cz]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    aspect = resolution[0] / resolution[1]
    view.CameraParallelScale = 0.5 * max(1.15 * (bounds[5] - bounds[4]) + 2 * pad,
                                         1.35 * (bounds[1] - bounds[0] + 2 * pad) / aspect)
    simple.Render(view)
    simple.SaveScreenshot(filename, view, ImageResolution=list(resolution),
                          TransparentBackground=0)
    # Release the view (and its OpenGL context) now, not at interpreter exit, when the
    # X connection of xvfb may already be gone.
    simple.Delete(view)
    return slab


def show_spheres(simple, source, view, color_by, preset, resolution=None):
    """Shows SOURCE's particles in VIEW as sphere glyphs of their Radius, coloured by the point
    array COLOR_BY with the colour map PRESET; RESOLUTION (theta, phi) or the glyph's default.
    Returns the display and the colour transfer function."""
    spheres = simple.Glyph(Input=source, GlyphType="Sphere")
    spheres.GlyphType.Radius = 1.0
    if resolution:
        spheres.GlyphType.ThetaResolution, spheres.GlyphType.PhiResolution = resolution
    spheres.ScaleArray = ["POINTS", "Radius"]
    spheres.ScaleFactor = 1.0
    spheres.GlyphMode = "All Points"
    spheres.OrientationArray = ["POINTS", "No orientation array"]
    return _colored(simple, simple.Show(spheres, view), color_by, preset)


def show_point_spheres(simple, source, view, color_by, preset, radius):
    """Shows SOURCE's particles in VIEW as point splats shaded as spheres of one RADIUS (Point
    Gaussian), coloured as show_spheres does: the same picture for particles of one size, without
    a glyph's triangles (some 17 kB a particle). Returns the display and the colour transfer
    function."""
    display = simple.Show(source, view)
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Sphere"
    display.GaussianRadius = radius
    return _colored(simple, display, color_by, preset)


def radius_splats(display):
    """Makes DISPLAY show each particle as a point splat shaded as a sphere of its own Radius
    (Point Gaussian scaled by the Radius array, not through a transfer function): particles of
    many sizes without a glyph's triangles. Returns the display."""
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Sphere"
    display.ScaleByArray = 1
    display.SetScaleArray = ["POINTS", "Radius"]
    display.UseScaleFunction = 0  # the radius itself, not mapped through a transfer function
    display.GaussianRadius = 1.0
    return display


def _colored(simple, display, color_by, preset):
    simple.ColorBy(display, ("POINTS", color_by))
    lut = simple.GetColorTransferFunction(color_by)
    lut.ApplyPreset(preset, True)
    return display, lut

"""Figures shared by the examples: velocity-field cross-sections side by side (after Figure 1 of
Zhang et al., LPSC 2021) and the crater profile plot."""

import os


def speed_slab(simple, source, radius_expr=None):
    """The source with Speed = |Velocity| and, if radius_expr is given, a Radius for drawing."""
    speed = simple.Calculator(Input=source, ResultArrayName="Speed", Function="mag(Velocity)")
    if radius_expr is None:
        return speed
    return simple.Calculator(Input=speed, ResultArrayName="Radius", Function=radius_expr)


def side_by_side(paths, filename, width, height):
    """Puts PNG panels next to each other in one picture (matplotlib, no axes)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(paths), figsize=(len(paths) * width / 100, height / 100), dpi=100)
    for ax, path in zip(axes, paths):
        ax.imshow(plt.imread(path))
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(filename)
    plt.close(fig)
    return filename


def handoff_figure(simple, sph, hand, handoff_time, filename, width=900):
    """Figure 1 of the hybrid seed: the SPH velocity field at the hand-off time and the DEM
    state after the hand-off, side by side, coloured by speed on one scale (0 to the SPH's
    99th percentile). sph: the SPHImpact proxy; hand: the ImpactHandoff proxy."""
    import numpy as np
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from .cross_section import render_cross_section
    at_handoff = simple.ForceTime(Input=sph, ForcedTime=handoff_time, IgnorePipelineTime=1)
    data = servermanager.Fetch(at_handoff)
    speed = np.linalg.norm(vtk_to_numpy(data.GetPointData().GetArray("Velocity")), axis=1)
    vmax = float(np.percentile(speed, 99)) if speed.size else 1.0
    height = int(width * 9 / 16)
    folder = os.path.dirname(filename)
    left, right = os.path.join(folder, "sph.png"), os.path.join(folder, "dem.png")
    render_cross_section(speed_slab(simple, at_handoff, "SmoothingLength/5"), left, color_by="Speed",
                         color_range=(0.0, vmax), resolution=(width, height), label=f"SPH at {handoff_time:.1e} s")
    render_cross_section(speed_slab(simple, hand), right, color_by="Speed", color_range=(0.0, vmax),
                         resolution=(width, height), label="DEM after the hand-off")
    return side_by_side([left, right], filename, width, height)


def profile_plot(radius, height, filename, measures=None, reference=None, title=None):
    """The azimuthally averaged surface height against distance from the impact axis, mirrored
    to both sides, with the measured diameter, rim and depth and an optional reference crater
    (a dict with diameter, rim_diameter and depth, drawn as markers)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    r = np.asarray(radius, dtype=float)
    z = np.asarray(height, dtype=float)
    ok = np.isfinite(z)
    fig, ax = plt.subplots(figsize=(9, 4), dpi=100)
    ax.plot(np.concatenate([-r[ok][::-1], r[ok]]), np.concatenate([z[ok][::-1], z[ok]]), "k-", lw=1.5,
            label="surface (azimuthal mean)")
    surface = (measures or {}).get("surface") or 0.0
    ax.axhline(surface, color="0.5", ls="--", lw=1, label="pre-impact surface")
    if measures and measures.get("found"):
        d, rd, depth = measures["diameter"], measures["rim_diameter"], measures["depth"]
        ax.plot([-d / 2, d / 2], [surface, surface], "r-", lw=2, label=f"diameter {d:.3g} m")
        ax.plot([-rd / 2, rd / 2], [surface + measures["rim_height"]] * 2, "b-", lw=2,
                label=f"rim diameter {rd:.3g} m")
        ax.plot([0, 0], [surface, surface - depth], "g-", lw=2, label=f"depth {depth:.3g} m")
    if reference:
        ax.plot([-reference["diameter"] / 2, reference["diameter"] / 2], [surface] * 2, "rx", ms=9,
                label=f"{reference.get('name', 'reference')} diameter {reference['diameter']:.3g} m")
    ax.set_xlabel("distance from the impact axis (m)")
    ax.set_ylabel("height (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.legend(fontsize=8, loc="lower right")
    if title:
        ax.set_title(title)
    fig.tight_layout()
    fig.savefig(filename)
    plt.close(fig)
    return os.path.basename(filename)

"""A 2D hard-disk impact ("ball pit"), rendered frame by frame and assembled into an MP4.

HardDiskCrater runs event by event and stops exactly at every frame time, so the frames are
evenly spaced. Writes the frames, movie.mp4 (ffmpeg), plots of the ejection angles against
launch distance (with the Maxwell Z-model's 45-56 degrees) and of the shock front, and
report.md / report.json under --output-dir.

    scripts/pvbatch examples/hard_disk_movie.py --help
    scripts/pvbatch examples/hard_disk_movie.py --preset "Dense sand" --end-time 0.05
"""

import argparse
import math
import os
import shutil
import subprocess
import sys
import time

from craterkit import fetch, field_value, load_plugin
from craterkit.report import write_report

PRESETS = ["Custom", "Ball pit", "Dense sand", "Clump impactor"]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--preset", default="Custom", choices=PRESETS,
                   help="teaching preset; Custom uses the options below")
    p.add_argument("--width", type=float, default=1.0, help="box width, m")
    p.add_argument("--ground-depth", type=float, default=0.5, help="m")
    p.add_argument("--headroom", type=float, default=0.3, help="m of box above the ground")
    p.add_argument("--disk-radius", type=float, default=0.005, help="m")
    p.add_argument("--max-disk-radius", type=float, default=0.0, help="m (0: one size)")
    p.add_argument("--area-fraction", type=float, default=0.7)
    p.add_argument("--impactor", choices=["Disk", "Clump"], default="Disk")
    p.add_argument("--impactor-radius", type=float, default=0.03, help="m")
    p.add_argument("--density-ratio", type=float, default=3.0)
    p.add_argument("--impact-speed", type=float, default=10.0, help="m/s")
    p.add_argument("--impact-angle", type=float, default=0.0, help="degrees from vertical")
    p.add_argument("--restitution", type=float, default=1.0)
    p.add_argument("--gravity", type=float, default=0.0, help="m/s^2")
    p.add_argument("--tracer-fraction", type=float, default=0.02)
    p.add_argument("--end-time", type=float, default=0.04, help="s")
    p.add_argument("--frame-interval", type=float, default=0.0005, help="s")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--resolution", type=int, nargs=2, default=[1280, 720], help="pixels")
    p.add_argument("--fps", type=int, default=25, help="movie frames per second")
    p.add_argument("--no-movie", action="store_true", help="frames only, no ffmpeg")
    p.add_argument("--output-dir", default="results/hard_disk")
    return p.parse_args(argv)


def make_view(simple, src, args, width, height):
    view = simple.CreateView("RenderView")
    view.ViewSize = list(args.resolution)
    view.OrientationAxesVisibility = 0
    view.Background = [0.08, 0.08, 0.1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    disks = simple.Glyph(Input=simple.OutputPort(src, 0), GlyphType="Sphere")
    disks.ScaleArray = ["POINTS", "Radius"]
    disks.ScaleFactor = 2.0  # the sphere glyph has radius 0.5
    disks.GlyphMode = "All Points"
    disks.GlyphType.ThetaResolution = 12
    disks.GlyphType.PhiResolution = 6
    shown = simple.Show(disks, view)
    simple.ColorBy(shown, ("POINTS", "Material"))
    lut = simple.GetColorTransferFunction("Material")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = ["0", "ground", "1", "impactor"]
    lut.IndexedColors = [0.85, 0.72, 0.45, 0.85, 0.2, 0.15]
    shown.SetScalarBarVisibility(view, False)
    tracers = simple.Show(simple.OutputPort(src, 1), view)
    simple.ColorBy(tracers, ("POINTS", None))
    tracers.AmbientColor = tracers.DiffuseColor = [0.2, 0.45, 0.95]
    tracers.LineWidth = 2.0
    outline = simple.Show(simple.OutputPort(src, 2), view)
    simple.ColorBy(outline, ("POINTS", None))
    outline.AmbientColor = outline.DiffuseColor = [1.0, 1.0, 1.0]
    outline.LineWidth = 1.5
    text = simple.Text(Text="")
    label = simple.Show(text, view)
    label.WindowLocation = "Upper Left Corner"
    label.FontSize = 14
    simple.Render(view)  # the first render resets the camera: place it afterwards
    cam = view.GetActiveCamera()
    cx, cz = width / 2.0, height / 2.0
    cam.SetFocalPoint(cx, 0.0, cz)
    cam.SetPosition(cx, -10.0, cz)
    cam.SetViewUp(0.0, 0.0, 1.0)
    view.CameraParallelProjection = 1
    aspect = args.resolution[0] / args.resolution[1]
    view.CameraParallelScale = 0.51 * max(height, width / aspect)
    return view, text


def fit_slope(xs, ys):
    n = len(xs)
    if n < 2:
        return float("nan")
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def plots(output_dir, distances, angles, frame_times, front):
    """Ejection angle against launch distance and the shock front against time (PNG)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    files = []
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.scatter(distances, angles, s=6, alpha=0.5, label="ejected disks")
    ax.axhspan(45.0, 56.3, color="tab:orange", alpha=0.2, label="Z-model, Z = 3 to 3.5")
    ax.set_xlabel("launch distance from the impact point (m)")
    ax.set_ylabel("ejection angle from the surface (deg)")
    ax.set_ylim(0, 90)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(output_dir, "ejection_angles.png"), dpi=120)
    files.append("ejection_angles.png")
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(frame_times, front, "o-", ms=3)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("shock front distance from the impact point (m)")
    fig.tight_layout()
    fig.savefig(os.path.join(output_dir, "shock_front.png"), dpi=120)
    files.append("shock_front.png")
    plt.close(fig)
    return files


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    frames_dir = os.path.join(args.output_dir, "frames")
    os.makedirs(frames_dir, exist_ok=True)
    for old in os.listdir(frames_dir):
        if old.startswith("frame_") and old.endswith(".png"):
            os.remove(os.path.join(frames_dir, old))
    simple = load_plugin()
    src = simple.HardDiskCrater(
        Preset=PRESETS.index(args.preset), Width=args.width, GroundDepth=args.ground_depth,
        Headroom=args.headroom, DiskRadius=args.disk_radius, MaxDiskRadius=args.max_disk_radius,
        AreaFraction=args.area_fraction, ImpactorType=0 if args.impactor == "Disk" else 1,
        ImpactorRadius=args.impactor_radius, DensityRatio=args.density_ratio,
        ImpactSpeed=args.impact_speed, ImpactAngle=args.impact_angle, Restitution=args.restitution,
        Gravity=args.gravity, TracerFraction=args.tracer_fraction, EndTime=args.end_time,
        FrameInterval=args.frame_interval, RandomSeed=args.seed)
    times = list(src.TimestepValues)
    print(f"[1/3] building the ground ({args.preset}), {len(times)} frames to {times[-1]:.4g} s",
          flush=True)
    start = time.time()
    src.UpdatePipeline(0.0)
    first = fetch(src)
    if first.GetNumberOfPoints() == 0:
        print("error: the source failed; see the error above", file=sys.stderr)
        return 1
    box = first.GetFieldData().GetArray("BoxSize").GetTuple3(0)
    box_w, box_h = box[0], box[2]
    print(f"      {first.GetNumberOfPoints()} disks in {time.time() - start:.1f} s", flush=True)
    view, text = make_view(simple, src, args, box_w, box_h)

    print("[2/3] running and rendering", flush=True)
    sim_start = time.time()
    data = first
    for k, t in enumerate(times):
        view.ViewTime = t
        src.UpdatePipeline(t)
        data = fetch(src)
        if data.GetNumberOfPoints() == 0:
            print("error: the run failed; see the error above", file=sys.stderr)
            return 1
        text.Text = (f"t = {1000 * t:.1f} ms   collisions {int(field_value(data, 'PairCollisions')):,}   "
                     f"crater depth {100 * field_value(data, 'CraterDepth'):.1f} cm")
        simple.SaveScreenshot(os.path.join(frames_dir, f"frame_{k:04d}.png"), view,
                              ImageResolution=list(args.resolution))
        if k % max(1, len(times) // 10) == 0 or k == len(times) - 1:
            print(f"      frame {k + 1}/{len(times)}: t = {t:.4f} s, "
                  f"{int(field_value(data, 'PairCollisions')):,} collisions, "
                  f"shock front {field_value(data, 'ShockFrontRadius'):.3f} m, "
                  f"{time.time() - sim_start:.1f} s", flush=True)
    elapsed = time.time() - sim_start

    print("[3/3] movie, plots and report", flush=True)
    movie = None
    if not args.no_movie:
        ffmpeg = shutil.which("ffmpeg")
        if ffmpeg is None:
            print("warning: ffmpeg not found (Debian package ffmpeg); frames only", file=sys.stderr)
        else:
            movie = os.path.join(args.output_dir, "movie.mp4")
            cmd = [ffmpeg, "-y", "-loglevel", "error", "-framerate", str(args.fps),
                   "-i", os.path.join(frames_dir, "frame_%04d.png"), "-c:v", "libx264",
                   "-pix_fmt", "yuv420p", "-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2", movie]
            if subprocess.run(cmd).returncode != 0:
                print("error: ffmpeg failed", file=sys.stderr)
                return 1
    simple.Delete(view)
    del view
    fd = data.GetFieldData()

    def series(name):
        a = fd.GetArray(name)
        return [a.GetValue(i) for i in range(a.GetNumberOfTuples())] if a else []

    angles, distances = series("EjectionAngle"), series("EjectionDistance")
    front = series("ShockFrontHistory")
    frame_times = times[:len(front)]
    # Shock speed: slope of the front while it is inside the ground (below 80 % of the depth).
    depth = args.ground_depth
    inside = [(t, f) for t, f in zip(frame_times, front) if 0.0 < f < 0.8 * depth]
    shock_speed = fit_slope([p[0] for p in inside], [p[1] for p in inside])
    # Mean ejection angle in three bands of launch distance.
    bands = []
    if distances:
        edge = max(distances)
        for lo, hi in [(0.0, edge / 3), (edge / 3, 2 * edge / 3), (2 * edge / 3, edge * 1.0001)]:
            sel = [a for a, d in zip(angles, distances) if lo <= d < hi]
            bands.append({"from_m": round(lo, 4), "to_m": round(hi, 4), "count": len(sel),
                          "mean_angle_deg": round(sum(sel) / len(sel), 2) if sel else None})
    plot_files = plots(args.output_dir, distances, angles, frame_times, front)
    mean_angle = sum(angles) / len(angles) if angles else float("nan")
    report = {
        "example": "hard_disk_movie",
        "preset": args.preset,
        "disks": data.GetNumberOfPoints(),
        "ground_disks": int(field_value(data, "GroundDisks")),
        "frames": len(times),
        "end_time_s": times[-1],
        "pair_collisions": int(field_value(data, "PairCollisions")),
        "seconds_run_and_render": round(elapsed, 2),
        "kinetic_energy_start_J_per_m": field_value(first, "KineticEnergy"),
        "kinetic_energy_end_J_per_m": field_value(data, "KineticEnergy"),
        "ejected_disks": len(angles),
        "mean_ejection_angle_deg": round(mean_angle, 2) if angles else None,
        "z_model_ejection_angle_deg": "45 (Z = 3) to 56 (Z = 3.5)",
        "ejection_angle_by_distance": bands,
        "shock_speed_m_s": round(shock_speed, 3) if not math.isnan(shock_speed) else None,
        "impact_speed_m_s": args.impact_speed if args.preset == "Custom" else "preset",
        "crater_depth_m": field_value(data, "CraterDepth"),
        "crater_width_m": field_value(data, "CraterWidth"),
        "movie": os.path.basename(movie) if movie else None,
        "plots": plot_files,
    }
    last = os.path.join("frames", f"frame_{len(times) - 1:04d}.png")
    write_report(args.output_dir, "hard-disk crater (event-driven)", last, report)
    print(f"      {len(angles)} ejected disks, mean ejection angle {mean_angle:.1f} deg "
          f"(Z-model 45-56), shock speed {shock_speed:.2f} m/s", flush=True)
    print(f"wrote {len(times)} frames{', movie.mp4' if movie else ''}, plots and report in "
          f"{args.output_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

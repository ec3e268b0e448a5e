"""Hypervelocity debris cloud: an aluminium sphere through an aluminium plate (BondedImpact).

The headline case of Watson & Steinhauser 2017 (Materials 10:379): D = 9.53 mm at 6.7 km/s on a
plate of t/D = 0.425, bonded-particle law eps = 0.01 J, kappa = 4.56e6 N/m, r_cut = 1.5 sigma,
observed at 32 us. Small by default (1e4 particles, about a minute on two cores); the paper used
7.4e5 (--particles). Writes a side view of the debris cloud coloured by fragment (the analogue
of the paper's Figure 11), report.md and report.json with the measured fragmentation F,
length ratio R = L_a/L_r and axial velocity v_a/v0 next to the paper's and the experiment's.
The cloud is measured by mass quantiles (--cloud-mass-fraction, Solvers/bonded/BondedFragments.h):
the outline of the bulk that a photograph shows, not the stray particles; v_a is also given as
the leading edge's displacement between the last two outputs, the experiment's measure.
--dissipation ShockViscosity runs the model with shock heating (docs/physics.md §5.1); --compare
runs the paper's model and that one side by side (debris_cloud_compare.png). --set PROPERTY=VALUE
sets any other BondedImpact property (for example the shock heating's ShockViscosityQuadratic).

    scripts/pvbatch examples/hvi_debris_cloud.py --help
"""

import argparse
import os
import sys
import time

from craterkit import fetch, field_value, load_plugin, print_progress, property_settings
from craterkit.cross_section import show_point_spheres
from craterkit.report import write_report

# What the paper states in its text (figures give the rest only as plots).
PAPER = {
    "R_experiment": "1.55 (Section 3.1, the photograph of Figure 6)",
    "R_simulation": "local maximum of Figure 9 at (0.01, 4.56e6), between its plateau ~1.47 and "
                    "peak 1.54 (Section 3.1); no number printed",
    "va_over_v0": "Figures 10 and 13 only (the simulation over-predicts Piekutowski's "
                  "measurement, Section 3.2.1); no number printed",
    "F": "complete fragmentation of the impactor (Figure 14, Section 3.2.2); model valid where "
         "F >= 0.3 (Section 3.3, Figures 16b and 17)",
}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--particles", type=float, default=1e4,
                   help="approximate particle count (the paper: 7.4e5)")
    p.add_argument("--spacing", type=float, default=0.0,
                   help="lattice spacing in m; 0: from --particles (the paper's: 2.05e-4)")
    p.add_argument("--plate-width-ratio", type=float, default=4.0, help="plate side / D")
    p.add_argument("--impact-speed", type=float, default=6700.0, help="m/s")
    p.add_argument("--thickness-ratio", type=float, default=0.425, help="plate t/D")
    p.add_argument("--diameter", type=float, default=9.53e-3, help="sphere diameter, m")
    p.add_argument("--end-time", type=float, default=32e-6, help="s (the paper: 32 us)")
    p.add_argument("--outputs", type=int, default=4, help="number of output times after 0")
    p.add_argument("--seed", type=int, default=1, help="seed of the Boltzmann jitter")
    p.add_argument("--cloud-mass-fraction", type=float, default=0.95,
                   help="fraction of the cloud's mass inside the measured extents (1: every "
                        "particle, max - min); see Solvers/bonded/BondedFragments.h")
    p.add_argument("--dissipation", choices=("None", "ShockViscosity"), default="None",
                   help="None: the paper's model; ShockViscosity: with shock heating")
    p.add_argument("--compare", action="store_true",
                   help="run both models and show their clouds side by side")
    p.add_argument("--set", action="append", default=[], metavar="PROPERTY=VALUE",
                   help="any other BondedImpact property, for every model run, e.g. --set "
                        "ShockViscosityQuadratic=0.1 --set Temperature=2e-3")
    p.add_argument("--output-dir", default="results/hvi_debris_cloud")
    p.add_argument("--width", type=int, default=1200, help="image width in pixels")
    args = p.parse_args(argv)
    args.settings = property_settings(p, args.set)
    return args


def render_side_view(simple, source, data, filename, width, label):
    """Side view (along z) of every particle, coloured by fragment: the 15 largest fragments
    each in their own colour, all smaller ones (mostly single particles) in the last."""
    view = simple.CreateView("RenderView")
    height = int(width * 9 / 16)
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.ViewTime = field_value(data, "Time")  # the view renders its own time, not the last update
    capped = simple.Calculator(Input=source, ResultArrayName="Fragment",
                               Function="min(FragmentId, 15)")
    # Splats, not sphere glyphs (the model's particles share σ): glyphs took 14 GB at the paper's
    # 7.4e5 particles (benchmarks/README.md, the headline run).
    radius = data.GetPointData().GetArray("Radius").GetRange()[1]
    display, lut = show_point_spheres(simple, capped, view, "Fragment", "Turbo", radius)
    lut.RescaleTransferFunction(0.0, 15.0)
    display.SetScalarBarVisibility(view, True)
    bar = simple.GetScalarBar(lut, view)
    bar.Title = "fragment (0 largest, 15: the rest)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    text = simple.Text(Text=label)
    text_display = simple.Show(text, view)
    text_display.WindowLocation = "Upper Left Corner"
    text_display.FontSize = 20
    text_display.Color = [0.1, 0.1, 0.1]
    simple.Render(view)
    b = data.GetBounds()
    cx, cy = 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3])
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraPosition = [cx, cy, 10.0 * (b[1] - b[0] + b[3] - b[2])]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = 0.55 * max(b[3] - b[2], (b[1] - b[0]) * height / width)
    simple.Render(view)
    simple.SaveScreenshot(filename, view, ImageResolution=[width, height], TransparentBackground=0)
    simple.Delete(view)


def run_model(simple, args, dissipation):
    """One BondedImpact run to --end-time with the given Dissipation, printing each output;
    returns the source, its last output and the leading edge's speed from the last two outputs."""
    source = simple.BondedImpact(ParticleCount=args.particles, Spacing=args.spacing,
                                 PlateWidthRatio=args.plate_width_ratio,
                                 ImpactSpeed=args.impact_speed,
                                 ThicknessRatio=args.thickness_ratio, Diameter=args.diameter,
                                 Seed=args.seed, EndTime=args.end_time, Dissipation=dissipation,
                                 CloudMassFraction=args.cloud_mass_fraction,
                                 OutputInterval=args.end_time / max(1, args.outputs), **args.settings)
    print_progress(source, f"BondedImpact ({dissipation})")
    data, edges, energies = None, [], []  # edges: (time, leading edge behind the plate)
    for t in source.TimestepValues:
        source.UpdatePipeline(t)
        data = fetch(source)
        if data.GetNumberOfPoints() == 0:
            return source, None, 0.0, 0.0
        edges.append((field_value(data, "Time"), field_value(data, "DebrisCloudLeadingEdge")))
        energies.append(field_value(data, "TotalEnergy"))
        print(f"{dissipation}: t = {1e6 * field_value(data, 'Time'):6.2f} us, step "
              f"{int(field_value(data, 'Step'))}, broken bonds {int(field_value(data, 'BrokenBonds'))}, "
              f"F {field_value(data, 'Fragmentation'):.3f}, R {field_value(data, 'DebrisCloudRatio'):.3f}, "
              f"v_a/v0 {field_value(data, 'AxialVelocityRatio'):.3f}, internal energy "
              f"{field_value(data, 'InternalEnergyTotal'):.4g} J", flush=True)
    (t1, s1), (t2, s2) = edges[-2], edges[-1]  # Section 3.1's measure
    va_snapshots = (s2 - s1) / (t2 - t1) / args.impact_speed if t2 > t1 and s1 > 0 else 0.0
    drift = (energies[-1] - energies[0]) / energies[0] if energies[0] else 0.0
    return source, data, va_snapshots, drift


def measures(data, va_snapshots, drift):
    """The report's figures of one run's last output."""
    value = lambda name: field_value(data, name)  # noqa: E731
    return {"F_measured": round(value("Fragmentation"), 4), "R_measured": round(value("DebrisCloudRatio"), 4),
            "va_over_v0_measured": round(value("AxialVelocityRatio"), 4),
            "va_over_v0_two_snapshots": round(va_snapshots, 4),
            "front_sharpness": round(value("DebrisCloudFrontSharpness"), 4),
            "largest_cloud_fragment_fraction": round(value("LargestCloudFragmentFraction"), 4),
            "internal_energy_J": value("InternalEnergyTotal"), "total_energy_J": value("TotalEnergy"),
            "total_energy_drift": drift, "broken_bonds": int(value("BrokenBonds")), "bonds": int(value("Bonds")),
            "cloud_particles": int(value("CloudParticles")), "cloud_fragments": int(value("CloudFragments")),
            "debris_cloud_axial_length_m": value("DebrisCloudAxialLength"),
            "debris_cloud_radial_extent_m": value("DebrisCloudRadialExtent")}


def side_by_side(images, filename):
    """The PNG IMAGES next to each other, left to right, in FILENAME."""
    from vtkmodules.vtkFiltersCore import vtkImageAppend
    from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
    append = vtkImageAppend()
    append.SetAppendAxis(0)
    for image in images:
        reader = vtkPNGReader()
        reader.SetFileName(image)
        reader.Update()
        append.AddInputData(reader.GetOutput())
    writer = vtkPNGWriter()
    writer.SetFileName(filename)
    writer.SetInputConnection(append.GetOutputPort())
    writer.Write()


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    simple = load_plugin()
    models = ("None", "ShockViscosity") if args.compare else (args.dissipation,)
    runs, images = {}, []
    for model in models:
        start = time.time()
        source, data, va_snapshots, drift = run_model(simple, args, model)
        if data is None:
            print("error: the bonded run failed; see the error above", file=sys.stderr)
            return 1
        m = measures(data, va_snapshots, drift)
        m["run_seconds"] = round(time.time() - start, 1)
        m["particle_steps_per_s"] = round(data.GetNumberOfPoints() * field_value(data, "Step") / m["run_seconds"])
        m["set_properties"] = {key: source.GetPropertyValue(key) for key in args.settings}  # as the source holds them
        runs[model] = m
        images.append(os.path.join(args.output_dir, "debris_cloud.png" if len(models) == 1 else
                                   f"debris_cloud_{model}.png"))
        render_side_view(simple, source, data, images[-1], args.width,
                         f"{model}: {data.GetNumberOfPoints()} particles, v0 = {args.impact_speed / 1000:.2f} km/s, "
                         f"t/D = {args.thickness_ratio}, t = {1e6 * field_value(data, 'Time'):.1f} us\n"
                         f"F = {m['F_measured']:.3f}, R = {m['R_measured']:.2f}, v_a/v0 = "
                         f"{m['va_over_v0_measured']:.3f}, front {m['front_sharpness']:.3f} L_a")
        print(f"{model}: F = {m['F_measured']:.3f}, R = {m['R_measured']:.3f} (experiment 1.55), v_a/v0 = "
              f"{m['va_over_v0_measured']:.3f} (two snapshots {m['va_over_v0_two_snapshots']:.3f}), front width "
              f"{m['front_sharpness']:.3f} L_a, internal energy {m['internal_energy_J']:.4g} J, total energy "
              f"drift {drift:.2e}; {int(field_value(data, 'Step'))} steps in {m['run_seconds']} s", flush=True)
        simple.Delete(source)
    if args.compare:
        images.append(os.path.join(args.output_dir, "debris_cloud_compare.png"))
        side_by_side(images[:2], images[-1])
    report = {"example": "hvi_debris_cloud", "particles": data.GetNumberOfPoints(),
              "impact_speed_m_s": args.impact_speed, "thickness_ratio": args.thickness_ratio,
              "end_time_s": field_value(data, "Time"), "steps": int(field_value(data, "Step")),
              "time_step_s": field_value(data, "TimeStep"), "cloud_mass_fraction": args.cloud_mass_fraction,
              "F_paper": PAPER["F"], "R_experiment": PAPER["R_experiment"],
              "R_paper_simulation": PAPER["R_simulation"], "va_over_v0_paper": PAPER["va_over_v0"],
              "frames": [os.path.basename(i) for i in images]}
    if args.compare:
        report["models"] = runs
    else:
        report.update(runs[models[0]], dissipation=models[0])
    write_report(args.output_dir, "hypervelocity debris cloud (bonded particles)", os.path.basename(images[-1]),
                 report)
    print(f"wrote {', '.join(images)}, report.md and report.json")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

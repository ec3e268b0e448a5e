"""Bonded-particle sweeps of Watson & Steinhauser 2017: calibration grid and fragmentation map.

1. Calibration (the paper's Figures 7, 9, 10): the headline impact (9.53 mm Al sphere, 6.7 km/s,
   t/D = 0.425, to 32 us) over a grid of (eps, kappa); contour plots of the debris cloud's
   length ratio R = L_a/L_r (experiment: 1.55) and axial velocity v_a/v0, and of F.
2. Fragmentation map (the paper's Figure 16): F = N_frag/N_part (Eq. 21) over (t/D, v0) at the
   best fit (0.01 J, 4.56e6 N/m); the paper's validity cut-off F = 0.3 is drawn.
The grids default to the values the paper's text names (eps 0.01, 0.1, 1; kappa 1.14e6,
4.56e6, 9.12e6); its figures hold more points, which the text does not list. One progress line
per run; finished runs are kept in results.json, so an interrupted sweep resumes where it
stopped. --quick runs a 2 x 2 version of each at a tiny size (for the tests).

    scripts/pvbatch examples/hvi_sweep.py --help
"""

import argparse
import json
import math
import os
import sys
import time

from craterkit import fetch, field_value, load_plugin


def floats(text):
    return [float(v) for v in text.split(",")]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--particles", type=float, default=1e4, help="approximate particle count")
    p.add_argument("--end-time", type=float, default=32e-6, help="s")
    p.add_argument("--epsilons", type=floats, default=[0.01, 0.1, 1.0], help="J, comma-separated")
    p.add_argument("--kappas", type=floats, default=[1.14e6, 4.56e6, 9.12e6], help="N/m")
    p.add_argument("--thickness-ratios", type=floats, default=[0.05, 0.1, 0.2, 0.425, 0.8])
    p.add_argument("--speeds", type=floats, default=[3000.0, 5000.0, 6700.0, 8000.0], help="m/s")
    p.add_argument("--quick", action="store_true", help="2 x 2 grids at a tiny size")
    p.add_argument("--output-dir", default="results/hvi_sweep")
    args = p.parse_args(argv)
    if args.quick:
        args.particles, args.end_time = 600, 4e-6
        args.epsilons, args.kappas = [0.01, 1.0], [1.14e6, 4.56e6]
        args.thickness_ratios, args.speeds = [0.2, 0.425], [5000.0, 6700.0]
    return args


def run_key(args, eps, kappa, ratio, speed):
    return (f"N={args.particles:g} T={args.end_time:g} eps={eps:g} kappa={kappa:g} "
            f"tD={ratio:g} v0={speed:g}")


def run_one(simple, args, eps, kappa, ratio, speed):
    source = simple.BondedImpact(ParticleCount=args.particles, Epsilon=eps, Kappa=kappa,
                                 ThicknessRatio=ratio, ImpactSpeed=speed, EndTime=args.end_time,
                                 OutputInterval=args.end_time)
    source.UpdatePipeline(0.0)
    start = fetch(source)
    source.UpdatePipeline(args.end_time)
    data = fetch(source)
    simple.Delete(source)
    if start.GetNumberOfPoints() == 0 or data.GetNumberOfPoints() == 0:
        raise RuntimeError("the run failed; see the error above")
    result = {key: field_value(data, name) for key, name in
              [("F", "Fragmentation"), ("R", "DebrisCloudRatio"),
               ("va_v0", "AxialVelocityRatio"), ("broken_bonds", "BrokenBonds"), ("time", "Time")]}
    result["particles"] = data.GetNumberOfPoints()
    # Conservation through the run: total energy (with the broken bonds' energy) and momentum.
    e0 = field_value(start, "TotalEnergy")
    result["energy_drift"] = (field_value(data, "TotalEnergy") - e0) / e0
    p0, p1 = (d.GetFieldData().GetArray("TotalMomentum").GetTuple3(0) for d in (start, data))
    result["momentum_change"] = math.dist(p0, p1) / math.hypot(*p0)
    return result


def contour(x, y, values, xlabel, ylabel, title, filename, logx=False, level=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    X, Y = np.meshgrid(x, y)
    Z = np.array(values).reshape(len(y), len(x))
    fig, ax = plt.subplots(figsize=(6, 4.5), dpi=100)
    filled = ax.contourf(X, Y, Z, levels=12, cmap="viridis")
    fig.colorbar(filled, ax=ax)
    if level is not None and Z.min() < level < Z.max():
        ax.contour(X, Y, Z, levels=[level], colors="red", linewidths=2)
    ax.plot(X.ravel(), Y.ravel(), "k.", ms=4)
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(filename)
    plt.close(fig)


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    path = os.path.join(args.output_dir, "results.json")
    results = json.load(open(path)) if os.path.isfile(path) else {}
    simple = load_plugin()
    calibration = [(e, k, 0.425, 6700.0) for k in args.kappas for e in args.epsilons]
    fragmentation = [(0.01, 4.56e6, r, v) for v in args.speeds for r in args.thickness_ratios]
    todo = calibration + [run for run in fragmentation if run not in calibration]
    for number, (eps, kappa, ratio, speed) in enumerate(todo, 1):
        key = run_key(args, eps, kappa, ratio, speed)
        if key in results:
            print(f"[{number}/{len(todo)}] {key}: kept", flush=True)
            continue
        start = time.time()
        results[key] = run_one(simple, args, eps, kappa, ratio, speed)
        r = results[key]
        print(f"[{number}/{len(todo)}] {key}: F {r['F']:.3f}, R {r['R']:.3f}, "
              f"v_a/v0 {r['va_v0']:.3f} ({time.time() - start:.1f} s)", flush=True)
        with open(path + ".part", "w") as f:
            json.dump(results, f, indent=1)
        os.replace(path + ".part", path)

    def grid(runs, name):
        return [results[run_key(args, *run)][name] for run in runs]

    out = args.output_dir
    contour(args.epsilons, args.kappas, grid(calibration, "R"), "epsilon (J)", "kappa (N/m)",
            "length ratio R = L_a/L_r (experiment 1.55)", os.path.join(out, "calibration_R.png"),
            logx=True, level=1.55)
    contour(args.epsilons, args.kappas, grid(calibration, "va_v0"), "epsilon (J)", "kappa (N/m)",
            "axial velocity v_a/v0", os.path.join(out, "calibration_va.png"), logx=True)
    contour(args.epsilons, args.kappas, grid(calibration, "F"), "epsilon (J)", "kappa (N/m)",
            "fragmentation F", os.path.join(out, "calibration_F.png"), logx=True, level=0.3)
    contour(args.thickness_ratios, [v / 1000 for v in args.speeds], grid(fragmentation, "F"),
            "t/D", "v0 (km/s)", "fragmentation F (red: the paper's cut-off 0.3)",
            os.path.join(out, "fragmentation_map.png"), level=0.3)
    print(f"{len(todo)} runs; wrote results.json and four contour plots in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

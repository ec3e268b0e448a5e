"""Build a granular bed and render a crater-style cross-section of it, headless.

The main job of scripts/demo until the SCI pipeline exists: a bed in the SCI-like
hemispherical container, a slab through the axis coloured by height, the original surface
dashed and the central axis drawn. Writes a PNG, report.md and report.json.

    scripts/pvbatch examples/bed_cross_section.py --help
    scripts/pvbatch examples/bed_cross_section.py --packing HCP --particles 50000
"""

import argparse
import math
import os
import sys
import time

from craterkit import field_value, fetch, load_plugin
from craterkit.cross_section import render_cross_section
from craterkit.report import write_report


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--packing", choices=["RCP", "HCP"], default="RCP")
    p.add_argument("--container", choices=["Bowl", "Box"], default="Bowl")
    p.add_argument("--container-radius", type=float, default=15.0,
                   help="bowl radius in m (the box is 2R x 2R x R)")
    p.add_argument("--particle-radius", type=float, default=0.6, help="m")
    p.add_argument("--particles", type=int, default=None,
                   help="approximate particle count; sets the particle radius")
    p.add_argument("--packing-fraction", type=float, default=0.56, help="RCP placement")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--output-dir", default="results")
    p.add_argument("--width", type=int, default=1600, help="image width in pixels")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    os.makedirs(args.output_dir, exist_ok=True)
    simple = load_plugin()
    R = args.container_radius
    if args.container == "Bowl":
        volume = 2.0 / 3.0 * math.pi * R ** 3
    else:
        volume = 2 * R * 2 * R * R
    fraction = 0.7405 if args.packing == "HCP" else args.packing_fraction
    radius = args.particle_radius
    if args.particles:
        radius = (fraction * volume / (args.particles * 4.0 / 3.0 * math.pi)) ** (1.0 / 3.0)

    print(f"[1/3] building a {args.packing} bed in a {args.container} of radius {R} m, "
          f"particle radius {radius:.4g} m", flush=True)
    start = time.time()
    bed = simple.GranularBed(Packing=args.packing, Container=args.container,
                             ContainerRadius=R, BoxSize=[2 * R, 2 * R, R],
                             ParticleRadius=radius, PackingFraction=args.packing_fraction,
                             RandomSeed=args.seed)
    data = fetch(bed)
    elapsed = time.time() - start
    n = data.GetNumberOfPoints()
    if n == 0:
        print("error: the bed is empty; see the error above", file=sys.stderr)
        return 1
    phi = field_value(data, "BulkPackingFraction")
    print(f"      {n} particles in {elapsed:.1f} s, bulk packing fraction {phi:.4f}", flush=True)

    print("[2/3] rendering the cross-section", flush=True)
    image = os.path.join(args.output_dir, "bed_cross_section.png")
    label = f"{args.packing}, r = {radius:.3g} m, N = {n}"
    render_cross_section(bed, image, label=label,
                         resolution=(args.width, int(args.width * 9 / 16)))

    print("[3/3] writing the report", flush=True)
    report = {
        "example": "bed_cross_section",
        "packing": args.packing,
        "container": args.container,
        "container_radius_m": R,
        "particle_radius_m": radius,
        "particles": n,
        "bulk_packing_fraction": phi,
        "top_height_m": field_value(data, "TopHeight"),
        "coordination_number": field_value(data, "CoordinationNumber"),
        "seed": args.seed,
        "bed_seconds": round(elapsed, 3),
        "image": os.path.basename(image),
    }
    write_report(args.output_dir, "granular bed cross-section", os.path.basename(image), report)
    print(f"wrote {image}, report.md and report.json in {args.output_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

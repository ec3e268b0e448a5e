#!/usr/bin/env python3
"""Hard disks: CraterKit's event-driven engine against DynamO on the same hard-disk gas.

    benchmarks/hard_disk/run.py                                   # CraterKit alone
    benchmarks/hard_disk/run.py --dynarun /path/to/dynarun        # and DynamO, with the ratio
    benchmarks/hard_disk/run.py --sizes 1000 100000 --repeats 3

The gas of `ck_edmd_bench` (benchmarks/README.md): N equal disks of radius 1 and unit mass in
a periodic square box at area fraction 0.4, started on a square lattice with unit speeds in
random directions, equilibrated for 2 N collisions, then timed over max(10 N, 2e6)
collisions, on one core (taskset -c 0).

DynamO (dynamomd.org, a general event-driven MD code; not part of CraterKit and not built by
it: give the path of a `dynarun` you built) is three-dimensional only. Hard spheres whose
centres lie in the plane z = 0 with v_z = 0 stay there for ever (an in-plane collision has no
z component), so spheres of diameter 2 in a periodic box four diameters thick (the thinnest
its cell list takes) are exactly these hard disks. This script writes that configuration
(the same lattice; velocity directions from the same distribution, not the same random
numbers), equilibrates it for 2 N collisions, and times
`dynarun -E -c T` (T collisions, no output plugins) less the time of `dynarun -E -c 1`
(loading and set-up). It checks that every sphere ended with z = 0 and v_z = 0 and that the
kinetic energy is unchanged. DynamO counts only pair collisions in `-c`, as ck_edmd_bench
does; neither counts cell crossings.

The host's speed varies by up to 30 % from run to run (a shared machine): the repeats are
interleaved (CraterKit, DynamO, CraterKit, ...) and the table gives the best of each.
"""

import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from shutil import which

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = os.path.join(ROOT, "build", "benchmarks", "hard_disk", "ck_edmd_bench")


def one_core(cmd):
    return (["taskset", "-c", "0"] if which("taskset") else []) + cmd


def craterkit(n, eta):
    out = subprocess.run(one_core([BENCH, repr(eta), str(n)]), check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def write_dynamo_config(path, n, eta, seed=5):
    """N spheres of diameter 2 on a square lattice in the plane z = 0, v_z = 0, unit speeds."""
    r, diam = 1.0, 2.0
    side = math.sqrt(n * math.pi * r * r / eta)
    k = int(math.ceil(math.sqrt(n)))
    rng = random.Random(seed)
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<DynamOconfig version="1.5.0">\n <Simulation>\n'
                '  <Scheduler Type="NeighbourList"><Sorter Type="BoundedPQMinMax3"/></Scheduler>\n')
        f.write(f'  <SimulationSize x="{side!r}" y="{side!r}" z="{4.0000001 * diam!r}"/>\n')
        f.write('  <Genus><Species Mass="1" Name="Bulk" Type="Point"><IDRange Type="All"/></Species></Genus>\n'
                '  <BC Type="PBC"/>\n  <Topology/>\n  <Interactions>\n'
                f'   <Interaction Type="HardSphere" Diameter="{diam!r}" Name="Bulk"><IDPairRange Type="All"/></Interaction>\n'
                '  </Interactions>\n  <Locals/>\n  <Globals/>\n  <SystemEvents/>\n  <Dynamics Type="Newtonian"/>\n'
                ' </Simulation>\n <Properties/>\n <ParticleData>\n')
        for i in range(n):  # DynamO's box is centred on the origin
            x = (i % k + 0.5) * side / k - 0.5 * side
            y = (i // k + 0.5) * side / k - 0.5 * side
            a = 2.0 * math.pi * rng.random()
            f.write(f'  <Pt ID="{i}"><P x="{x!r}" y="{y!r}" z="0"/><V x="{math.cos(a)!r}" y="{math.sin(a)!r}" z="0"/></Pt>\n')
        f.write(' </ParticleData>\n</DynamOconfig>\n')


def planar_and_energy(path):
    """Largest |z|, largest |v_z| and the kinetic energy per particle of a DynamO configuration."""
    zmax = vzmax = ke = 0.0
    count = 0
    for _, el in ET.iterparse(path):
        if el.tag == "P":
            zmax = max(zmax, abs(float(el.get("z"))))
        elif el.tag == "V":
            vx, vy, vz = (float(el.get(c)) for c in "xyz")
            vzmax = max(vzmax, abs(vz))
            ke += 0.5 * (vx * vx + vy * vy + vz * vz)
            count += 1
        if el.tag == "Pt":
            el.clear()
    return zmax, vzmax, ke / max(count, 1)


def dynamo(dynarun, n, eta, work):
    """Collisions per second of dynarun on the gas, after a 2 N-collision equilibration.
    dynarun runs in the work folder, where its own output file (output.xml.bz2) lands."""
    work = os.path.abspath(work)
    start, eq = os.path.join(work, f"start_{n}.xml"), os.path.join(work, f"eq_{n}.xml")
    if not os.path.exists(eq):
        write_dynamo_config(start, n, eta)
        subprocess.run([dynarun, start, "-c", str(2 * n), "-o", eq], check=True, capture_output=True, cwd=work)
    timed = max(10 * n, 2_000_000)
    end, end1 = os.path.join(work, f"end_{n}.xml"), os.path.join(work, f"end1_{n}.xml")
    t0 = time.perf_counter()
    subprocess.run(one_core([dynarun, "-E", eq, "-c", "1", "-o", end1]), check=True, capture_output=True, cwd=work)
    setup = time.perf_counter() - t0
    t0 = time.perf_counter()
    subprocess.run(one_core([dynarun, "-E", eq, "-c", str(timed), "-o", end]), check=True, capture_output=True, cwd=work)
    seconds = time.perf_counter() - t0 - setup
    z, vz, ke = planar_and_energy(end)
    _, _, ke0 = planar_and_energy(eq)
    if z != 0.0 or vz != 0.0:
        sys.exit(f"DynamO's run left the plane (|z| {z}, |vz| {vz}): not the same gas")
    if abs(ke / ke0 - 1.0) > 1e-9:
        sys.exit(f"DynamO's kinetic energy changed by {ke / ke0 - 1.0:.2e}")
    return {"collisions": timed, "seconds": seconds, "collisions_per_s": timed / seconds,
            "setup_s": setup, "kinetic_energy_change": ke / ke0 - 1.0}


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--area-fraction", type=float, default=0.4)
    p.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000, 100000, 1000000])
    p.add_argument("--repeats", type=int, default=2)
    p.add_argument("--dynarun", default=os.environ.get("DYNARUN", ""), help="a DynamO dynarun binary (or $DYNARUN)")
    p.add_argument("--work", default="", help="folder for DynamO's configurations (default: a temporary one)")
    args = p.parse_args(argv)
    if not os.path.exists(BENCH):
        sys.exit(f"{BENCH} is missing: build first (scripts/test or scripts/demo)")
    if args.dynarun and not os.access(args.dynarun, os.X_OK):
        sys.exit(f"--dynarun {args.dynarun}: not an executable")
    if not (0.0 < args.area_fraction < 0.8):
        sys.exit("--area-fraction must be in (0, 0.8)")
    work = args.work or tempfile.mkdtemp(prefix="ck_dynamo_")
    os.makedirs(work, exist_ok=True)
    rows = []
    for n in args.sizes:
        ck, dy = [], []
        for rep in range(args.repeats):
            ck.append(craterkit(n, args.area_fraction))
            print(f"N = {n}: CraterKit {ck[-1]['collisions_per_s']:.3g} collisions/s", flush=True)
            if args.dynarun:
                dy.append(dynamo(args.dynarun, n, args.area_fraction, work))
                print(f"N = {n}: DynamO    {dy[-1]['collisions_per_s']:.3g} collisions/s "
                      f"(set-up {dy[-1]['setup_s']:.2f} s excluded; stayed planar, energy change "
                      f"{dy[-1]['kinetic_energy_change']:.1e})", flush=True)
        best_ck = max(c["collisions_per_s"] for c in ck)
        best_dy = max(d["collisions_per_s"] for d in dy) if dy else None
        rows.append((n, best_ck, best_dy, ck[0]))
    print("\n| N | CraterKit collisions/s | ns per collision | cell crossings per collision | DynamO collisions/s | ratio |")
    print("|---|---|---|---|---|---|")
    for n, c, d, first in rows:
        ratio = f"{c / d:.1f}x" if d else "-"
        dtext = f"{d:.3g}" if d else "-"
        print(f"| {n} | {c:.3g} | {1e9 / c:.0f} | {first['cell_crossings_per_collision']:.2f} | {dtext} | {ratio} |")
    print(f"\n(best of {args.repeats}, area fraction {args.area_fraction}, one core"
          f"{'; DynamO: ' + args.dynarun if args.dynarun else '; no DynamO given (--dynarun)'})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""The whole DEM pipeline at 10^6 grains in one pvbatch process: GranularBed (an HCP box bed)
-> DEMIntegrator (with an impactor 6.7 times the grains' radius, 150 steps) -> CraterProfile
-> FragmentAnalysis. Prints the seconds of each stage, the resident memory after it (VmRSS,
and its change) and the peak so far (VmHWM), in MiB as /proc/self/status gives them (its "kB"
are KiB), and the peak per particle in KiB and in kB of 1000 bytes.

    scripts/pvbatch benchmarks/pipeline_1e6/run.py                      # ~10^6 grains
    scripts/pvbatch benchmarks/pipeline_1e6/run.py --particles 100000   # a quick check
    scripts/pvbatch benchmarks/pipeline_1e6/run.py --particles 1e7      # ~10^7: about 20 GB

Goals (benchmarks/README.md): at most 2 kB a grain end to end (the whole process's peak over the
particles); no analysis stage (CraterProfile,
FragmentAnalysis) slower than 2 s at 10^6 grains. The DEM's contact parameters and time step
are those of benchmarks/dem_bed_impact (r = 5 cm, 2000 kg/m^3, k_N = 4.19e6 N/m, dt = 3.70e-5 s),
given explicitly so that the run takes exactly 150 steps.
"""

import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from craterkit import load_plugin  # noqa: E402

RADIUS = 0.05        # m, the grains
DENSITY = 2000.0     # kg/m^3
HCP = 0.74048048969306104
STIFFNESS = 4.19e6   # N/m
STEP = 3.70e-5       # s


def memory_kb():
    """(VmRSS, VmHWM) of this process in KiB."""
    out = {}
    with open("/proc/self/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmRSS", "VmHWM"):
                out[key] = int(value.split()[0])
    return out["VmRSS"], out["VmHWM"]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--particles", type=float, default=1e6, help="grains requested (approximate)")
    p.add_argument("--steps", type=int, default=150, help="DEM steps")
    p.add_argument("--impactor-ratio", type=float, default=6.7,
                   help="impactor radius over the grains' radius")
    p.add_argument("--json", default=None, help="also write the figures to this file")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    simple = load_plugin()
    # A box twice as wide as deep holding the requested number of grains at HCP's packing.
    volume = args.particles * 4.0 / 3.0 * 3.141592653589793 * RADIUS ** 3 / HCP
    depth = (volume / 4.0) ** (1.0 / 3.0)
    box = [2.0 * depth, 2.0 * depth, depth]
    stages = []
    rss0, _ = memory_kb()
    last = [rss0]

    def stage(name, proxy, t=None):
        start = time.time()
        if t is None:
            proxy.UpdatePipeline()
        else:
            proxy.UpdatePipeline(t)
        seconds = time.time() - start
        rss, hwm = memory_kb()
        stages.append({"stage": name, "seconds": round(seconds, 3), "rss_MiB": round(rss / 1024, 1),
                       "rss_change_MiB": round((rss - last[0]) / 1024, 1),
                       "peak_MiB": round(hwm / 1024, 1)})
        print(f"{name:17s} {seconds:8.2f} s   RSS {rss / 1024:8.1f} MiB ({(rss - last[0]) / 1024:+8.1f})"
              f"   peak {hwm / 1024:8.1f} MiB", flush=True)
        last[0] = rss

    print(f"box {box[0]:.3f} x {box[1]:.3f} x {box[2]:.3f} m, grains of radius {RADIUS} m, "
          f"{os.environ.get('OMP_NUM_THREADS', 'default')} threads, load average "
          f"{os.getloadavg()[0]:.2f}; RSS before {rss0 / 1024:.1f} MiB", flush=True)
    bed = simple.GranularBed(Packing="HCP", Container="Box", BoxSize=box, ParticleRadius=RADIUS,
                             ParticleDensity=DENSITY, MaxParticles=max(2000000, int(1.1 * args.particles)))
    stage("GranularBed", bed)
    n = bed.GetDataInformation().GetNumberOfPoints()
    if n == 0:
        sys.exit("GranularBed made no grains (its error is above)")
    end = (args.steps - 0.5) * STEP  # the first step at or after it: step `steps`
    dem = simple.DEMIntegrator(Input=bed, NormalStiffness=STIFFNESS, TimeStep=STEP,
                               AddImpactor=1, ImpactorRadius=args.impactor_ratio * RADIUS,
                               ImpactorDensity=DENSITY, ImpactSpeed=1.0, EndTime=end,
                               OutputInterval=end)
    stage("DEMIntegrator", dem, end)
    if dem.FieldData["Step"] is None:
        sys.exit("DEMIntegrator failed (its error is above)")
    steps = int(dem.FieldData["Step"].GetRange()[0])
    grains = dem.GetDataInformation().GetNumberOfPoints()
    profile = simple.CraterProfile(Input=dem)
    stage("CraterProfile", profile, end)
    fragments = simple.FragmentAnalysis(Input=dem)
    stage("FragmentAnalysis", fragments, end)
    _, peak = memory_kb()
    kib = peak / grains
    kb = peak * 1.024 / grains  # kB of 1000 bytes
    print(f"{n} bed grains + impactor = {grains} particles, {steps} DEM steps; peak "
          f"{peak / 1024:.1f} MiB = {kib:.2f} KiB = {kb:.2f} kB a particle (ParaView's own "
          f"{rss0 / 1024:.1f} MiB included); load average {os.getloadavg()[0]:.2f}", flush=True)
    slowest = max(s["seconds"] for s in stages if s["stage"] in ("CraterProfile", "FragmentAnalysis"))
    print(f"goals: <= 2 kB a grain: {'met' if kb <= 2.0 else 'NOT met'}; "
          f"analysis stages <= 2 s: {'met' if slowest <= 2.0 else 'NOT met'} (slowest {slowest:.2f} s)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"particles": grains, "steps": steps, "stages": stages,
                       "rss_before_MiB": round(rss0 / 1024, 1), "peak_MiB": round(peak / 1024, 1),
                       "KiB_per_particle": round(kib, 3), "kB_per_particle": round(kb, 3),
                       "load_average": os.getloadavg()}, f, indent=1)
    return 0 if steps == args.steps else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/python3
"""SPH benchmark: CraterKit against PySPH (Debian python3-pysph) on PySPH's own example
solid_mech/impact3d.py, then CraterKit's throughput on the SCI-like default and its scaling.

impact3d.py: a steel sphere at 3.1 km/s into an aluminium plate, elastic-plastic SPH, 36,962
particles, time step 1 ns. Both codes run the same particles, materials and number of steps
on 2 threads (PySPH with --openmp); PySPH's step loop is timed from its own log ("Run took"),
after a first run has compiled its kernels. CraterKit sums over the same neighbours (Wendland
C2 kernel with the reach of PySPH's Gaussian, 3h = 3.9 dx). Prints particle-steps per second
and the ratio.

    benchmarks/sph_impact/run.py                  # 100 steps; SCI-like scaling 1e3..5.4e5
    benchmarks/sph_impact/run.py --steps 50 --no-scaling
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def log(msg):
    print(msg, flush=True)


def run(cmd, env=None, cwd=None):
    start = time.time()
    out = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{out.stdout[-3000:]}")
    return out.stdout, time.time() - start


def pysph(steps, threads):
    import pysph  # noqa: F401  (python3-pysph must be importable by /usr/bin/python3)
    example = os.path.join(os.path.dirname(pysph.__file__), "examples", "solid_mech", "impact3d.py")
    work = tempfile.mkdtemp(prefix="ck_pysph_")
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    cmd = ["/usr/bin/python3", example, "--openmp", "--tf", f"{steps * 1e-9:.3e}", "--disable-output",
           "-d", os.path.join(work, "out")]
    out, wall = run(cmd, env=env, cwd=work)
    shutil.rmtree(work, ignore_errors=True)
    took = re.search(r"Run took:\s*([0-9.eE+-]+)\s*secs", out)
    n = re.search(r"Total:\s*(\d+)", out)
    if not took or not n:
        raise RuntimeError("could not read PySPH's log:\n" + out[-2000:])
    return int(n.group(1)), float(took.group(1)), wall


def craterkit(binary, args, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out, _ = run([binary] + args, env=env)
    rate = re.search(r"([0-9.eE+]+) particle-steps/s", out)
    return out, float(rate.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--no-scaling", action="store_true")
    a = ap.parse_args()
    binary = os.path.join(a.build, "benchmarks", "sph_impact", "ck_sph_bench")
    if not os.path.exists(binary):
        sys.exit(f"{binary} not found: build first (scripts/test or cmake --build build)")

    log(f"PySPH impact3d.py, {a.steps} steps of 1 ns, {a.threads} threads (first: compiling, not timed) ...")
    pysph(2, a.threads)
    n, took, wall = pysph(a.steps, a.threads)
    py_rate = n * a.steps / took
    log(f"PySPH: {n} particles, {a.steps} steps, run took {took:.2f} s ({wall:.1f} s with start-up): "
        f"{py_rate:.4g} particle-steps/s")
    out, ck_rate = craterkit(binary, ["pysph-impact3d", str(a.steps)], a.threads)
    log(out.strip())
    log(f"ratio CraterKit / PySPH on impact3d: {ck_rate / py_rate:.1f}x")
    out, ck_cubic = craterkit(binary, ["pysph-impact3d", str(a.steps), "2.5", "cubic"], a.threads)
    log(f"CraterKit with its default kernel (cubic spline, reach 2.5 dx; fewer neighbours): {ck_cubic:.4g} "
        f"particle-steps/s")

    if a.no_scaling:
        return
    log("SCI-like default (SPHImpact), 2e-5 s, by size:")
    for across, radius in [(4, 0.15), (4, 0.3), (6, 0.45), (8, 0.6)]:
        out, rate = craterkit(binary, ["2e-5", str(across), str(radius)], a.threads)
        first = out.splitlines()[0]
        last = out.strip().splitlines()[-1]
        log(f"  {first}\n    {last}")


if __name__ == "__main__":
    main()

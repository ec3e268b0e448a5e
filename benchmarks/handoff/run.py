#!/usr/bin/python3
"""Hand-off benchmark: CraterKit's hand-off of N SPH particles onto a bed of N spheres (time
of each step), and the alpha shape against VTK's vtkDelaunay3D with the same alpha on the
same points (the compact set), printing the ratio.

    benchmarks/handoff/run.py                     # N = 1e5 (with the VTK comparison) and 1e6
    benchmarks/handoff/run.py --sizes 1e5 --vtk-max 1e5
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="1e5,1e6")
    ap.add_argument("--vtk-max", type=float, default=2e5, help="largest N for the vtkDelaunay3D comparison")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    a = ap.parse_args()
    binary = os.path.join(a.build, "benchmarks", "handoff", "ck_handoff_bench")
    if not os.path.exists(binary):
        sys.exit(f"{binary} not found: build first")
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "2"))
    for size in a.sizes.split(","):
        out = subprocess.run([binary, size], env=env, stdout=subprocess.PIPE, text=True, check=True).stdout
        print(out.strip(), flush=True)
        if float(size) > a.vtk_max:
            continue
        alpha = float(re.search(r"alpha radius ([0-9.eE+-]+)", out).group(1))
        ours = float(re.search(r"alpha shape ([0-9.]+)", out).group(1))
        vtk = subprocess.run([os.path.join(ROOT, "scripts", "pvbatch"), os.path.join(HERE, "delaunay_vtk.py"), size,
                              str(alpha)], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
        line = [l for l in vtk.splitlines() if l.startswith("vtkDelaunay3D")]
        print(line[0] if line else vtk[-2000:], flush=True)
        if line:
            theirs = float(re.search(r": ([0-9.]+) s", line[0]).group(1))
            print(f"alpha shape: CraterKit (CGAL) {ours:.2f} s, vtkDelaunay3D {theirs:.2f} s: {theirs / ours:.1f}x",
                  flush=True)


if __name__ == "__main__":
    main()

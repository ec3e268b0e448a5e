"""Helpers the benchmark scripts share: progress lines, running a command with its time, and
the mpirun prefix for the peers (LAMMPS, LIGGGHTS) on this machine."""

import os
import subprocess
import time


def log(msg):
    print(msg, flush=True)


def run(cmd, env=None, cwd=None):
    """Runs CMD; returns its output and wall time, or raises with the output's tail."""
    start = time.time()
    out = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True)
    if out.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{out.stdout[-3000:]}")
    return out.stdout, time.time() - start


def mpirun(n):
    """mpirun for N ranks as root, on a 2-core machine that may be oversubscribed."""
    base = ["mpirun", "-np", str(n)]
    if os.geteuid() == 0:
        base += ["--allow-run-as-root"]
    return base + ["--oversubscribe", "--bind-to", "none"]

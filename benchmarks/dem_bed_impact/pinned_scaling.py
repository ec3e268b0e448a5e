#!/usr/bin/python3
"""DEM thread scaling, 1 to 2 threads, on a machine whose two processors may run at different
speeds (ck_dem_bench run on the bed-impact benchmark's bed).

On the 2-core machine the benchmarks run on, one processor was at times 1.5 times slower than
the other for minutes on end (1-thread runs of 4.8 s or 7.5 s depending on where they ran), so
a 1-thread run left to the scheduler gives no fixed yardstick. This script pins every run:
1 thread on processor 0 (taskset -c 0), 1 thread on processor 1 (taskset -c 1), 2 threads on
both (taskset -c 0,1), for each binary given, in rounds; the order of the runs rotates from
round to round, so that no configuration always follows the same one. Before every run (and
after the last) the speed of each processor is probed in this process, pinned to it: a fixed
pure-Python loop (compute) and a fixed 64 MB memory copy (bandwidth), seconds printed per run.

Each ratio is taken within a round (the runs of a round are a minute apart at most); quoted
are the medians of the per-round ratios with their range:
  fast:  the faster processor's 1-thread time over the 2-thread time;
  slow:  the slower processor's;
  mean:  the mean of the two 1-thread times;
  equal: 2 T_ideal / T2 with T_ideal = T_a T_b / (T_a + T_b), the 2-thread time of a perfect
         split over two processors with these speeds (each does the share its speed allows):
         the scaling the 2-thread run would show on two processors of equal speed.
Two more views, for a machine whose slow spells are one-sided (a processor is slowed, never
sped up): "best", the fastest 1-thread run (either processor) over the fastest 2-thread run;
"quiet", the ratio of the medians of the runs whose compute probes before and after, on the
processors the run used, were all within 15 % of the session's fastest (so neither processor
was in a slow spell at either end of the run; the copy probe varies too much from run to run
to be a criterion, it is printed only). The step loop's seconds (printed by ck_dem_bench) are
used, not the whole process's: the input is read serially. Every run's state_hash is printed;
they must all agree.

    benchmarks/dem_bed_impact/pinned_scaling.py --bed bed.txt --steps 1000 --rounds 5 \\
        new=build/benchmarks/dem_bed_impact/ck_dem_bench old=/path/to/ck_dem_bench
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

CONFIGS = [("1@cpu0", 1, "0"), ("1@cpu1", 1, "1"), ("2@cpu0,1", 2, "0,1")]


def probe(cpu):
    """Seconds of a fixed compute loop and of a fixed memory copy, pinned to CPU."""
    os.sched_setaffinity(0, {cpu})
    start = time.perf_counter()
    acc = 0
    for i in range(3_000_000):
        acc = (acc + i * i) & 0xFFFFFFFF
    compute = time.perf_counter() - start
    src = bytearray(64 << 20)
    dst = bytearray(64 << 20)
    dst[:] = src  # touch the pages before timing
    start = time.perf_counter()
    for _ in range(16):
        dst[:] = src
    memory = time.perf_counter() - start
    return compute, memory


def run_once(binary, threads, cpus, bed, steps):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    start = time.perf_counter()
    out = subprocess.run(["taskset", "-c", cpus, binary, "run", bed, str(steps)], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - start
    if out.returncode != 0:
        raise RuntimeError(f"{binary} failed:\n{out.stdout[-2000:]}")
    result = json.loads(out.stdout.strip().splitlines()[-1])
    return result["seconds"], wall, result["state_hash"]


def summary(label, values):
    return f"{label} {statistics.median(values):.3f}x ({min(values):.3f}-{max(values):.3f})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binaries", nargs="+", help="NAME=PATH of a ck_dem_bench")
    ap.add_argument("--bed", required=True)
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    binaries = [b.split("=", 1) for b in args.binaries]
    items = [(name, path, c) for name, path in binaries for c in CONFIGS]
    times = {(name, c[0]): [] for name, _, c in items}
    runs = []  # (name, label, cpus, loop, probes before)
    hashes = set()
    print("round  binary  config     probe cpu0 / cpu1 (compute s, copy s)   loop s   wall s")
    for r in range(args.rounds):
        shift = r % len(items)
        for name, path, (label, threads, cpus) in items[shift:] + items[:shift]:
            p0, p1 = probe(0), probe(1)
            os.sched_setaffinity(0, {0, 1})
            loop, wall, h = run_once(path, threads, cpus, args.bed, args.steps)
            hashes.add(h)
            times[(name, label)].append(loop)
            runs.append((name, label, [int(c) for c in cpus.split(",")], loop, (p0, p1)))
            print(f"{r + 1:5d}  {name:6s}  {label:9s}  {p0[0]:.3f} {p0[1]:.3f} / {p1[0]:.3f} "
                  f"{p1[1]:.3f}              {loop:7.3f}  {wall:7.3f}", flush=True)
    last = (probe(0), probe(1))
    print("state_hash:", ", ".join(sorted(hashes)))
    probes = [r[4] for r in runs] + [last]
    fastest = [min(p[c][0] for p in probes) for c in (0, 1)]

    def quiet(k):
        """Run k's compute probes before and after within 15 % of the fastest, on its CPUs."""
        return all(p[c][0] <= 1.15 * fastest[c] for p in (probes[k], probes[k + 1])
                   for c in runs[k][2])
    for name, _ in binaries:
        a, b, two = (times[(name, c[0])] for c in CONFIGS)
        print(f"{name}: medians 1@cpu0 {statistics.median(a):.3f} s, 1@cpu1 "
              f"{statistics.median(b):.3f} s, 2 threads {statistics.median(two):.3f} s")
        fast = [min(x, y) / t for x, y, t in zip(a, b, two)]
        slow = [max(x, y) / t for x, y, t in zip(a, b, two)]
        mean = [0.5 * (x + y) / t for x, y, t in zip(a, b, two)]
        equal = [2.0 * x * y / (x + y) / t for x, y, t in zip(a, b, two)]
        print(f"{name}: 1 -> 2 threads, per-round medians: " + "; ".join(
            [summary("fast", fast), summary("slow", slow), summary("mean", mean),
             summary("equal", equal)]))
        print(f"{name}: best {min(a + b) / min(two):.3f}x ({min(a + b):.3f} s / {min(two):.3f} s)")
        calm = {c[0]: [r[3] for k, r in enumerate(runs) if r[0] == name and r[1] == c[0]
                       and quiet(k)] for c in CONFIGS}
        ones = calm[CONFIGS[0][0]] + calm[CONFIGS[1][0]]
        if ones and calm[CONFIGS[2][0]]:
            t1, t2 = statistics.median(ones), statistics.median(calm[CONFIGS[2][0]])
            print(f"{name}: quiet {t1 / t2:.3f}x (1 thread {t1:.3f} s over {len(ones)} runs, "
                  f"2 threads {t2:.3f} s over {len(calm[CONFIGS[2][0]])})")
        else:
            print(f"{name}: quiet: too few quiet runs")
    if len(hashes) > 1:
        print("error: the runs' state hashes differ: the binaries or thread counts do not compute "
              "the same steps, so their times are not comparable", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

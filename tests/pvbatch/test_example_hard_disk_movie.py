"""Runs examples/hard_disk_movie.py on a small box and checks the frames, the movie and the
report (energy of the elastic run, ejecta, shock front)."""

import json
import os
import shutil
import sys

from craterkit.testing import Checker, run_example

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example hard_disk_movie")
code = run_example(source_dir, "hard_disk_movie",
                   ["--output-dir", out, "--width", "0.5", "--ground-depth", "0.25",
                    "--headroom", "0.15", "--impactor-radius", "0.02", "--end-time", "0.01",
                    "--frame-interval", "0.001", "--resolution", "480", "270"])
t.check(code == 0, f"example exited with {code}")
report = json.load(open(os.path.join(out, "report.json")))
t.check(report["frames"] == 11, f"frames {report['frames']}")
frames = sorted(f for f in os.listdir(os.path.join(out, "frames")) if f.endswith(".png"))
t.check(len(frames) == 11, f"{len(frames)} frame files")
for f in frames:
    t.check(os.path.getsize(os.path.join(out, "frames", f)) > 3000, f"frame {f} empty")
e0, e1 = report["kinetic_energy_start_J_per_m"], report["kinetic_energy_end_J_per_m"]
t.check(abs(e1 - e0) < 1e-9 * e0, f"elastic run lost energy: {e0} -> {e1}")
t.check(report["pair_collisions"] > 1000, f"collisions {report['pair_collisions']}")
t.check(report["shock_speed_m_s"] is not None and report["shock_speed_m_s"] > 0, "no shock speed")
if shutil.which("ffmpeg"):
    movie = os.path.join(out, "movie.mp4")
    t.check(os.path.isfile(movie) and os.path.getsize(movie) > 1000, "movie.mp4 missing or empty")
else:
    print("ffmpeg is not installed: the movie was not checked (scripts/test installs it)")
sys.exit(t.close())

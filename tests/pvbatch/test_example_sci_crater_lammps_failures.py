"""examples/sci_crater.py --dem-engine lammps when LAMMPS fails, with the stand-ins for lmp and
mpirun of lammps_fakes.py (no LAMMPS needed), at a size below test_example_sci_crater_lammps.py's
so that the SPH stage takes seconds rather than minutes (g = 1e5 m/s^2 and the hand-off at
0.1 sqrt(D/g); 300 grains requested, 2 frames):
 a. a fresh run whose LAMMPS stops with an ERROR line ends with a message (no traceback) that
    quotes the line, names log.lammps, says the SPH stage's outputs are kept and gives the command
    that resumes; OUTPUT_DIR still holds sph_handoff.vtp;
 b. that very command (--resume), with LAMMPS past a 2 s limit, does not run the SPH stage again
    (it reads sph_handoff.vtp) and names the limit;
 c-e. resumed again: no lmp; a LAMMPS without pair_style granular; a dump cut short in frame 2:
    each named, the SPH outputs still there;
 f. as a user runs it (scripts/pvbatch in a child process, no lmp): exit status 1, the message
    on stderr, no traceback."""

import os
import shlex
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps_fakes import ERROR_LINE, Fakes, dump_text  # noqa: E402

from craterkit.testing import Checker, run_script  # noqa: E402

source_dir, out = sys.argv[1], sys.argv[2]
t = Checker("example sci_crater --dem-engine lammps, failures")
example = os.path.join(source_dir, "examples", "sci_crater.py")
run_dir = os.path.join(out, "run")
fakes = Fakes(os.path.join(out, "fakes"))
fakes.use()
os.environ.pop("CRATERKIT_LAMMPS_TIMEOUT", None)
tiny = ["--particles", "300", "--frames", "2", "--width", "300", "--gravity", "100000", "--handoff-fraction", "0.1",
        "--dem-engine", "lammps", "--lammps-ranks", "2", "--output-dir", run_dir]
kept = os.path.join(run_dir, "sph_handoff.vtp")


def run(what, args):
    """Runs the example in this interpreter; returns its message (the SystemExit text), stdout
    and the seconds it took. An exception other than SystemExit fails the check."""
    clock = time.time()
    try:
        code, stdout, stderr = run_script(example, args, capture=True)
    except Exception as error:  # noqa: BLE001 - a traceback is what this test refuses
        t.check(False, f"{what}: the example raised {type(error).__name__}: {error}")
        return "", "", time.time() - clock
    seconds = time.time() - clock
    message = code if isinstance(code, str) else ""
    t.check(isinstance(code, str), f"{what}: the example ended with {code!r}, not a message")
    t.check("Traceback" not in stdout + stderr + message, f"{what}: a traceback in its output")
    t.check(os.path.isfile(kept), f"{what}: sph_handoff.vtp is gone")
    print(f"--- {what} ({seconds:.0f} s); the message:\n{message}", flush=True)
    return message, stdout, seconds


# a. A fresh run, LAMMPS stops with an ERROR line.
fakes.mode("error")
message, stdout, _ = run("a. LAMMPS stops with an ERROR line", tiny)
for word in (f'"{ERROR_LINE}"', os.path.join(run_dir, "lammps", "log.lammps"), "The SPH stage's outputs are kept",
             kept, "--resume"):
    t.check(word in message, f"a: the message does not say '{word}'")
t.check("[1/5] SPH impact" in stdout, "a: the fresh run did not run the SPH stage")
t.check(os.path.isfile(os.path.join(run_dir, "lammps", "in.craterkit")), "a: no deck written")
checkpoint = os.path.join(run_dir, "sph.cksph")
if os.path.isfile(checkpoint):
    t.check(checkpoint in message, "a: sph.cksph is kept but not named")
print(f"a: sph.cksph {'kept' if os.path.isfile(checkpoint) else 'not written at this size'}", flush=True)
command = shlex.split(message.strip().splitlines()[-1]) if message else []
t.check(command[2:] == tiny + ["--resume"], f"a: the resume command is not this run's with --resume: {command}")
t.check(command[:1] and os.path.basename(command[0]) == "pvbatch" and os.path.samefile(command[1], example),
        f"a: the resume command does not run the example through scripts/pvbatch: {command[:2]}")
resume = command[2:] if command[2:] == tiny + ["--resume"] else tiny + ["--resume"]

# b. The command given, with LAMMPS past its limit: the SPH stage is read back, not run.
code, usage, _ = run_script(example, ["--help"], capture=True)
limit = ["--lammps-timeout", "2"] if "--lammps-timeout" in usage else []
if not limit:
    os.environ["CRATERKIT_LAMMPS_TIMEOUT"] = "2"
fakes.mode("sleep")
fakes.pids()
message, stdout, seconds = run("b. resumed, LAMMPS past 2 s", resume + limit)
os.environ.pop("CRATERKIT_LAMMPS_TIMEOUT", None)
t.check(f"[1/5] SPH state from {kept}" in stdout and "[1/5] SPH impact" not in stdout,
        "b: --resume did not read the SPH stage's sph_handoff.vtp")
for word in ("time limit of 2 s", "stopped with its 2 MPI ranks", "--resume"):
    t.check(word in message, f"b: the message does not say '{word}'")
t.check(len(fakes.pids()) == 2, "b: the stand-in LAMMPS did not start on 2 ranks")

# c. No lmp: named before a deck is written.
os.environ["LMP"] = "craterkit-test-no-such-lmp"
os.remove(os.path.join(run_dir, "lammps", "in.craterkit"))
message, _, _ = run("c. resumed, no lmp", resume)
for word in ("LAMMPS ('craterkit-test-no-such-lmp') not found", "apt-get install lammps", "--resume"):
    t.check(word in message, f"c: the message does not say '{word}'")
t.check(not os.path.exists(os.path.join(run_dir, "lammps", "in.craterkit")), "c: a deck was written without lmp")
fakes.use()

# d. A LAMMPS without pair_style granular.
fakes.help(missing=["pair granular"], packages="KSPACE MOLECULE")
fakes.mode("sleep")
fakes.pids()
message, _, _ = run("d. resumed, a LAMMPS without pair_style granular", resume)
for word in ("pair style 'granular' (package GRANULAR)", "installed packages: KSPACE MOLECULE", "--resume"):
    t.check(word in message, f"d: the message does not say '{word}'")
t.check(not fakes.pids(), "d: LAMMPS was started although it lacks pair_style granular")
fakes.help()

# e. A dump cut short in frame 2.
lines = dump_text(frames=2).splitlines(keepends=True)
fakes.mode("dump", "".join(lines[:-2]))
message, _, _ = run("e. resumed, a dump cut short", resume)
for word in (f"LAMMPS dump {os.path.join(run_dir, 'lammps', 'dump.craterkit')}", "cut short in frame 2", "--resume"):
    t.check(word in message, f"e: the message does not say '{word}'")

# f. As a user runs it: a child scripts/pvbatch (without pvbatch's own MPI environment), no lmp.
env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
env["LMP"] = "craterkit-test-no-such-lmp"
clock = time.time()
done = subprocess.run([os.path.join(source_dir, "scripts", "pvbatch"), example] + resume, env=env,
                      capture_output=True, text=True, stdin=subprocess.DEVNULL)
print(f"--- f. scripts/pvbatch, no lmp ({time.time() - clock:.0f} s): exit {done.returncode}; stderr:\n"
      f"{done.stderr.strip()}", flush=True)
t.check(done.returncode == 1, f"f: exit status {done.returncode}, 1 expected")
t.check("LAMMPS ('craterkit-test-no-such-lmp') not found" in done.stderr and "--resume" in done.stderr,
        "f: the message is not on stderr")
t.check("Traceback" not in done.stderr + done.stdout, "f: a traceback")
sys.exit(t.close())

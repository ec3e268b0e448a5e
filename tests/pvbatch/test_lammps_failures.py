"""The LAMMPS route's failures, each ending in a LammpsError whose message names what went wrong
and what to do (docs/lammps.md, "When LAMMPS fails"), with stand-ins for lmp and mpirun written
at run time (lammps_fakes.py) and a deck written by LAMMPSDeckWriter from a small bed:
 1. no lmp (LMP names a missing executable), no mpirun: LammpsNotFound naming it and the package;
 2. a LAMMPS without pair_style granular, without fix wall/gran/region, or older than 29 Oct 2020
    (`lmp -h`): LammpsLacksStyle naming the style and its package, before anything runs;
 3. LAMMPS exiting 1 with an ERROR line: LammpsFailed quoting the line and naming log.lammps;
 4. a run past its time limit: LammpsTimeout naming the limit, back within the limit + 10 s, no
    rank left running (the stand-in mpirun; Open MPI's mpirun too when installed); and run-lammps
    itself stopped by TERM before its limit: exit 143, a message, and no rank left running;
 5. a dump cut short (in a frame's atom lines, in the middle of its last line, in a header), or
    a frame short of the deck's: LammpsDumpError naming the file and the frame.
With LAMMPS installed, the real thing as well: a whole run reads back; a deck with an unknown
command fails quoting LAMMPS' own ERROR line; a deck that runs too long is stopped with its ranks."""

import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lammps_fakes import ERROR_LINE, Fakes, alive, dump_text, running_in  # noqa: E402

from craterkit import load_plugin  # noqa: E402
from craterkit.lammps import (LammpsDumpError, LammpsFailed, LammpsLacksStyle, LammpsNotFound,  # noqa: E402
                              LammpsTimeout, RUN_LAMMPS, _child_environment, check_lammps, lammps_available,
                              read_lammps_dump, run_lammps, write_lammps_deck)
from craterkit.testing import Checker  # noqa: E402

simple = load_plugin()


def started_ranks(fakes):
    """The pids the stand-in lmp recorded so far (without forgetting them, as fakes.pids() does)."""
    path = os.path.join(fakes.folder, "pids")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return f.read().split()
t = Checker("test_lammps_failures")
folder = tempfile.mkdtemp(prefix="craterkit-lammps-failures-")
real_lammps = lammps_available() and "LMP" not in os.environ and "MPIRUN" not in os.environ
real_mpirun = shutil.which("mpirun")


def raised(call, *args, **kwargs):
    """The exception CALL raises (None if it returns), and its message."""
    try:
        call(*args, **kwargs)
    except Exception as error:  # noqa: BLE001 - the test names the class it expects
        return error, str(error)
    return None, ""


def expect(what, error, cls, message, *words):
    t.check(isinstance(error, cls), f"{what}: {type(error).__name__} raised, {cls.__name__} expected: {message}")
    for word in words:
        t.check(word in message, f"{what}: the message does not say '{word}': {message}")
    t.check("Traceback" not in message, f"{what}: a traceback in the message")
    print(f"{what}: {type(error).__name__}: {message.splitlines()[0] if message else ''}", flush=True)


# A deck as the example writes it: a small bowl of grains, two output times.
bed = simple.GranularBed(Packing="HCP", Container="Bowl", ContainerRadius=0.2, ParticleRadius=0.03,
                         SurfaceHeight=0.0)
deck = os.path.join(folder, "deck")
write_lammps_deck(simple, bed, deck, Container="FromInput", EndTime=0.01, OutputInterval=0.005)
text = open(os.path.join(deck, "in.craterkit")).read()
t.check("pair_style granular" in text and "wall/gran/region" in text, "the deck has no granular styles")

# The real LAMMPS first (before the stand-ins take LMP and MPIRUN): a whole run reads back.
if real_lammps:
    clock = time.time()
    dump = run_lammps(deck, 2)
    reader, times = read_lammps_dump(simple, dump)
    t.check(len(times) == 2, f"LAMMPS: {len(times)} frames read back, 2 expected")
    print(f"LAMMPS: a whole run of the deck read back in {time.time() - clock:.1f} s", flush=True)
    # An unknown command: LAMMPS' own ERROR line, quoted.
    bad = os.path.join(folder, "bad")
    shutil.copytree(deck, bad)
    with open(os.path.join(bad, "in.craterkit"), "a") as f:
        f.write("bogus_command 1 2\n")
    error, message = raised(run_lammps, bad, 2)
    expect("LAMMPS, an unknown command", error, LammpsFailed, message,
           "ERROR: Unknown command: bogus_command", os.path.join(bad, "log.lammps"))
    # A run too long for its limit: stopped, with its ranks.
    long = os.path.join(folder, "long")
    shutil.copytree(deck, long)
    with open(os.path.join(long, "in.craterkit"), "a") as f:
        f.write("run 1000000000 pre no post no\n")
    clock = time.time()
    error, message = raised(run_lammps, long, 2, timeout=3)
    seconds = time.time() - clock
    expect("LAMMPS, past 3 s", error, LammpsTimeout, message, "time limit of 3 s", os.path.join(long, "log.lammps"))
    t.check(seconds < 3 + 10 + 5, f"LAMMPS past 3 s: run_lammps returned after {seconds:.1f} s")
    time.sleep(0.5)
    t.check(not running_in(long), f"LAMMPS past 3 s: processes {running_in(long)} still run in its folder")
else:
    print("LAMMPS (lmp) or mpirun not installed: only the stand-ins are run", flush=True)

fakes = Fakes(os.path.join(folder, "fakes"))
fakes.use()
t.check(check_lammps(deck).startswith("run-lammps: LAMMPS 29 Sep 2021"), "the stand-in LAMMPS did not pass the check")

# 1. No lmp, no mpirun.
for name, value in (("LMP", os.path.join(folder, "no-such-dir", "lmp")), ("LMP", "craterkit-test-no-such-lmp")):
    os.environ[name] = value
    t.check(not lammps_available(), f"lammps_available() with {name}={value}")
    for call, args in ((check_lammps, ()), (run_lammps, (deck, 2))):
        error, message = raised(call, *args)
        expect(f"1. {call.__name__}, {name}={value}", error, LammpsNotFound, message,
               f"LAMMPS ('{value}') not found", "apt-get install lammps", "LMP")
fakes.use(mpirun="craterkit-test-no-such-mpirun")
error, message = raised(run_lammps, deck, 2)
expect("1. no mpirun", error, LammpsNotFound, message, "'craterkit-test-no-such-mpirun' not found",
       "apt-get install openmpi-bin", "MPIRUN")
fakes.use()

# 2. A LAMMPS without a style the deck needs: refused before anything runs.
fakes.mode("sleep")  # a run would hang: the refusal must come first
fakes.pids()
for missing, words in ((["pair granular"], ["pair style 'granular'", "package GRANULAR"]),
                       (["fix wall/gran/region"], ["fix style 'wall/gran/region'", "package GRANULAR"]),
                       (["fix nve/sphere", "fix gravity"], ["fix style 'gravity'", "fix style 'nve/sphere'"])):
    fakes.help(missing=missing, packages="KSPACE MANYBODY MOLECULE")
    for call, args in ((check_lammps, ()), (run_lammps, (deck, 2))):
        error, message = raised(call, *args)
        expect(f"2. {call.__name__} without {', '.join(missing)}", error, LammpsLacksStyle, message,
               *words, "29 Sep 2021", "installed packages: KSPACE MANYBODY MOLECULE", "LMP")
fakes.help(version="3 Mar 2020")
error, message = raised(run_lammps, deck, 2)
expect("2. LAMMPS 3 Mar 2020", error, LammpsLacksStyle, message, "3 Mar 2020", "older than 29 Oct 2020",
       "damping tsuji")
t.check(not fakes.pids(), "2. the stand-in ran although a style was missing")
fakes.help()

# 3. LAMMPS stops with an ERROR line.
fakes.mode("error")
error, message = raised(run_lammps, deck, 2)
expect("3. an ERROR line", error, LammpsFailed, message, f'"{ERROR_LINE}"', os.path.join(deck, "log.lammps"),
       os.path.join(deck, "screen.lammps"))

# 4. A run past its time limit: stopped with every rank, through each mpirun there is.
for label, mpirun in (("the stand-in mpirun", fakes.mpirun), ("Open MPI's mpirun", real_mpirun)):
    if not mpirun:
        continue
    fakes.use(mpirun=mpirun)
    fakes.mode("sleep")
    fakes.pids()
    clock = time.time()
    error, message = raised(run_lammps, deck, 2, timeout=2)
    seconds = time.time() - clock
    expect(f"4. past 2 s, {label}", error, LammpsTimeout, message, "time limit of 2 s", "stopped with its 2 MPI ranks",
           "CRATERKIT_LAMMPS_TIMEOUT", os.path.join(deck, "log.lammps"))
    t.check(seconds < 2 + 10 + 5, f"4. {label}: run_lammps returned after {seconds:.1f} s")
    pids = fakes.pids()
    for _ in range(20):
        if not any(alive(p) for p in pids):
            break
        time.sleep(0.25)
    t.check(len(pids) == 2, f"4. {label}: {len(pids)} ranks started, 2 expected")
    t.check(not any(alive(p) for p in pids), f"4. {label}: ranks {[p for p in pids if alive(p)]} still run")
    print(f"4. {label}: stopped after {seconds:.1f} s, ranks {pids} gone", flush=True)
    # run-lammps itself stopped (a ctest timeout, Ctrl-C) before its limit: it stops the ranks too.
    fakes.pids()
    child = subprocess.Popen([RUN_LAMMPS, deck, "2"], env=_child_environment(None), stdin=subprocess.DEVNULL,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    for _ in range(100):  # until both ranks have started
        if len(started_ranks(fakes)) == 2:
            break
        time.sleep(0.1)
    child.send_signal(signal.SIGTERM)
    stderr = child.communicate(timeout=30)[1]
    pids = fakes.pids()
    t.check(child.returncode == 128 + signal.SIGTERM,
            f"4. {label}, run-lammps stopped by TERM: exit {child.returncode}, {128 + signal.SIGTERM} expected")
    t.check("stopped by SIGTERM" in stderr and "2 MPI ranks were stopped too" in stderr,
            f"4. {label}, run-lammps stopped by TERM: its message: {stderr.strip()}")
    t.check(len(pids) == 2 and not any(alive(p) for p in pids),
            f"4. {label}, run-lammps stopped by TERM: ranks {pids}, still running {[p for p in pids if alive(p)]}")
    print(f"4. {label}: run-lammps stopped by TERM, ranks {pids} gone", flush=True)
fakes.use()

# 5. Dumps cut short: the reader's refusal, or the file's last line, named with the frame.
whole = dump_text(frames=2)
lines = whole.splitlines(keepends=True)
cuts = {  # name: (text, words the message must hold)
    "in frame 2's atom lines": ("".join(lines[:-2]), ["cut short in frame 2", "frame 1 is whole",
                                                       "declares more atoms than the file holds"]),
    "in the middle of its last line": (whole[:-9], ["cut short in frame 2", "its last", "middle of a line"]),
    "in frame 2's header": ("".join(lines[:18]), ["cut short in frame 2", "unexpected end of file"]),
    "in frame 1's atom lines": ("".join(lines[:13]), ["cut short in frame 1", "no frame is whole"]),
}
dumps = os.path.join(folder, "dumps")
os.makedirs(dumps)
path = os.path.join(dumps, "whole.dump")
open(path, "w").write(whole)
reader, times = read_lammps_dump(simple, path)
t.check(len(times) == 2, f"5. the whole dump: {len(times)} frames")
for k, (what, (cut, words)) in enumerate(cuts.items()):
    path = os.path.join(dumps, f"cut{k}.dump")
    open(path, "w").write(cut)
    error, message = raised(read_lammps_dump, simple, path)
    expect(f"5. cut {what}", error, LammpsDumpError, message, f"LAMMPS dump {path}", *words)
# A frame short of the deck's write_dump lines.
short = os.path.join(folder, "short")
os.makedirs(short)
open(os.path.join(short, "in.craterkit"), "w").write("run 225\nwrite_dump all custom dump.craterkit\n" * 3)
open(os.path.join(short, "dump.craterkit"), "w").write(whole)
error, message = raised(read_lammps_dump, simple, os.path.join(short, "dump.craterkit"))
expect("5. a frame short", error, LammpsDumpError, message, "holds 2 frame(s), the deck writes 3",
       "stops after frame 2")
# Through run_lammps: the run "finishes" but its dump is cut short.
fakes.mode("dump", "".join(lines[:-2]))
dump = run_lammps(deck, 2)
error, message = raised(read_lammps_dump, simple, dump)
expect("5. a run's dump cut short", error, LammpsDumpError, message,
       f"LAMMPS dump {os.path.join(deck, 'dump.craterkit')}", "cut short in frame 2")

shutil.rmtree(folder, ignore_errors=True)
sys.exit(t.close())

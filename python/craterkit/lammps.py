"""The DEM stage on LAMMPS from a pvbatch script (docs/lammps.md).

    from craterkit.lammps import write_lammps_deck, run_lammps, read_lammps_dump
    write_lammps_deck(simple, hand, "run.lammps", time=t0, EndTime=t1, OutputInterval=dt)
    dump = run_lammps("run.lammps", ranks=2)
    reader, times = read_lammps_dump(simple, dump)   # times count from t0

The deck itself is written by the LAMMPSDeckWriter proxy (Readers/vtkCraterKitLAMMPSDeckWriter,
Solvers/dem/LammpsDeck); these helpers only call it, scripts/run-lammps and the dump reader.

Every failure raises a LammpsError (a RuntimeError) whose message says what went wrong and
what to do: LammpsNotFound (no lmp or mpirun), LammpsLacksStyle (this LAMMPS lacks a style,
package or version the deck needs; found from `lmp -h` before running), LammpsFailed (LAMMPS
stopped: its ERROR line and log), LammpsTimeout (past the time limit; stopped with its MPI
ranks), LammpsDumpError (a dump cut short: the file and the frame).
"""

import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
try:  # the installed package finds scripts/run-lammps beside itself
    from . import resource_path
    RUN_LAMMPS = resource_path("run-lammps")
except ImportError:
    RUN_LAMMPS = os.path.join(ROOT, "scripts", "run-lammps")


class LammpsError(RuntimeError):
    """A LAMMPS stage that cannot go on; the message says what went wrong and what to do."""


class LammpsNotFound(LammpsError):
    """No LAMMPS executable (LMP, default lmp) or no mpirun (MPIRUN) on the PATH."""


class LammpsLacksStyle(LammpsError):
    """This LAMMPS lacks a style, a package or the version the deck needs (from `lmp -h`)."""


class LammpsFailed(LammpsError):
    """LAMMPS stopped with an error (the message quotes its ERROR line and names its log)."""


class LammpsTimeout(LammpsError):
    """LAMMPS ran past its time limit and was stopped with its MPI ranks."""


class LammpsDumpError(LammpsError):
    """A dump that cannot be read whole: missing, or cut short (the message names the frame)."""


# run-lammps' exit status -> the error it stands for (its header lists them).
_ERRORS = {1: LammpsFailed, 2: LammpsError, 3: LammpsNotFound, 4: LammpsLacksStyle, 5: LammpsTimeout}


def _child_environment(timeout=None):
    # pvbatch runs as an MPI singleton: its Open MPI / PMIx variables would make the child
    # mpirun try to join it and fail before LAMMPS starts, so the child gets none of them.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    env["OMP_NUM_THREADS"] = "1"
    if timeout is not None:
        env["CRATERKIT_LAMMPS_TIMEOUT"] = str(int(-(-float(timeout) // 1)))  # whole seconds, rounded up
    return env


def _run_script(arguments, timeout=None):
    done = subprocess.run([RUN_LAMMPS] + arguments, env=_child_environment(timeout), capture_output=True,
                          text=True, stdin=subprocess.DEVNULL)
    if done.returncode != 0:
        lines = [line[len("run-lammps: "):] if line.startswith("run-lammps: ") else line
                 for line in done.stderr.strip().splitlines()]
        error = _ERRORS.get(done.returncode, LammpsError)
        raise error("\n".join(lines) if lines else f"scripts/run-lammps failed (exit {done.returncode})")
    return done.stdout


def check_lammps(directory=None):
    """Checks, without running anything, that LAMMPS and mpirun are there and that this LAMMPS
    has every style the deck in DIRECTORY uses (without one: every style a DEM deck uses).
    Returns run-lammps' line naming the version; raises LammpsNotFound or LammpsLacksStyle."""
    return _run_script(["--check"] + ([directory] if directory else [])).strip()


def write_lammps_deck(simple, source, directory, time=None, **properties):
    """Writes SOURCE's output (at TIME, if given) as a LAMMPS deck into DIRECTORY with the
    LAMMPSDeckWriter; PROPERTIES are DEMIntegrator's (ContactLaw, SurfaceGravity, EndTime, ...).
    Raises RuntimeError when the writer reports an error (no in.craterkit written)."""
    deck = os.path.join(directory, "in.craterkit")
    if os.path.exists(deck):
        os.remove(deck)  # so that a refused state cannot leave an older deck looking fresh
    writer = simple.LAMMPSDeckWriter(Input=source, FileName=directory, **properties)
    if time is None:
        writer.UpdatePipeline()
    else:
        writer.UpdatePipeline(time)
    simple.Delete(writer)
    if not os.path.isfile(deck):
        raise RuntimeError(f"LAMMPSDeckWriter wrote no deck into {directory} (see the error above)")
    return directory


def run_lammps(directory, ranks=2, timeout=None):
    """Runs the deck in DIRECTORY with scripts/run-lammps on RANKS MPI ranks; returns the dump's
    path. TIMEOUT: seconds after which LAMMPS is stopped with its ranks (0: no limit; None: the
    environment's CRATERKIT_LAMMPS_TIMEOUT, else 3600). Raises LammpsNotFound, LammpsLacksStyle
    (checked before running), LammpsFailed or LammpsTimeout, each saying what to do."""
    out = _run_script([directory, str(ranks)], timeout)
    for line in out.splitlines():
        if line.startswith("run-lammps: dumps"):
            return line.rsplit(": ", 1)[1].strip()
    raise LammpsError("scripts/run-lammps named no dump:\n" + out)


def lammps_available():
    """True when `lmp` and `mpirun` are on the PATH (the deck can run here)."""
    from shutil import which
    return which(os.environ.get("LMP", "lmp")) is not None and which(os.environ.get("MPIRUN", "mpirun")) is not None


def read_lammps_dump(simple, dump, frames=None):
    """The dump as a LAMMPSDumpReader proxy and its snapshot times. The deck counts time from the
    state it was written from: add that state's Time for the pipeline's clock. FRAMES: the
    number of snapshots expected; by default the number of write_dump lines of the deck
    (in.craterkit) beside the dump, if there is one. Raises LammpsDumpError naming the file and
    the frame when the dump is missing, cut short or holds fewer frames."""
    if not os.path.isfile(dump):
        raise LammpsDumpError(f"LAMMPS dump {dump} does not exist: the run wrote no dump")
    with _VtkErrors() as box:  # the reader reads the dump's index when it is made
        reader = simple.LAMMPSDumpReader(FileNames=[dump])
        reader.UpdatePipelineInformation()
    values = reader.TimestepValues  # a list, or one number for a single snapshot
    times = [] if values is None else [float(v) for v in values] if hasattr(values, "__len__") else [float(values)]
    if not times or "ERROR" in box["text"]:
        simple.Delete(reader)
        raise LammpsDumpError(_unreadable(dump, box["text"]))
    if box["text"].strip():  # the reader's warnings, shown as they would have been
        import sys
        print(box["text"].strip(), file=sys.stderr, flush=True)
    if not dump.endswith(".gz") and not _ends_with_newline(dump):
        simple.Delete(reader)
        raise LammpsDumpError(
            f"LAMMPS dump {dump} is cut short in frame {len(times)} (its last, t = {times[-1]:.6g} s from the "
            f"state): the file ends in the middle of a line, which LAMMPS never writes; the run that wrote it "
            f"did not finish writing it (stopped, or the disk full?): run the deck again")
    if frames is None:
        frames = _deck_frames(os.path.join(os.path.dirname(dump), "in.craterkit"))
    if frames and len(times) < frames:
        simple.Delete(reader)
        raise LammpsDumpError(
            f"LAMMPS dump {dump} holds {len(times)} frame(s), the deck writes {frames}: it stops after frame "
            f"{len(times)} (t = {times[-1]:.6g} s from the state); the run did not finish: run the deck again")
    return reader, times


# --- reading a dump: the error messages ------------------------------------------------------

class _VtkErrors:
    """Collects VTK's error and warning text within the block and keeps it off stderr (the
    caller says what went wrong in its own words)."""

    def __enter__(self):
        from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow, vtkStringOutputWindow
        self.verbosity = vtkLogger.GetCurrentVerbosityCutoff()
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)
        self.original = vtkOutputWindow.GetInstance()
        self.original.Register(None)
        self.window = vtkStringOutputWindow()
        vtkOutputWindow.SetInstance(self.window)
        self.box = {"text": ""}
        return self.box

    def __exit__(self, *_):
        from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow
        self.box["text"] = self.window.GetOutput()
        vtkOutputWindow.SetInstance(self.original)
        self.original.UnRegister(None)
        vtkLogger.SetStderrVerbosity(self.verbosity)
        return False


def _ends_with_newline(path):
    with open(path, "rb") as f:
        f.seek(0, os.SEEK_END)
        if f.tell() == 0:
            return True
        f.seek(-1, os.SEEK_END)
        return f.read(1) == b"\n"


def _deck_frames(deck):
    """The number of write_dump lines of a deck (its output times); None without the deck."""
    try:
        with open(deck) as f:
            return sum(1 for line in f if line.startswith("write_dump "))
    except OSError:
        return None


def _unreadable(dump, vtk_text):
    """The message for a dump the reader refused: the reader's own words (file:line: what), and
    the frame they fall in, counted by its ITEM: ATOMS lines before that line."""
    said = re.search(r"invalid input: (.*)", vtk_text)
    reason = said.group(1).strip() if said else (vtk_text.strip().splitlines() or ["no snapshot read"])[-1]
    start = re.search(r"snapshot starting at line (\d+)", reason)
    at = re.search(r":(\d+): ", reason)
    line = int(start.group(1)) if start else int(at.group(1)) if at else None
    where = ""
    if line is not None:
        import gzip
        whole = 0
        with (gzip.open if dump.endswith(".gz") else open)(dump, "rb") as f:
            for number, text in enumerate(f, 1):
                if number >= line:
                    break
                whole += text.startswith(b"ITEM: ATOMS")
        done = f"frames 1-{whole} are whole" if whole > 1 else "frame 1 is whole" if whole else "no frame is whole"
        where = f" in frame {whole + 1} (from line {line}; {done})"
    if re.search(r"unexpected end of file|declares more atoms than the file holds|exceeds what the rest", reason):
        return (f"LAMMPS dump {dump} is cut short{where}: {reason}. The run that wrote it did not finish "
                f"writing it (stopped, or the disk full?): run the deck again")
    return f"LAMMPS dump {dump} cannot be read{where}: {reason}"

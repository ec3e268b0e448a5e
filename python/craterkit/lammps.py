"""The DEM stage on LAMMPS from a pvbatch script (issue 34; docs/lammps.md).

    from craterkit.lammps import write_lammps_deck, run_lammps, read_lammps_dump
    write_lammps_deck(simple, hand, "run.lammps", time=t0, EndTime=t1, OutputInterval=dt)
    dump = run_lammps("run.lammps", ranks=2)
    reader, times = read_lammps_dump(simple, dump)   # times count from t0

The deck itself is written by the LAMMPSDeckWriter proxy (Readers/vtkCraterKitLAMMPSDeckWriter,
Solvers/dem/LammpsDeck); these helpers only call it, scripts/run-lammps and the dump reader.
"""

import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RUN_LAMMPS = os.path.join(ROOT, "scripts", "run-lammps")


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
    path. Raises RuntimeError with the script's message when LAMMPS is missing or fails."""
    # pvbatch runs as an MPI singleton: its Open MPI / PMIx variables would make the child
    # mpirun try to join it and fail before LAMMPS starts, so the child gets none of them.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
    env["OMP_NUM_THREADS"] = "1"
    if timeout:
        env["CRATERKIT_LAMMPS_TIMEOUT"] = str(int(timeout))
    done = subprocess.run([RUN_LAMMPS, directory, str(ranks)], env=env, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"run-lammps failed ({done.returncode}):\n{done.stderr.strip()}")
    for line in done.stdout.splitlines():
        if line.startswith("run-lammps: dumps"):
            return line.rsplit(": ", 1)[1].strip()
    raise RuntimeError("run-lammps named no dump:\n" + done.stdout)


def lammps_available():
    """True when `lmp` and `mpirun` are on the PATH (the deck can run here)."""
    from shutil import which
    return which(os.environ.get("LMP", "lmp")) is not None and which(os.environ.get("MPIRUN", "mpirun")) is not None


def read_lammps_dump(simple, dump):
    """The dump as a LAMMPSDumpReader proxy and its snapshot times. The deck counts time from the
    state it was written from: add that state's Time for the pipeline's clock."""
    reader = simple.LAMMPSDumpReader(FileNames=[dump])
    reader.UpdatePipelineInformation()
    return reader, list(reader.TimestepValues)

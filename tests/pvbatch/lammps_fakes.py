"""Stand-ins for LAMMPS (lmp) and mpirun, written into a folder at run time, for the tests of
the LAMMPS route's failures (test_lammps_failures.py, test_example_sci_crater_lammps_failures.py).

    fakes = Fakes(folder)                 # folder/lmp, folder/mpirun, folder/help.txt, folder/mode
    fakes.use()                           # LMP and MPIRUN name them (os.environ)
    fakes.help(missing=["pair granular"]) # `lmp -h` lists every style a deck uses but these
    fakes.mode("error")                   # a run prints an ERROR line and exits 1
    fakes.mode("sleep")                   # a run sleeps (each rank records its pid in folder/pids)
    fakes.mode("dump", text)              # a run writes TEXT as dump.craterkit and exits 0

The stand-in lmp answers `-h` with a listing in LAMMPS' own layout (Installed packages, then
"* Pair styles:" and so on); the stand-in mpirun starts -np copies of its command in the
background and waits for them (an Open MPI mpirun on the PATH runs the stand-in lmp as well)."""

import os
import stat

# The styles of the listing: every one a CraterKit deck (DEM or bonded) uses, and a few more.
STYLES = {
    "atom": "atomic bond sphere",
    "pair": "granular lj/cut",
    "bond": "harmonic table",
    "fix": "bond/break gravity nve nve/sphere wall/gran wall/gran/region",
    "region": "block cylinder plane sphere union",
    "command": "run write_dump",
}
HEADINGS = {"atom": "* Atom styles:", "pair": "* Pair styles:", "bond": "* Bond styles:", "fix": "* Fix styles",
            "region": "* Region styles:", "command": "* Command styles"}
PACKAGES = "GRANULAR MC MOLECULE"
VERSION = "29 Sep 2021 - Update 2"

# The ERROR line the stand-in prints (LAMMPS' wording for a style it does not have).
ERROR_LINE = "ERROR: Unknown fix style wall/gran/region (src/modify.cpp:892)"

LMP = r"""#!/usr/bin/env bash
# A stand-in for LAMMPS written by CraterKit's tests (tests/pvbatch/lammps_fakes.py).
here=$(cd "$(dirname "$0")" && pwd)
if [[ "${1:-}" == "-h" ]]; then cat "$here/help.txt"; exit 0; fi
echo $$ >>"$here/pids"
rank=${OMPI_COMM_WORLD_RANK:-${FAKE_RANK:-0}}
log=log.lammps
while [[ $# -gt 0 ]]; do case $1 in -log) log=$2; shift 2 ;; *) shift ;; esac; done
[[ $rank == 0 ]] && echo "LAMMPS (stand-in of CraterKit's tests)" >"$log"
case $(cat "$here/mode") in
error)
  if [[ $rank == 0 ]]; then
    echo "@ERROR@" | tee -a "$log"
    echo "Last command: fix wall1 all wall/gran/region granular hooke" >>"$log"
  fi
  exit 1 ;;
sleep) exec sleep 600 ;;
dump) [[ $rank == 0 ]] && cp "$here/dump.txt" dump.craterkit; exit 0 ;;
esac
"""

MPIRUN = r"""#!/usr/bin/env bash
# A stand-in for mpirun written by CraterKit's tests: -np N copies of the command, waited for.
np=1
while [[ $# -gt 0 ]]; do
  case $1 in -np | -n) np=$2; shift 2 ;; -*) shift ;; *) break ;; esac
done
pids=()
for ((k = 0; k < np; k++)); do FAKE_RANK=$k "$@" & pids+=($!); done
status=0
for p in "${pids[@]}"; do wait "$p" || status=$?; done
exit $status
"""


def _executable(path, text):
    with open(path, "w") as f:
        f.write(text)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


class Fakes:
    def __init__(self, folder):
        os.makedirs(folder, exist_ok=True)
        self.folder = folder
        self.lmp = os.path.join(folder, "lmp")
        self.mpirun = os.path.join(folder, "mpirun")
        _executable(self.lmp, LMP.replace("@ERROR@", ERROR_LINE))
        _executable(self.mpirun, MPIRUN)
        self.help()
        self.mode("error")

    def use(self, mpirun=None):
        """LMP names the stand-in lmp, MPIRUN the stand-in mpirun (or MPIRUN if given)."""
        os.environ["LMP"] = self.lmp
        os.environ["MPIRUN"] = mpirun or self.mpirun

    def help(self, missing=(), packages=PACKAGES, version=VERSION):
        """The `lmp -h` listing: every style of STYLES but MISSING ("kind name" strings)."""
        parts = [f"\nLarge-scale Atomic/Molecular Massively Parallel Simulator - {version}\n",
                 "Usage example: lmp -var t 300 -echo screen -in in.alloy\n",
                 "List of command line options supported by this LAMMPS executable:\n",
                 "-help                       : print this help message (-h)\n",
                 "Installed packages:\n", packages + " \n",
                 "List of individual style options included in this LAMMPS executable\n"]
        for kind, names in STYLES.items():
            kept = [n for n in names.split() if f"{kind} {n}" not in missing]
            parts += [HEADINGS[kind] + "\n", "".join(f"{n:<16}" for n in kept) + "\n"]
        with open(os.path.join(self.folder, "help.txt"), "w") as f:
            f.write("\n".join(parts))

    def mode(self, mode, dump_text=None):
        with open(os.path.join(self.folder, "mode"), "w") as f:
            f.write(mode + "\n")
        if dump_text is not None:
            with open(os.path.join(self.folder, "dump.txt"), "w") as f:
                f.write(dump_text)

    def pids(self):
        """The pids the stand-in lmp recorded since the last call (and forgets them)."""
        path = os.path.join(self.folder, "pids")
        if not os.path.exists(path):
            return []
        with open(path) as f:
            pids = [int(w) for w in f.read().split()]
        os.remove(path)
        return pids


def alive(pid):
    """True while process PID runs (a zombie waiting to be reaped counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def running_in(folder):
    """The live processes whose working directory is FOLDER (a deck's: LAMMPS and its ranks)."""
    found = []
    target = os.path.realpath(folder)
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                if os.path.realpath(os.readlink(f"/proc/{name}/cwd")) == target and alive(int(name)):
                    found.append(int(name))
            except OSError:
                pass
    return found


def dump_text(frames=2, atoms=3):
    """A LAMMPS `dump custom` text as the deck writes it (ITEM: TIME first), FRAMES snapshots."""
    out = []
    for k in range(1, frames + 1):
        out += ["ITEM: TIME", f"{0.005 * k:.17g}", "ITEM: TIMESTEP", str(225 * k), "ITEM: NUMBER OF ATOMS",
                str(atoms), "ITEM: BOX BOUNDS mm mm mm"] + ["-0.2 0.2"] * 3
        out.append("ITEM: ATOMS id type x y z vx vy vz omegax omegay omegaz radius mass")
        for i in range(1, atoms + 1):
            out.append(f"{i} 1 {0.05 * i:.17g} 0.012345678901234567 {0.03 * k:.17g} 0 0 {-0.1 * k:.17g} "
                       f"0 0 0 0.029999999999999999 0.22619467105846511")
    return "\n".join(out) + "\n"

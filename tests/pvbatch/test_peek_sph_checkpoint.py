"""benchmarks/sci_crater/peek_sph_checkpoint.py on a small SPHImpact run in its container: the
state it writes from the checkpoint is the run's own output at that time (the same particles,
without the container's, at the same positions), the impactor's depth it prints is the one
computed from that output, and a file that is not a checkpoint is refused by name. Also
benchmarks/sci_crater/target_motion.py on the same checkpoint: its regions hold every target
particle once, and their vertical momentum adds up to the output's."""

import contextlib
import io
import os
import re
import runpy
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from craterkit import fetch, load_plugin
from craterkit.testing import Checker

source_dir = sys.argv[1]
tool = os.path.join(source_dir, "benchmarks", "sci_crater", "peek_sph_checkpoint.py")
simple = load_plugin()
t = Checker("test_peek_sph_checkpoint")
folder = tempfile.mkdtemp()
path = os.path.join(folder, "run.cksph")
sph = simple.SPHImpact(ParticlesAcrossImpactor=3, TargetRadius=0.15, TargetContainer=1, EndTime=2e-5,
                       OutputInterval=2e-5, CheckpointFile=path, CheckpointInterval=5)
sph.UpdatePipeline(2e-5)
state = fetch(sph)
x = vtk_to_numpy(state.GetPoints().GetData())
m = vtk_to_numpy(state.GetPointData().GetArray("Mass"))
imp = vtk_to_numpy(state.GetPointData().GetArray("Material")) == 0


def peek(args):
    sys.argv = [tool] + args
    out = io.StringIO()
    code = 0
    with contextlib.redirect_stdout(out):
        try:
            runpy.run_path(tool, run_name="__main__")
        except SystemExit as stop:
            code = stop.code
    return code, out.getvalue()


vtp = os.path.join(folder, "peek.vtp")
code, printed = peek([path, vtp])
t.check(code == 0, f"the tool exited with {code}")
r = vtkXMLPolyDataReader()
r.SetFileName(vtp)
r.Update()
xp = vtk_to_numpy(r.GetOutput().GetPoints().GetData())
t.check(xp.shape == x.shape and np.array_equal(xp, x),
        f"the peeked state ({xp.shape[0]} particles) is not the run's output ({x.shape[0]})")
depth = -np.average(x[imp, 2], weights=m[imp])
found = re.search(r"impactor's centre of mass ([0-9.eE+-]+) m deep", printed)
t.check(found is not None and abs(float(found.group(1)) - depth) <= 1e-3 * abs(depth),
        f"printed impactor depth {found.group(1) if found else None} against {depth:.4g} m: {printed!r}")
t.check(re.search(r"t = 2e-05 s", printed) is not None, f"time not printed: {printed!r}")
sys.path.insert(0, os.path.dirname(tool))
from target_motion import target_motion  # noqa: E402

v = vtk_to_numpy(state.GetPointData().GetArray("Velocity"))
tgt = vtk_to_numpy(state.GetPointData().GetArray("Material")) == 1
_, regions = target_motion(path)
count = sum(r[0] for r in regions.values())
pz = sum(r[2] for r in regions.values())
want = float(np.sum(m[tgt] * v[tgt, 2]))
t.check(count == int(tgt.sum()), f"target_motion counted {count} target particles, the output has {tgt.sum()}")
t.check(abs(pz - want) <= 1e-9 * float(np.sum(m[tgt] * np.abs(v[tgt, 2]))) + 1e-300,
        f"target_motion's p_z {pz:.6g} against the output's {want:.6g} kg m/s")
bad = os.path.join(folder, "not_a_checkpoint.cksph")
open(bad, "w").write("hello\n")
code, _ = peek([bad])
t.check(isinstance(code, str) and "not_a_checkpoint" in code, f"a bad file gave {code!r}")
sys.exit(t.close())

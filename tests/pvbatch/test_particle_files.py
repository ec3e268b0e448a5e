"""Particle readers and writers through ParaView: write a bed as pkdgrav .ss and as a LAMMPS
dump, open both by extension, compare; numbered dumps and multi-snapshot dumps as time
steps; a DEM checkpoint opened for inspection; a read file feeding DEMIntegrator; malformed
files give errors naming file and line or byte."""

import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_particle_files")
folder = tempfile.mkdtemp()

bed = simple.GranularBed(Packing="HCP", Container="Box", BoxSize=[1.0, 1.0, 0.5], ParticleRadius=0.05)
ref = fetch(bed)
n = ref.GetNumberOfPoints()
x_ref = vtk_to_numpy(ref.GetPoints().GetData())
id_ref = vtk_to_numpy(ref.GetPointData().GetArray("Id"))
m_ref = vtk_to_numpy(ref.GetPointData().GetArray("Mass"))


def arrays(data):
    pd = data.GetPointData()
    return (vtk_to_numpy(data.GetPoints().GetData()), vtk_to_numpy(pd.GetArray("Id")),
            vtk_to_numpy(pd.GetArray("Mass")))


# pkdgrav .ss: written in pkdgrav units, read back in SI.
ss_path = os.path.join(folder, "bed.ss")
writer = simple.PkdgravSsWriter(Input=bed, FileName=ss_path)
writer.UpdatePipeline()
t.check(os.path.getsize(ss_path) == 16 + 96 * n, f".ss size {os.path.getsize(ss_path)} for {n} particles")
ss = simple.OpenDataFile(ss_path)
t.check(ss is not None and ss.GetXMLName() == "PkdgravSsReader", f"opened .ss with {ss and ss.GetXMLName()}")
x, ids, m = arrays(fetch(ss))
t.check(x.shape == x_ref.shape and np.allclose(x, x_ref, rtol=1e-14, atol=1e-15), ".ss positions differ")
t.check(np.array_equal(ids, id_ref), ".ss ids differ")
t.check(np.allclose(m, m_ref, rtol=1e-14), ".ss masses differ")
ss_si = simple.PkdgravSsReader(FileNames=[ss_path], PkdgravUnits=0)
x_raw = vtk_to_numpy(fetch(ss_si).GetPoints().GetData())
t.check(abs(x_raw[:, 0].max() - x_ref[:, 0].max() / 1.495978707e11) < 1e-20, "PkdgravUnits=0 should leave AU values")

# File › Save Data picks the writer by extension.
saved = os.path.join(folder, "saved.ss")
simple.SaveData(saved, proxy=bed)
t.check(os.path.isfile(saved) and open(saved, "rb").read() == open(ss_path, "rb").read(),
        "SaveData(.ss) did not use the pkdgrav writer")

# LAMMPS dump: exact round trip.
dump_path = os.path.join(folder, "bed.dump")
simple.LAMMPSDumpWriter(Input=bed, FileName=dump_path).UpdatePipeline()
dump = simple.OpenDataFile(dump_path)
t.check(dump is not None and dump.GetXMLName() == "LAMMPSDumpReader", "dump not opened by the dump reader")
x, ids, m = arrays(fetch(dump))
t.check(np.array_equal(x, x_ref) and np.array_equal(ids, id_ref) and np.array_equal(m, m_ref),
        "dump round trip is not exact")

# Numbered LIGGGHTS-style files become time steps; so do the snapshots of one file.
text = open(dump_path).read()
series = []
for k, time in enumerate([0.0, 0.5, 1.0]):
    path = os.path.join(folder, f"dump.{k}.liggghts")
    open(path, "w").write(text.replace("ITEM: TIME\n0\n", f"ITEM: TIME\n{time}\n", 1))
    series.append(path)
reader = simple.LAMMPSDumpReader(FileNames=series)
times = list(reader.TimestepValues)
t.check(times == [0.0, 0.5, 1.0], f"series times {times}")
reader.UpdatePipeline(0.5)
t.check(field_value(fetch(reader), "Time") == 0.5, "series: the 0.5 s file was not read")
multi = os.path.join(folder, "multi.dump")
open(multi, "w").write(text + text.replace("ITEM: TIME\n0\n", "ITEM: TIME\n2.5\n", 1))
two = simple.LAMMPSDumpReader(FileNames=[multi])
t.check(list(two.TimestepValues) == [0.0, 2.5], f"snapshots {list(two.TimestepValues)}")

# A DEM checkpoint, opened for inspection.
ck = os.path.join(folder, "run.ckdem")
dem = simple.DEMIntegrator(Input=bed, SurfaceGravity=[0, 0, -9.81], EndTime=0.01, OutputInterval=0.01,
                           CheckpointFile=ck, CheckpointInterval=10)
dem.UpdatePipeline(0.01)
opened = simple.OpenDataFile(ck)
cdata = fetch(opened)
t.check(cdata.GetNumberOfPoints() == n, f"checkpoint holds {cdata.GetNumberOfPoints()} particles")
t.check(field_value(cdata, "Time") > 0.0, "checkpoint time missing")

# A file from another code feeds the DEM directly.
dem2 = simple.DEMIntegrator(Input=ss, SurfaceGravity=[0, 0, -9.81], Container="None", EndTime=0.002,
                            OutputInterval=0.002)
dem2.UpdatePipeline(0.002)
t.check(fetch(dem2).GetNumberOfPoints() == n, "DEMIntegrator did not run on the .ss input")

# Malformed files: errors name the file and the line or byte, outputs are empty.
bad = os.path.join(folder, "bad.dump")
open(bad, "w").write(text.replace("ITEM: ATOMS id", "ITEM: ATOMS idx", 1)
                     .replace("\n1 1 ", "\n1 1 nan? ", 1))
with captured_vtk_messages() as log:
    out = fetch(simple.LAMMPSDumpReader(FileNames=[bad]))
t.check(out.GetNumberOfPoints() == 0 and "bad.dump:" in log["text"], f"bad dump: {log['text'][:300]!r}")
trunc = os.path.join(folder, "trunc.ss")
open(trunc, "wb").write(open(ss_path, "rb").read()[:-10])
with captured_vtk_messages() as log:
    out = fetch(simple.PkdgravSsReader(FileNames=[trunc]))
t.check(out.GetNumberOfPoints() == 0 and "trunc.ss: byte 8" in log["text"], f"truncated .ss: {log['text'][:300]!r}")
# A checkpoint with one bit flipped in its payload: CraterKitCheckpointReader refuses it by name
# (its CRC-32 no longer matches; docs/proxies/ParticleReaders.md), and reads nothing.
corrupt = os.path.join(folder, "corrupt.ckdem")
data = bytearray(open(ck, "rb").read())
data[len(data) // 2] ^= 0x10
open(corrupt, "wb").write(bytes(data))
with captured_vtk_messages() as log:
    out = fetch(simple.CraterKitCheckpointReader(FileNames=[corrupt]))
t.check(out.GetNumberOfPoints() == 0 and "corrupt.ckdem" in log["text"] and "corrupt (checksum" in log["text"],
        f"a flipped bit in a checkpoint: {log['text'][:300]!r}")

sys.exit(t.close())

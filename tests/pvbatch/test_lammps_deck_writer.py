"""LAMMPSDeckWriter through ParaView: a GranularBed and a DEMIntegrator time step (an impactor
in flight, so that velocities and spins are not zero) written as LAMMPS decks and their data files
parsed back here, independently of the C++ parser: positions, velocities and angular velocities
equal the originals bit for bit, atom id = Id + 1, type = Material + 1, diameter = 2 Radius, and
the mass LAMMPS computes from diameter and density is the original to rounding. The deck is the
run DEMIntegrator would do with the same properties: its time step is DEMIntegrator's TimeStep
field, its dumps fall at DEMIntegrator's output times after the state's, its bowl becomes a
wall/gran/region. SaveData picks the writer by the .lammps extension; the Python helper writes
the same deck; cohesion and an EndTime before the state are refused with errors naming them. A
BondedImpact state at step 0 gives the bonded deck with every set-up bond, its step and its
positions bit for bit; a later bonded state is refused."""

import math
import os
import re
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from craterkit import fetch, field_value, load_plugin
from craterkit.lammps import write_lammps_deck
from craterkit.testing import Checker, captured_vtk_messages

simple = load_plugin()
t = Checker("test_lammps_deck_writer")
folder = tempfile.mkdtemp()


def parse_data(path):
    """Atoms (id type diameter density x y z) and Velocities (id v w) sections, keyed by id;
    float() of the %.17g text is the correctly rounded double."""
    atoms, vel, section = {}, {}, None
    for line in open(path):
        words = line.split("#")[0].split()
        if not words:
            continue
        if words[0] in ("Atoms", "Velocities"):
            section = words[0]
            continue
        if section == "Atoms":
            atoms[int(words[0])] = [int(words[1])] + [float(w) for w in words[2:7]]
        elif section == "Velocities":
            vel[int(words[0])] = [float(w) for w in words[1:7]]
    return atoms, vel


def check_round_trip(data, directory, what):
    atoms, vel = parse_data(os.path.join(directory, "data.craterkit"))
    pd = data.GetPointData()
    n = data.GetNumberOfPoints()
    t.check(len(atoms) == n and len(vel) == n, f"{what}: {len(atoms)} atoms, {len(vel)} velocities for {n} particles")
    if len(atoms) != n or len(vel) != n:
        return
    ids = vtk_to_numpy(pd.GetArray("Id")).astype(np.int64)
    order = [int(i) + 1 for i in ids]
    a = np.array([atoms[k] for k in order])
    v = np.array([vel[k] for k in order])
    x = vtk_to_numpy(data.GetPoints().GetData())
    u = vtk_to_numpy(pd.GetArray("Velocity"))
    w = vtk_to_numpy(pd.GetArray("AngularVelocity"))
    t.check(np.array_equal(a[:, 3:6], x), f"{what}: positions differ from the original (bit for bit)")
    t.check(np.array_equal(v[:, 0:3], u), f"{what}: velocities differ from the original (bit for bit)")
    t.check(np.array_equal(v[:, 3:6], w), f"{what}: angular velocities differ from the original")
    t.check(np.array_equal(a[:, 0], vtk_to_numpy(pd.GetArray("Material")) + 1), f"{what}: type != Material + 1")
    t.check(np.array_equal(a[:, 1], 2.0 * vtk_to_numpy(pd.GetArray("Radius"))), f"{what}: diameter != 2 Radius")
    # LAMMPS' mass 4/3 pi (d/2)^3 rho: the original within a few roundings of the density's quotient.
    m = 4.0 / 3.0 * math.pi * (0.5 * a[:, 1]) ** 3 * a[:, 2]
    t.check(np.allclose(m, vtk_to_numpy(pd.GetArray("Mass")), rtol=1e-14, atol=0), f"{what}: masses differ")
    return atoms


def deck_text(directory):
    return open(os.path.join(directory, "in.craterkit")).read()


# A settled bed in a bowl, written as it is.
bed = simple.GranularBed(Packing="HCP", Container="Bowl", ContainerRadius=0.6, ParticleRadius=0.05,
                         SurfaceHeight=0.0)
bed_data = fetch(bed)
deck1 = os.path.join(folder, "bed.lammps")
simple.LAMMPSDeckWriter(Input=bed, FileName=deck1, EndTime=0.5, OutputInterval=0.25).UpdatePipeline()
check_round_trip(bed_data, deck1, "GranularBed")
text = deck_text(deck1)
t.check("wall/gran/region" in text and re.search(r"region \S+ sphere", text) is not None,
        "the bowl (FromInput) is not written as a wall/gran/region on a sphere")
# CraterKit clips the damped normal force at zero (ContactModels.h): every grain and wall
# coefficient set ends with LAMMPS' limit_damping.
contact_lines = [line for line in text.splitlines() if line.startswith("pair_coeff") or "wall/gran" in line]
t.check(len(contact_lines) == 2 and all("damping tsuji limit_damping" in line for line in contact_lines),
        f"pair and wall coefficients should all end with limit_damping: {[c[-40:] for c in contact_lines]}")
t.check(len(re.findall(r"^write_dump", text, re.M)) == 2, "EndTime 0.5 every 0.25: two dumps expected")

# A DEMIntegrator time step with an impactor in flight: the deck of a running state.
props = dict(AddImpactor=1, ImpactorRadius=0.1, ImpactSpeed=3.0, ImpactAngle=30.0, MaxExpectedSpeed=3.0,
             SurfaceGravity=[0.0, 0.0, -9.81])
dem = simple.DEMIntegrator(Input=bed, EndTime=0.02, OutputInterval=0.01, KeptStates=0, **props)
dem.UpdatePipeline(0.01)
state = fetch(simple.ForceTime(Input=dem, ForcedTime=0.01, IgnorePipelineTime=1))
t0 = field_value(state, "Time")
t.check(abs(t0 - 0.01) < 1e-3, f"DEMIntegrator state at {t0} s")
t.check(np.abs(vtk_to_numpy(state.GetPointData().GetArray("Velocity"))).max() > 1.0, "impactor not moving")
deck2 = os.path.join(folder, "step.lammps")
write_lammps_deck(simple, dem, deck2, time=0.01, EndTime=0.05, OutputInterval=0.01,
                  **{k: v for k, v in props.items() if k != "AddImpactor"})
check_round_trip(state, deck2, "DEMIntegrator step")
text = deck_text(deck2)
dt = float(re.search(r"^timestep (\S+)", text, re.M).group(1))
t.check(dt == field_value(state, "TimeStep"), f"deck step {dt} s, DEMIntegrator's {field_value(state, 'TimeStep')} s")
runs = [int(k) for k in re.findall(r"^run (\d+)", text, re.M)]
times = np.cumsum(runs) * dt
# DEMIntegrator's output times from this state on: t0 + 0.01 k up to EndTime 0.05, itself an
# output time; in the deck counted from t0, each at the nearest step.
want = np.array([0.01, 0.02, 0.03, 0.05 - t0])
t.check(len(times) == 4 and np.all(np.abs(times - want) <= 0.5 * dt), f"dump times {times} s after the state")
t.check("fix gravity all gravity 9.81" in text, "gravity not written")

# Save Data by extension, and the same deck.
saved = os.path.join(folder, "saved.lammps")
simple.SaveData(saved, proxy=bed, EndTime=0.5, OutputInterval=0.25)
t.check(os.path.isfile(os.path.join(saved, "in.craterkit")) and deck_text(saved) == deck_text(deck1),
        "SaveData(.lammps) did not write the same deck")

# A BondedImpact state at its first time step: the bonded model's deck, with every set-up bond.
bonded = simple.BondedImpact(ParticleCount=800, EndTime=1e-6, OutputInterval=5e-7)
bonded.UpdatePipeline(0.0)
state0 = fetch(simple.ForceTime(Input=bonded, ForcedTime=0.0, IgnorePipelineTime=1))
deck3 = os.path.join(folder, "bonded.lammps")
write_lammps_deck(simple, bonded, deck3, time=0.0, EndTime=1e-6, OutputInterval=5e-7)
text = deck_text(deck3)
data = open(os.path.join(deck3, "data.craterkit")).read()
bonds = int(re.search(r"^(\d+) bonds$", data, re.M).group(1))
t.check(bonds == int(field_value(state0, "Bonds")), f"{bonds} bonds written, BondedImpact formed {field_value(state0, 'Bonds')}")
t.check("bond_style table linear" in text and "fix break all bond/break 1 1" in text,
        "the bonded deck lacks its bond table or fix bond/break")
t.check(float(re.search(r"^timestep (\S+)", text, re.M).group(1)) == field_value(state0, "TimeStep"),
        "the bonded deck's step is not BondedImpact's")
x = vtk_to_numpy(state0.GetPoints().GetData())
rows = re.search(r"Atoms # bond\n\n(.*?)\n\n", data, re.S).group(1).splitlines()
xb = np.array([[float(w) for w in row.split()[3:6]] for row in rows])
t.check(xb.shape == x.shape and np.array_equal(xb, x), "bonded positions differ from BondedImpact's (bit for bit)")
# A later state has lost bonds the arrays do not name: refused.
bonded.UpdatePipeline(5e-7)
with captured_vtk_messages() as messages:
    simple.LAMMPSDeckWriter(Input=bonded, FileName=os.path.join(folder, "late"), EndTime=1e-6,
                            OutputInterval=5e-7).UpdatePipeline(5e-7)
t.check("first time step" in messages["text"], f"a late bonded state was not refused: {messages['text'][:200]}")

# Refused: cohesion (no pair_style granular counterpart) and no output time after the state.
for bad, word in (({"Cohesion": 10.0}, "cohesion"), ({"EndTime": 0.0}, "EndTime")):
    where = os.path.join(folder, f"bad_{word}")
    with captured_vtk_messages() as messages:
        simple.LAMMPSDeckWriter(Input=bed, FileName=where, **bad).UpdatePipeline()
    t.check(not os.path.exists(os.path.join(where, "in.craterkit")), f"{word}: a deck was written")
    t.check(word in messages["text"], f"{word}: no error naming it ({messages['text'][:300]})")
sys.exit(t.close())

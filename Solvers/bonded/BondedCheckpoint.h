// Bonded checkpoint files: the whole state of a BondedSolver, so that a run restored from one
// (BondedSolver::readCheckpoint, BondedRun::resumeFrom) continues bit for bit.
//
// The framing (header, format version, CRC-32 checksums, old files read with a warning) is
// common/CheckpointFormat.h, kind "BONDED". The payload, native byte order: "CKBOND01", the
// particle and bond counts (uint64), the law (σ, ε, κ, r_cut), the impact axis (3 doubles),
// the plate's rear face and the impact speed, the solver parameters Δt, Δt fraction and skin,
// the solver's Δt, the step (uint64), the broken bonds (uint64), the dissipated energy, then
// the arrays positions, velocities, forces (3 doubles per particle), masses (double), bodies
// (uint8), bonds (i, j as uint32 and the rest length as a double) and the bonds' broken flags
// (uint8). Format version 1 (whose files are this payload alone) ends there; version 2 adds the
// shock heating (bonded/ShockViscosity.h): the dissipation (uint32), C_L, C_Q and w_th
// (double), and each particle's internal energy (double). A version-1 file is a run of the
// paper's model (no shock heating, no internal energy). The reader checks that the payload's
// size is exactly what the counts give before it allocates anything, and that every bond joins
// two particles of the file.
//
// The code is the BondedSolver members writeCheckpoint / readCheckpoint (BondedCheckpoint.cpp);
// a version-1 file's warning goes to the restored solver's warnings() (with the file's name).
#pragma once

#include "bonded/BondedSolver.h"

// DEM checkpoint files: the whole state of a DemSolver run, so that a run resumed from one
// continues bit-identically (the restored run rebuilds its pair list and merges the saved
// contact histories into it; Schwartz, Richardson & Michel 2012's SSDEM springs survive).
//
// The framing (header, format version, CRC-32 checksums, old files read with a warning) is
// common/CheckpointFormat.h, kind "DEM"; the solver's in-memory snapshots (DemRun) are framed
// the same way. The payload: "CKDEMCP2", native byte order (a uint32 1 probes it), the contact
// law's name and coefficients, the walls, the gravity, the run parameters, the particle count,
// time and step, the particle arrays (x v ω r m ρ material Id), the accelerations, the active
// contacts (i, j, history) sorted by (i, j), the (particle, wall) pairs within reach (particles,
// walls, histories, flags) sorted by particle then wall, the count of overlap-warning steps,
// and the magic again as a trailer (a file cut short is refused). The "CKDEMCP1" payload (the
// whole of a format-version-1 file, and of version-2 files written before CKDEMCP2) held one
// wall history and flag for every particle and wall, 405 bytes a particle in a box; it still
// reads. Every count is checked
// against the bytes left before anything is allocated. The writing and reading code is
// DemSolver::writeCheckpoint / readCheckpoint (DemCheckpoint.cpp); a file is written to
// PATH.part and renamed (common/AtomicWrite.h). A version-1 file's warning goes to the
// restored solver's warnings() (with the file's name).
#pragma once

#include "common/ParticleSet.h"
#include "dem/DemSolver.h"

#include <string>
#include <vector>

namespace craterkit {

// The particles of a checkpoint and where the run stood, for readers that show a checkpoint
// as a particle frame.
struct DemCheckpointState {
  ParticleSet particles;
  double time = 0.0;
  long long step = 0;
  std::vector<std::string> warnings; // the restored solver's (an old format, without checksum)
};

// Reads PATH as a restart would (the same checks; throws InputError naming the file).
DemCheckpointState readDemCheckpointState(const std::string& path);

} // namespace craterkit

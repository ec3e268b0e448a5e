// SPH checkpoint files (.cksph): the whole particle state of an SphRun and where the run
// stood, so that a run of the same set-up resumes from it (SphRun::resumeFrom) and a reader
// can show it (CraterKitCheckpointReader).
//
// The framing (header, format version, CRC-32 checksums, old files read with a warning) is
// common/CheckpointFormat.h, kind "SPH". The payload, unchanged since format version 1 (whose
// files are this payload alone): "CKSPH1\n\0", particle count and steps (uint64), time and the
// next time step (double), then the arrays x v m ρ u h S α D (double) and material (int32),
// native byte order. Written to PATH.part and renamed (common/AtomicWrite.h), so a crash never
// leaves a half-written file.
#pragma once

#include "sph/SphState.h"

#include <cstddef>
#include <string>

namespace craterkit {

void writeSphCheckpoint(const std::string& path, const SphState& s, double time, std::size_t steps,
                        double nextStep);

// Throws InputError naming the file and what is wrong with it ("PATH: the checkpoint is corrupt
// (checksum mismatch)" for a damaged file). A file of format version 1 (no checksum) reads with
// a warning naming the file, put in *warning when given (else dropped).
SphState readSphCheckpoint(const std::string& path, double& time, std::size_t& steps,
                           double& nextStep, std::string* warning = nullptr);

} // namespace craterkit

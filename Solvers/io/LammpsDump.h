// LAMMPS / LIGGGHTS text dumps (`dump custom`): any number of snapshots per file, columns in
// any order (gzip-compressed files are inflated by FileBytes first). Known columns map to the
// CraterKit data model (docs/architecture.md); every other column is kept as an extra array.
// Format: LAMMPS documentation, `dump` command (ITEM: TIMESTEP / NUMBER OF ATOMS / BOX
// BOUNDS / ATOMS blocks).
#pragma once

#include "io/ParticleFrame.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit {

// Where each snapshot of a dump starts, and its step and particle count (a cheap scan).
struct DumpIndexEntry {
  std::size_t offset = 0; // byte offset of its "ITEM: TIMESTEP" line
  std::size_t line = 1;   // line number of that line
  long long timestep = 0;
  std::size_t count = 0;
  double time = 0.0;   // its ITEM: TIME, else the step number
  std::size_t end = 0; // byte offset just past its last atom line (0: not known, found again)
};
std::vector<DumpIndexEntry> indexDump(std::string_view text, const std::string& fileName);
// Parses the snapshot that starts at entry.offset.
ParticleFrame parseDumpSnapshot(std::string_view text, const DumpIndexEntry& entry,
                                const std::string& fileName);
// Writes one snapshot with the columns id type x y z vx vy vz omegax omegay omegaz radius mass
// (type = Material + 1), at full precision.
std::string writeDump(const ParticleFrame& frame);

} // namespace craterkit

// Community particle formats, parsed without VTK so that they can be unit-tested and fuzzed
// on their own (the readers in Readers/ call these).
//
// - LAMMPS / LIGGGHTS text dumps (`dump custom`): any number of snapshots per file, columns in
//   any order, gzip-compressed files too. Known columns map to the CraterKit data model
//   (ARCHITECTURE.md); every other column is kept as an extra array.
// - pkdgrav `.ss` files: XDR (big-endian) header {double time; int n; int magic} and, per
//   particle, {mass, radius, pos[3], vel[3], spin[3]: double; color, org_idx: int} (the
//   standard format, magic -1; the "reduced" format, magic -10101, is refused by name).
//
// Every malformed input raises ParseError naming the file and the line or byte offset; no
// parser allocates more than the bytes it was given could describe.
#pragma once

#include "common/Error.h"
#include "common/ParticleSet.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit {

class ParseError : public InputError {
public:
  using InputError::InputError;
};

// A per-particle array that is not part of the data model (kept under its file name).
struct ExtraArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

// One snapshot of particles.
struct ParticleFrame {
  double time = 0.0;       // s (or the file's time unit: a dump stores the step, see below)
  long long timestep = -1; // a dump's ITEM: TIMESTEP
  ParticleSet particles;   // the data-model arrays (zeros where a column was absent)
  bool hasVelocity = false, hasAngularVelocity = false, hasRadius = false, hasMass = false,
       hasDensity = false, hasMaterial = false, hasId = false;
  std::vector<ExtraArray> extra;
  bool hasBox = false;
  double box[6] = {0, 0, 0, 0, 0, 0}; // xlo xhi ylo yhi zlo zhi
};

// ---- LAMMPS / LIGGGHTS dumps ----------------------------------------------------------------

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

// ---- pkdgrav .ss ----------------------------------------------------------------------------

// pkdgrav's units: length 1 AU, mass 1 solar mass, time 1 yr / 2π (G = 1).
struct PkdgravUnits {
  static constexpr double length = 1.495978707e11; // m (IAU 2012)
  static constexpr double mass = 1.98840987e30;    // kg (IAU 2015 GM☉ / G)
  static double time();                            // s, sqrt(L³ / (G M))
};
// scaleToSI: multiply by the pkdgrav units (false: the file is already in SI).
ParticleFrame parseSs(std::string_view bytes, const std::string& fileName, bool scaleToSI);
std::string writeSs(const ParticleFrame& frame, bool scaleFromSI);

// ---- files ------------------------------------------------------------------------------------

// A file's bytes without a copy: a plain file is memory-mapped read-only (the page cache is
// read in place, populated up front); a gzip file (by its magic) is decompressed into memory.
// Throws ParseError naming the file. Mapped bytes are only valid while the file is not
// truncated by another program, so keep the object no longer than a parse (the dump reader
// keeps a copy of a dump of several snapshots, see readFileBytes).
class FileBytes {
public:
  explicit FileBytes(const std::string& path);
  ~FileBytes();
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;
  std::string_view view() const {
    return map_ ? std::string_view(map_, size_) : std::string_view(owned_);
  }

private:
  const char* map_ = nullptr;
  std::size_t size_ = 0;
  std::string owned_;
};

// The whole file as a string, gunzipped if it starts with the gzip magic; throws ParseError naming
// it.
std::string readFileBytes(const std::string& path);
// Decompresses a gzip stream held in memory (output capped at 1032 times the input).
std::string gunzip(std::string_view data, const std::string& name);

} // namespace craterkit

// The particle frame every file format of io/ reads and writes (LammpsDump, PkdgravSs), and
// the ParseError they and FileBytes raise. Parsed without VTK so that the formats can be
// unit-tested and fuzzed on their own (the readers in Readers/ call them).
//
// Every malformed input raises ParseError naming the file and the line or byte offset; no
// parser allocates more than the bytes it was given could describe.
#pragma once

#include "common/Error.h"
#include "common/ParticleSet.h"

#include <string>
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

} // namespace craterkit

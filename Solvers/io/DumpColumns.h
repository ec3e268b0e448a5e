// The ATOMS line of a LAMMPS dump (LammpsDump.h): what each column holds (LAMMPS `dump custom`
// keywords: id type x y z xu yu zu xs ys zs vx vy vz omegax omegay omegaz radius diameter mass
// density); any other column is an extra array of the frame.
#pragma once

#include "io/DumpText.h"
#include "io/ParticleFrame.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit {
namespace dump {

// ---- dump columns -----------------------------------------------------------------------------

enum class Col {
  Id,
  Type,
  X,
  Y,
  Z,
  Xs,
  Ys,
  Zs,
  Vx,
  Vy,
  Vz,
  Wx,
  Wy,
  Wz,
  Radius,
  Diameter,
  Mass,
  Density,
  Extra
};

Col columnKind(std::string_view name);

// A snapshot's columns: what each one holds, which kinds are present, and where each extra
// column goes (its array in the frame's extra arrays and its component there).
struct DumpColumns {
  std::vector<std::string> names;
  std::vector<Col> kind;
  bool has[static_cast<int>(Col::Extra) + 1] = {};
  std::vector<int> extraIndex, extraComp;
};

// Classifies the ATOMS line's columns and checks them (no kind twice, x, y and z present, a
// box for scaled coordinates); adds the frame's extra arrays (no values yet), grouped as
// vectors when three consecutive names end in x, y, z. Errors name the header's line.
DumpColumns classifyColumns(std::vector<std::string> names, ParticleFrame& f, const Cursor& c,
                            std::size_t headerLine);

} // namespace dump
} // namespace craterkit

// Numbers in LAMMPS decks (dem/LammpsDeck, bonded/BondedLammpsDeck): full precision, %.17g,
// which round-trips every double.
#pragma once

#include <cstdio>
#include <string>

namespace craterkit {

inline std::string lammpsNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

} // namespace craterkit

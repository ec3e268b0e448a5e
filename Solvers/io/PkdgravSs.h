// pkdgrav `.ss` files (pkdgrav: Richardson et al. 2000, Icarus 143, 45; its ssio format):
// XDR (big-endian) header {double time; int n; int magic} and, per
// particle, {mass, radius, pos[3], vel[3], spin[3]: double; color, org_idx: int} (the
// standard format, magic -1; the "reduced" format, magic -10101, is refused by name).
#pragma once

#include "io/ParticleFrame.h"

#include <string>
#include <string_view>

namespace craterkit {

// pkdgrav's units: length 1 AU, mass 1 solar mass, time 1 yr / 2π (G = 1).
struct PkdgravUnits {
  static constexpr double length = 1.495978707e11; // m (IAU 2012)
  static constexpr double mass = 1.98840987e30;    // kg (IAU 2015 GM☉ / G)
  static double time();                            // s, sqrt(L³ / (G M))
};
// scaleToSI: multiply by the pkdgrav units (false: the file is already in SI).
ParticleFrame parseSs(std::string_view bytes, const std::string& fileName, bool scaleToSI);
std::string writeSs(const ParticleFrame& frame, bool scaleFromSI);

} // namespace craterkit

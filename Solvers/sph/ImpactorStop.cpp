#include "sph/ImpactorStop.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace craterkit {

namespace {

// The particles of other, non-rigid materials within reach of MATERIAL's: inside the box of its
// particles widened by their largest support.
std::vector<std::size_t> candidates(const SphState& s, int material,
                                    const std::vector<Material>& materials) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.material[i] == material)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], s.x[3 * i + k] - s.h[i]);
        hi[k] = std::max(hi[k], s.x[3 * i + k] + s.h[i]);
      }
  std::vector<std::size_t> near;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int m = s.material[j];
    if (m == material || materials[static_cast<std::size_t>(m)].rigid)
      continue;
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && s.x[3 * j + k] >= lo[k] && s.x[3 * j + k] <= hi[k];
    if (inside)
      near.push_back(j);
  }
  return near;
}

} // namespace

double stopInFlow(SphState& s, int material, const std::vector<Material>& materials) {
  const std::vector<std::size_t> near = candidates(s, material, materials);
  double converted = 0.0;
  std::vector<std::size_t> group;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.material[i] != material)
      continue;
    group.assign(1, i);
    const double h2 = s.h[i] * s.h[i];
    for (std::size_t j : near) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k)
        d2 += (s.x[3 * j + k] - s.x[3 * i + k]) * (s.x[3 * j + k] - s.x[3 * i + k]);
      if (d2 < h2)
        group.push_back(j);
    }
    if (group.size() == 1)
      continue;
    double mass = 0.0, p[3] = {0, 0, 0}, kinetic = 0.0;
    for (std::size_t j : group) {
      mass += s.mass[j];
      for (int k = 0; k < 3; ++k) {
        p[k] += s.mass[j] * s.v[3 * j + k];
        kinetic += 0.5 * s.mass[j] * s.v[3 * j + k] * s.v[3 * j + k];
      }
    }
    double after = 0.0;
    for (int k = 0; k < 3; ++k)
      after += 0.5 * p[k] * p[k] / mass;
    const double heat = (kinetic - after) / mass; // J/kg, the same for every particle of the group
    for (std::size_t j : group) {
      for (int k = 0; k < 3; ++k)
        s.v[3 * j + k] = p[k] / mass;
      s.u[j] += heat;
    }
    converted += kinetic - after;
  }
  return converted;
}

} // namespace craterkit

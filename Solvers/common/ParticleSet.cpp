#include "common/ParticleSet.h"

#include <cmath>

namespace craterkit {

void ParticleSet::reserve(std::size_t n) {
  position.reserve(3 * n);
  velocity.reserve(3 * n);
  angularVelocity.reserve(3 * n);
  radius.reserve(n);
  mass.reserve(n);
  density.reserve(n);
  material.reserve(n);
  id.reserve(n);
}

void ParticleSet::add(const double x[3], double r, double rho, int mat, std::int64_t ident) {
  for (int k = 0; k < 3; ++k) {
    position.push_back(x[k]);
    velocity.push_back(0.0);
    angularVelocity.push_back(0.0);
  }
  radius.push_back(r);
  density.push_back(rho);
  mass.push_back(rho * 4.0 / 3.0 * M_PI * r * r * r);
  material.push_back(mat);
  id.push_back(ident);
}

} // namespace craterkit

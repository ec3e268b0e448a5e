#include "dem/Impactor.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace craterkit {

std::size_t addImpactor(ParticleSet& s, const ImpactorParams& p) {
  std::ostringstream msg;
  if (!(p.radius > 0.0) || !std::isfinite(p.radius))
    msg << "ImpactorRadius must be positive (got " << p.radius << " m)";
  else if (!(p.density > 0.0) || !std::isfinite(p.density))
    msg << "ImpactorDensity must be positive (got " << p.density << " kg/m^3)";
  else if (!(p.speed >= 0.0) || !std::isfinite(p.speed))
    msg << "ImpactSpeed must be non-negative and finite (got " << p.speed << " m/s)";
  else if (!(p.angle >= 0.0 && p.angle < 90.0))
    msg << "ImpactAngle must be in [0, 90) degrees from the vertical (got " << p.angle << ")";
  if (!msg.str().empty())
    throw InputError(msg.str());
  const double a = p.angle * M_PI / 180.0;
  const double dir[3] = {std::sin(a), 0.0, -std::cos(a)};
  // Start just clear of the surface: the sphere's lowest point a quarter radius above it.
  const double back = (1.25 * p.radius) / std::cos(a);
  const double x[3] = {p.target[0] - dir[0] * back, p.target[1], p.target[2] - dir[2] * back};
  std::int64_t next = 0;
  for (std::int64_t id : s.id)
    next = std::max(next, id + 1);
  s.add(x, p.radius, p.density, p.material, next);
  const std::size_t i = s.size() - 1;
  for (int k = 0; k < 3; ++k)
    s.velocity[3 * i + k] = p.speed * dir[k];
  return i;
}

} // namespace craterkit

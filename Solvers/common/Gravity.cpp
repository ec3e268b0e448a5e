#include "common/Gravity.h"

#include "common/Error.h"

#include <cmath>

namespace craterkit {

Gravity Gravity::downward(double g) {
  Gravity out;
  out.vector = {0.0, 0.0, -g};
  return out;
}

void Gravity::acceleration(const double x[3], double a[3]) const {
  switch (type) {
  case Type::None:
    a[0] = a[1] = a[2] = 0.0;
    return;
  case Type::Uniform:
    for (int k = 0; k < 3; ++k)
      a[k] = vector[k];
    return;
  default: {
    const double d[3] = {x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]};
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double f = r2 > 0.0 ? -GM / (r2 * std::sqrt(r2)) : 0.0;
    for (int k = 0; k < 3; ++k)
      a[k] = f * d[k];
  }
  }
}

double Gravity::potential(const double x[3]) const {
  switch (type) {
  case Type::None:
    return 0.0;
  case Type::Uniform:
    return -(vector[0] * x[0] + vector[1] * x[1] + vector[2] * x[2]);
  default: {
    const double d[3] = {x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return r > 0.0 ? -GM / r : 0.0;
  }
  }
}

double Gravity::magnitudeAt(const double x[3]) const {
  if (type == Type::Uniform)
    return std::sqrt(vector[0] * vector[0] + vector[1] * vector[1] + vector[2] * vector[2]);
  if (type == Type::PointMass) {
    const double d = std::hypot(centre[0] - x[0], centre[1] - x[1], centre[2] - x[2]);
    return d > 0.0 ? GM / (d * d) : 0.0;
  }
  return 0.0;
}

void Gravity::validate() const {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(vector[k]) || !std::isfinite(centre[k]))
      throw InputError("Gravity must be finite");
  if (!std::isfinite(GM) || GM < 0.0)
    throw InputError("the point-mass GM must be finite and non-negative");
}

} // namespace craterkit

#include "bed/SizeDistribution.h"

#include "common/Error.h"

#include <cmath>
#include <sstream>

namespace craterkit {

std::string SizeDistribution::typeName(Type t) {
  switch (t) {
  case Type::Monodisperse:
    return "Monodisperse";
  case Type::Uniform:
    return "Uniform";
  default:
    return "PowerLaw";
  }
}

void SizeDistribution::validate() const {
  std::ostringstream msg;
  if (type == Type::Monodisperse) {
    if (!(radius > 0.0) || !std::isfinite(radius)) {
      msg << "ParticleRadius must be positive and finite (got " << radius << " m)";
      throw InputError(msg.str());
    }
    return;
  }
  if (!(minRadius > 0.0) || !std::isfinite(minRadius)) {
    msg << "MinRadius must be positive and finite (got " << minRadius << " m)";
    throw InputError(msg.str());
  }
  if (!std::isfinite(maxRadius) || maxRadius < minRadius) {
    msg << "MaxRadius (" << maxRadius << " m) must be finite and not below MinRadius (" << minRadius
        << " m)";
    throw InputError(msg.str());
  }
  if (type == Type::PowerLaw && (!std::isfinite(exponent) || exponent <= 0.0)) {
    msg << "PowerLawExponent must be positive and finite (got " << exponent << ")";
    throw InputError(msg.str());
  }
}

double SizeDistribution::sample(Random& rng) const {
  switch (type) {
  case Type::Monodisperse:
    return radius;
  case Type::Uniform:
    return rng.uniform(minRadius, maxRadius);
  default: {
    if (maxRadius == minRadius)
      return minRadius;
    // Invert N(<r) for n(r) ∝ r^-(q+1): r = [a^-q - U (a^-q - b^-q)]^(-1/q).
    const double q = exponent;
    const double aq = std::pow(minRadius, -q), bq = std::pow(maxRadius, -q);
    const double r = std::pow(aq - rng.uniform() * (aq - bq), -1.0 / q);
    return std::min(std::max(r, minRadius), maxRadius);
  }
  }
}

double SizeDistribution::moment(int k) const {
  const double a = minRadius, b = maxRadius;
  switch (type) {
  case Type::Monodisperse:
    return std::pow(radius, k);
  case Type::Uniform:
    if (b == a)
      return std::pow(a, k);
    return (std::pow(b, k + 1) - std::pow(a, k + 1)) / ((k + 1) * (b - a));
  default: {
    if (b == a)
      return std::pow(a, k);
    // <r^k> = ∫ r^(k-q-1) dr / ∫ r^(-q-1) dr on [a, b].
    const double q = exponent;
    const double norm = (std::pow(a, -q) - std::pow(b, -q)) / q;
    const double p = k - q;
    const double num =
        std::abs(p) < 1e-12 ? std::log(b / a) : (std::pow(b, p) - std::pow(a, p)) / p;
    return num / norm;
  }
  }
}

} // namespace craterkit

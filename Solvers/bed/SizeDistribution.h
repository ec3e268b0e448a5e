// Particle radius distributions for granular beds.
//
// Monodisperse; uniform in radius on [rmin, rmax]; or a truncated power law with
// differential number density n(r) ∝ r^-(q+1) on [rmin, rmax], q the cumulative
// exponent (N(>r) ∝ r^-q, q ≈ 2.5–3 for boulder fields). Sampled by inverting the
// cumulative distribution (docs/physics.md §7).
#pragma once

#include "common/Random.h"

#include <string>

namespace craterkit {

struct SizeDistribution {
  enum class Type { Monodisperse = 0, Uniform = 1, PowerLaw = 2 };
  Type type = Type::Monodisperse;
  double radius = 0.5;    // m, monodisperse
  double minRadius = 0.4; // m, polydisperse
  double maxRadius = 0.6; // m, polydisperse
  double exponent = 3.0;  // cumulative power-law exponent q

  void validate() const; // throws InputError naming the bad parameter
  double smallest() const { return type == Type::Monodisperse ? radius : minRadius; }
  double largest() const { return type == Type::Monodisperse ? radius : maxRadius; }

  double sample(Random& rng) const;
  // Exact moments <r^k> of the distribution (k = 1 mean radius, k = 3 for volumes).
  double moment(int k) const;

  static std::string typeName(Type t);
};

} // namespace craterkit

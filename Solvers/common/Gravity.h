// Gravity for the particle solvers: none, uniform (a surface field g, usually (0, 0, -g)) or a
// point mass GM at a centre (Newton: a = -GM d / |d|^3, potential -GM / |d|).
//
// The one place that builds and applies the gravity vector: the DEM's forces and energies,
// the bed settling, the heap test and the choice of a stiffness (the load at the surface).
#pragma once

#include <array>

namespace craterkit {

struct Gravity {
  enum class Type { None = 0, Uniform = 1, PointMass = 2 };
  Type type = Type::Uniform;
  std::array<double, 3> vector{0.0, 0.0, -9.81}; // m/s^2 (Uniform)
  double GM = 0.0;                               // m^3/s^2 (PointMass)
  std::array<double, 3> centre{0.0, 0.0, 0.0};   // m (PointMass)

  // Uniform gravity of magnitude g along -z (z is up everywhere in CraterKit).
  static Gravity downward(double g);

  void acceleration(const double x[3], double a[3]) const;
  double potential(const double x[3]) const; // per unit mass
  // |g| at x: the load that sets a bed's stiffness (0 without gravity).
  double magnitudeAt(const double x[3]) const;
  void validate() const;
};

} // namespace craterkit

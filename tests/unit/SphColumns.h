// Shared set-ups of the SPH unit tests: a periodic column at rest in its lithostatic state.
#pragma once

#include "sph/SphSolver.h"

#include <cmath>
#include <exception>
#include <string>

namespace craterkit::sphtest {

// Cohesionless soil (φ = 30°, Drucker–Prager) with a soft Murnaghan equation of state (matrix
// density ρ0, K, n; G = 0.35 K).
inline Material granularSoil(double rho0, double K, double n = 7.0) {
  Material soil;
  soil.name = "soil";
  soil.eos.model = EquationOfState::Model::Murnaghan;
  soil.eos.murnaghanRho0 = rho0, soil.eos.murnaghanK0 = K, soil.eos.murnaghanN = n;
  soil.bulkModulus = K, soil.shearModulus = 0.35 * K;
  soil.strength = Material::Strength::DruckerPrager;
  soil.frictionAngle = 30.0, soil.cohesion = 0.0;
  return soil;
}

// What SphParams::validate says of par, with one default material ("" when it takes it).
inline std::string refusal(SphParams par) {
  par.materials = {Material()};
  try {
    par.validate();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// nxy × nxy × nz particles of spacing dx (material 0) on three rows of rigid floor (material 1),
// periodic across x and y (sets par's box), each carrying m = ρb dx³ at rest, built in the
// lithostatic state p = ρb g (H − z), H = nz dx, of a Murnaghan law (matrix density ρ0, K, n)
// through its density; the floor at ρ0. With distention α > 1 the soil is porous, ρb = ρ0 / α:
// its pressure p = K/n ((αρ/ρ0)^n − 1) / α (the solver's P–α form) gives
// ρ = ρb (1 + n α p / K)^(1/n).
inline SphState lithostaticColumn(SphParams& par, int nxy, int nz, double dx, double rho0, double g,
                                  double K, double n, double alpha = 1.0) {
  for (int a = 0; a < 2; ++a) {
    par.periodic[a] = true;
    par.boxLo[a] = 0.0;
    par.boxHi[a] = nxy * dx;
  }
  SphState s;
  const double rhoB = rho0 / alpha, H = nz * dx, m = rhoB * dx * dx * dx, rest[3] = {0, 0, 0};
  for (int k = -3; k < nz; ++k)
    for (int j = 0; j < nxy; ++j)
      for (int i = 0; i < nxy; ++i) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        if (k < 0) {
          s.add(x, rest, rho0 * dx * dx * dx, rho0, 0.0, 1);
          continue;
        }
        const double p = rhoB * g * (H - x[2]);
        s.add(x, rest, m, rhoB * std::pow(1.0 + n * alpha * p / K, 1.0 / n), 0.0, 0);
        s.alpha.back() = alpha;
      }
  return s;
}

} // namespace craterkit::sphtest

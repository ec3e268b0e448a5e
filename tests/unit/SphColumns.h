// Shared set-ups of the SPH unit tests: a periodic column at rest in its lithostatic state.
#pragma once

#include "sph/SphSolver.h"

#include <cmath>

namespace craterkit::sphtest {

// nxy × nxy × nz particles of spacing dx (material 0) on three rows of rigid floor (material 1),
// periodic across x and y (sets par's box), each carrying m = ρ0 dx³ at rest, built in the
// lithostatic state p = ρ0 g (H − z), H = nz dx, of a Murnaghan law (ρ0, K, n) through its
// density; the floor at ρ0.
inline SphState lithostaticColumn(SphParams& par, int nxy, int nz, double dx, double rho0, double g,
                                  double K, double n) {
  for (int a = 0; a < 2; ++a) {
    par.periodic[a] = true;
    par.boxLo[a] = 0.0;
    par.boxHi[a] = nxy * dx;
  }
  SphState s;
  const double H = nz * dx, m = rho0 * dx * dx * dx, rest[3] = {0, 0, 0};
  for (int k = -3; k < nz; ++k)
    for (int j = 0; j < nxy; ++j)
      for (int i = 0; i < nxy; ++i) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        const double p = k < 0 ? 0.0 : rho0 * g * (H - x[2]);
        s.add(x, rest, m, rho0 * std::pow(1.0 + n * p / K, 1.0 / n), 0.0, k < 0 ? 1 : 0);
      }
  return s;
}

} // namespace craterkit::sphtest

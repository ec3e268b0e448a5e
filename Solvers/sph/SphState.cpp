#include "sph/SphState.h"

#include "common/Error.h"
#include "sph/SphParams.h"

#include <cmath>
#include <string>

namespace craterkit {

void SphState::add(const double pos[3], const double vel[3], double m, double density,
                   double energy, int mat) {
  for (int k = 0; k < 3; ++k) {
    x.push_back(pos[k]);
    v.push_back(vel[k]);
  }
  mass.push_back(m);
  rho.push_back(density);
  u.push_back(energy);
  h.push_back(0.0);
  S.insert(S.end(), 6, 0.0);
  alpha.push_back(1.0);
  damage.push_back(0.0);
  material.push_back(mat);
}

void checkState(const SphState& s, const SphParams& par) {
  const std::size_t n = s.size();
  if (n == 0)
    throw InputError("SPH: no particles");
  if (n >= (std::size_t(1) << 27))
    throw InputError("SPH: more than 2^27 particles");
  if (s.x.size() != 3 * n || s.v.size() != 3 * n || s.rho.size() != n || s.u.size() != n ||
      s.S.size() != 6 * n || s.alpha.size() != n || s.damage.size() != n || s.material.size() != n)
    throw InputError("SPH: the particle arrays differ in length");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string which = "SPH: particle " + std::to_string(i);
    if (!(s.mass[i] > 0.0) || !(s.rho[i] > 0.0) || !(s.u[i] >= 0.0) || !std::isfinite(s.mass[i]) ||
        !std::isfinite(s.rho[i]) || !std::isfinite(s.u[i]))
      throw InputError(which + " has a non-positive mass or density or a negative energy");
    if (s.material[i] < 0 || static_cast<std::size_t>(s.material[i]) >= par.materials.size())
      throw InputError(which + " has an unknown material index");
    if (!(s.alpha[i] >= 1.0) || !std::isfinite(s.alpha[i]))
      throw InputError(which + " has a distention below 1");
    if (!(s.damage[i] >= 0.0 && s.damage[i] <= 1.0))
      throw InputError(which + " has a damage outside [0, 1]");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s.x[3 * i + k]) || !std::isfinite(s.v[3 * i + k]))
        throw InputError(which + " has a non-finite position or velocity");
    if (par.materials[static_cast<std::size_t>(s.material[i])].rigid &&
        (s.v[3 * i] != 0.0 || s.v[3 * i + 1] != 0.0 || s.v[3 * i + 2] != 0.0))
      throw InputError(which + " belongs to a rigid boundary but is moving");
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(s.S[6 * i + k]))
        throw InputError(which + " has a non-finite stress");
  }
}

double kineticEnergy(const SphState& s) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    e += 0.5 * s.mass[i] *
         (s.v[3 * i] * s.v[3 * i] + s.v[3 * i + 1] * s.v[3 * i + 1] +
          s.v[3 * i + 2] * s.v[3 * i + 2]);
  return e;
}

double internalEnergy(const SphState& s) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    e += s.mass[i] * s.u[i];
  return e;
}

double potentialEnergy(const SphState& s, const SphParams& par) {
  double e = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double* x = &s.x[3 * i];
    e -= s.mass[i] * (par.gravity[0] * x[0] + par.gravity[1] * x[1] + par.gravity[2] * x[2]);
    if (par.pointMassGM > 0.0) {
      const double dx = x[0] - par.pointMassAt[0], dy = x[1] - par.pointMassAt[1],
                   dz = x[2] - par.pointMassAt[2];
      e -= s.mass[i] * par.pointMassGM / std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  return e;
}

void totalMomentum(const SphState& s, double p[3]) {
  p[0] = p[1] = p[2] = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < 3; ++k)
      p[k] += s.mass[i] * s.v[3 * i + k];
}

void totalAngularMomentum(const SphState& s, double L[3]) {
  L[0] = L[1] = L[2] = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double* x = &s.x[3 * i];
    const double* v = &s.v[3 * i];
    const double m = s.mass[i];
    L[0] += m * (x[1] * v[2] - x[2] * v[1]);
    L[1] += m * (x[2] * v[0] - x[0] * v[2]);
    L[2] += m * (x[0] * v[1] - x[1] * v[0]);
  }
}

} // namespace craterkit

#include "sph/Overburden.h"

#include <cmath>

namespace craterkit {

std::vector<double> earlyBulkModuli(const std::vector<Material>& materials) {
  std::vector<double> K;
  K.reserve(materials.size());
  for (const Material& m : materials)
    K.push_back(m.lawBulkModulus());
  return K;
}

void keepOverburden(SphState& s, const SphParams& par, const std::vector<double>& earlyK) {
  const double* g = par.gravity;
  const double gNorm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (!(par.overburdenDensity > 0.0) || !(gNorm > 0.0))
    return;
  const double down[3] = {g[0] / gNorm, g[1] / gNorm, g[2] / gNorm};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto m = static_cast<std::size_t>(s.material[i]);
    const Material& mat = par.materials[m];
    if (mat.rigid || mat.eos.model != EquationOfState::Model::Murnaghan || !(earlyK[m] > 0.0))
      continue; // no late-stage law (gases keep theirs)
    const double* x = &s.x[3 * i];
    const double depth = x[0] * down[0] + x[1] * down[1] + x[2] * down[2] + par.overburdenSurface;
    if (depth <= 0.0)
      continue;
    const double Klate = mat.eos.murnaghanK0, pL = par.overburdenDensity * gNorm * depth;
    s.rho[i] += (1.0 - Klate / earlyK[m]) * pL * mat.eos.murnaghanRho0 / Klate;
  }
}

} // namespace craterkit

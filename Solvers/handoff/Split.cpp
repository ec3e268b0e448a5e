#include "handoff/Split.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace craterkit {

void checkInputs(const SphSnapshot& sph, const ParticleSet& bed) {
  const std::size_t ns = sph.size();
  if (ns == 0)
    throw InputError("ImpactHandoff: the SPH input has no particles");
  if (sph.x.size() != 3 * ns || sph.v.size() != 3 * ns)
    throw InputError("ImpactHandoff: the SPH input needs positions, Velocity and Mass for every "
                     "particle");
  if (bed.size() == 0)
    throw InputError("ImpactHandoff: the bed input has no particles");
  for (std::size_t i = 0; i < ns; ++i) {
    if (!(sph.mass[i] > 0.0) || !std::isfinite(sph.mass[i]))
      throw InputError("ImpactHandoff: SPH particle " + std::to_string(i) +
                       " has a non-positive Mass");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(sph.x[3 * i + k]) || !std::isfinite(sph.v[3 * i + k]))
        throw InputError("ImpactHandoff: SPH particle " + std::to_string(i) +
                         " has a non-finite position or Velocity");
  }
}

SplitSets splitBySpeed(const SphSnapshot& sph, double limit) {
  SplitSets s;
  for (std::size_t i = 0; i < sph.size(); ++i) {
    const double* v = &sph.v[3 * i];
    const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    (v2 > limit * limit ? s.ejecta : s.compact).push_back(i);
  }
  if (s.compact.size() < 4) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", limit);
    throw InputError("ImpactHandoff: fewer than 4 SPH particles are slower than "
                     "EjectaSpeedLimit (" +
                     std::string(text) + " m/s): no compact material to build a shape from");
  }
  return s;
}

std::vector<std::size_t> curtainOf(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                                   const CurtainTest& inCurtain) {
  std::vector<std::size_t> curtain;
  for (std::size_t i : compact)
    if (inCurtain(sph, i))
      curtain.push_back(i);
  return curtain;
}

HandoffTotals sphTotals(const SphSnapshot& s, const std::vector<std::size_t>& subset) {
  HandoffTotals t;
  for (std::size_t i : subset) {
    const double m = s.mass[i];
    const double* x = &s.x[3 * i];
    const double* v = &s.v[3 * i];
    t.mass += m;
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += m * v[a];
    t.angularMomentum[0] += m * (x[1] * v[2] - x[2] * v[1]);
    t.angularMomentum[1] += m * (x[2] * v[0] - x[0] * v[2]);
    t.angularMomentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
  }
  return t;
}

CompactCloud::CompactCloud(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                           double alphaRadius)
    : x(3 * compact.size()), h(compact.size()) {
  const std::size_t n = compact.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = compact[k];
    h[k] = i < sph.h.size() && sph.h[i] > 0.0 ? sph.h[i] : 2.0 * alphaRadius;
    hmax = std::max(hmax, h[k]);
    for (int a = 0; a < 3; ++a)
      x[3 * k + a] = sph.x[3 * i + a];
  }
  const SizeClasses sizes = sizeClasses(h.data(), n);
  hOrdinary = sizes.large ? sizes.ordinaryMax : hmax;
  cells.build(x.data(), n, hOrdinary);
  if (sizes.large == 0)
    return;
  isWide.assign(n, 0);
  std::vector<double> at;
  for (std::size_t k = 0; k < n; ++k)
    if (sizes.isLarge(h[k])) {
      wide.push_back(static_cast<std::uint32_t>(k));
      isWide[k] = 1;
      at.insert(at.end(), &x[3 * k], &x[3 * k] + 3);
    }
  wideCells.build(at.data(), wide.size(), hmax);
  orderGrid = CellList::denseGeometry(x.data(), n, hmax);
  orderKey.resize(n);
  for (std::size_t k = 0; k < n; ++k)
    orderKey[k] = orderGrid.cellOf(&x[3 * k]);
}

} // namespace craterkit

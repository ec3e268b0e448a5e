#include "bonded/ShockViscosity.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace craterkit {
namespace {

[[noreturn]] void refuse(const char* property, const char* what, double value) {
  std::ostringstream s;
  s << "BondedImpact: " << property << ' ' << what << ", got " << value;
  throw InputError(s.str());
}

} // namespace

const char* dissipationName(BondedDissipation d) {
  switch (d) {
  case BondedDissipation::None:
    return "None";
  case BondedDissipation::ShockViscosity:
    return "ShockViscosity";
  }
  return "?";
}

BondedDissipation dissipationByName(const std::string& name) {
  for (BondedDissipation d : {BondedDissipation::None, BondedDissipation::ShockViscosity})
    if (name == dissipationName(d))
      return d;
  throw InputError("BondedImpact: Dissipation '" + name + "' is not one of None, ShockViscosity");
}

void ShockViscosityParams::validate() const {
  if (!(linear >= 0.0) || !std::isfinite(linear))
    refuse("ShockViscosityLinear", "must not be negative", linear);
  if (!(quadratic >= 0.0) || !std::isfinite(quadratic))
    refuse("ShockViscosityQuadratic", "must not be negative", quadratic);
  if (linear == 0.0 && quadratic == 0.0)
    refuse("ShockViscosityLinear and ShockViscosityQuadratic",
           "are both zero (use Dissipation None for no dissipation)", 0.0);
  if (!(threshold > 0.0) || !std::isfinite(threshold))
    refuse("ShockViscosityThreshold",
           "must be a positive approach speed in m/s (0 would damp every contact)", threshold);
}

ShockViscosity::ShockViscosity(const ShockViscosityParams& params, const ws2017::Law& law,
                               double lightestMass, double timeStep)
    : p_(params) {
  p_.validate();
  rEq_ = law.rEq();
  rEq2_ = rEq_ * rEq_;
  stiffness_ = 72.0 * law.epsilon / rEq2_;                      // φ''(r_eq) of Eq. 3
  const double crossing = std::sqrt(lightestMass / stiffness_); // r_eq / c0
  interval_ = static_cast<std::uint64_t>(
      std::max(1.0, std::floor(crossing / (kPulsesPerCrossing * timeStep))));
  tau_ = static_cast<double>(interval_) * timeStep;
}

double ShockViscosity::soundSpeed(double mass) const { return rEq_ * std::sqrt(stiffness_ / mass); }

double ShockViscosity::impulse(double w, double mi, double mj) const {
  const double q = w - p_.threshold;
  if (!(q > 0.0))
    return 0.0;
  const double sum = mi + mj, mu = mi * mj / sum, mBar = 2.0 * mu;
  const double c0 = rEq_ * std::sqrt(stiffness_ / mBar);
  const double rate = 2.0 * (p_.quadratic * q + p_.linear * c0) / rEq_; // γ = F / (μ q)
  return -mu * q * std::expm1(-rate * tau_);
}

void ShockViscosity::pulse(const Lists& lists, const double* x, double* v, const double* m,
                           double* internal, double* scratch) const {
  constexpr std::size_t L = 8;
  const std::size_t n = lists.n, blocks = (n + L - 1) / L;
  double* dv = scratch;           // 3 n: each particle's velocity change
  double* heat = scratch + 3 * n; // n: Σ_j J w / 2
  const double rEq2 = rEq2_, wTh2 = p_.threshold * p_.threshold;
  // Block by block, the eight lanes side by side as in the force pass (each lane sums its own
  // entries in list order); the test of a row of entries has no branch, and only the rare pairs
  // it finds are worked on.
#pragma omp parallel for schedule(dynamic, 64)
  for (long bl = 0; bl < static_cast<long>(blocks); ++bl) {
    const std::size_t b = static_cast<std::size_t>(bl);
    double xi[L], yi[L], zi[L], ui[L], vi[L], wi[L], px[L], py[L], pz[L], h[L];
    for (std::size_t l = 0; l < L; ++l) {
      const std::size_t i = std::min(n - 1, b * L + l);
      xi[l] = x[3 * i], yi[l] = x[3 * i + 1], zi[l] = x[3 * i + 2];
      ui[l] = v[3 * i], vi[l] = v[3 * i + 1], wi[l] = v[3 * i + 2];
      px[l] = py[l] = pz[l] = h[l] = 0.0;
    }
    for (std::size_t e = lists.blockStart[b]; e < lists.blockStart[b + 1]; e += L) {
      // Branch-free over the eight lanes: which pairs are in contact and approach faster than
      // the threshold (−dot > w_th r, compared squared; the same bits from either side).
      double r2[L], dot[L];
      bool fast[L];
      bool any = false;
      for (std::size_t l = 0; l < L; ++l) {
        const std::size_t j = lists.partner[e + l];
        const double dx = xi[l] - x[3 * j], dy = yi[l] - x[3 * j + 1], dz = zi[l] - x[3 * j + 2];
        r2[l] = dx * dx + dy * dy + dz * dz;
        dot[l] =
            (ui[l] - v[3 * j]) * dx + (vi[l] - v[3 * j + 1]) * dy + (wi[l] - v[3 * j + 2]) * dz;
        fast[l] =
            (r2[l] < rEq2) & (r2[l] > 0.0) & (dot[l] < 0.0) & (dot[l] * dot[l] > wTh2 * r2[l]);
        any |= fast[l];
      }
      if (!any)
        continue;
      for (std::size_t l = 0; l < L; ++l) {
        if (!fast[l])
          continue;
        const std::size_t i = std::min(n - 1, b * L + l), j = lists.partner[e + l];
        const double dx = xi[l] - x[3 * j], dy = yi[l] - x[3 * j + 1], dz = zi[l] - x[3 * j + 2];
        const double r = std::sqrt(r2[l]), w = -dot[l] / r;
        const double J = impulse(w, m[i], m[j]);
        const double k = J / (m[i] * r);
        px[l] += k * dx, py[l] += k * dy, pz[l] += k * dz;
        h[l] += 0.5 * J * w;
      }
    }
    for (std::size_t l = 0; l < L && b * L + l < n; ++l) {
      const std::size_t i = b * L + l;
      dv[3 * i] = px[l], dv[3 * i + 1] = py[l], dv[3 * i + 2] = pz[l];
      heat[i] = h[l];
    }
  }
#pragma omp parallel for schedule(static)
  for (long il = 0; il < static_cast<long>(n); ++il) {
    const std::size_t i = static_cast<std::size_t>(il);
    if (heat[i] == 0.0 && dv[3 * i] == 0.0 && dv[3 * i + 1] == 0.0 && dv[3 * i + 2] == 0.0)
      continue;
    const double* d = dv + 3 * i;
    v[3 * i] += d[0], v[3 * i + 1] += d[1], v[3 * i + 2] += d[2];
    internal[i] += heat[i] - 0.5 * m[i] * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
}

} // namespace craterkit

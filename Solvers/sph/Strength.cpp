#include "sph/Strength.h"

#include <algorithm>

namespace craterkit {

Rheology::Rheology(const Material& m) {
  G = m.shearModulus;
  alpha0 = m.distention;
  pe = m.crushPe;
  ps = m.crushPs;
  switch (m.strength) {
  case Material::Strength::None:
    kind = Fluid;
    break;
  case Material::Strength::VonMises:
    kind = VonMises;
    yield = m.yieldStress;
    break;
  case Material::Strength::DruckerPrager: {
    kind = DruckerPrager;
    const double phi = m.frictionAngle * M_PI / 180.0, sn = std::sin(phi);
    const double d = std::sqrt(3.0) * (3.0 - sn);
    dpK = 6.0 * m.cohesion * std::cos(phi) / d;
    dpB3 = 3.0 * 2.0 * sn / d;
    break;
  }
  }
}

double compactDistention(const Rheology& r, const EquationOfState& eos, double rho, double u,
                         double& alpha, double P) {
  double& a = alpha;
  if (!(a > 1.0 && a > r.crushAlpha(P)))
    return P;
  auto bulkPressure = [&](double al) { return eos.pressure(al * rho, u) / al; };
  // Compaction: α is the largest value in [1, α] on or below the crush curve. f(α) =
  // α − α_crush(P(α)) is ≤ 0 at α = 1 and > 0 here; the crossing is found by the Illinois
  // variant of regula falsi (superlinear, ~6 equation-of-state calls instead of bisection's
  // 40), which keeps the bracket, with a bisection step whenever the bracket fails to halve.
  auto f = [&](double al) { return al - r.crushAlpha(bulkPressure(al)); };
  double lo = 1.0, hi = a, flo = f(lo), fhi = a - r.crushAlpha(P);
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-12 * hi && flo < 0.0; ++it) {
    const double width = hi - lo;
    double x = lo - flo * width / (fhi - flo);
    if (!(x > lo && x < hi))
      x = 0.5 * (lo + hi);
    const double fx = f(x);
    if (!(fx <= 0.0)) { // a NaN pressure counts as above the curve: lo keeps f(lo) <= 0
      hi = x, fhi = fx;
      if (side == 1)
        flo *= 0.5; // Illinois: the end kept twice in a row counts half
      side = 1;
    } else {
      lo = x, flo = fx;
      if (side == -1)
        fhi *= 0.5;
      side = -1;
    }
    if (hi - lo > 0.5 * width) { // slow progress: bisect once
      const double mid = 0.5 * (lo + hi), fm = f(mid);
      (!(fm <= 0.0) ? hi : lo) = mid;
      (!(fm <= 0.0) ? fhi : flo) = fm;
      side = 0;
    }
  }
  a = lo;
  return bulkPressure(a);
}

double limitStress(const Rheology& r, double D, double P, double* S) {
  if (P < 0.0)
    P *= 1.0 - D;
  double f = 1.0;
  const double J2 = 0.5 * dot6(S, S);
  switch (r.kind) {
  case Rheology::Fluid:
    f = 0.0;
    break;
  case Rheology::VonMises: {
    const double Y = (1.0 - D) * r.yield;
    if (3.0 * J2 > Y * Y)
      f = Y / std::sqrt(3.0 * J2);
    break;
  }
  case Rheology::DruckerPrager: {
    // Tension is cut at the cone's apex (p = 0 without cohesion); damage removes cohesion.
    const double k = (1.0 - D) * r.dpK;
    if (r.dpB3 > 0.0)
      P = std::max(P, -k / r.dpB3);
    else if (P < -k)
      P = -k;
    const double Y = std::max(0.0, k + r.dpB3 * P);
    if (J2 > Y * Y)
      f = Y / std::sqrt(J2);
    break;
  }
  }
  if (f < 1.0)
    for (int k = 0; k < 6; ++k)
      S[k] *= f;
  return P;
}

} // namespace craterkit

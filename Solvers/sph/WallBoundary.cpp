#include "sph/WallBoundary.h"

#include "sph/Kernels.h"
#include "sph/NeighbourList.h"
#include "sph/SphParams.h"
#include "sph/SphState.h"
#include "sph/Strength.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {

// The bulk density at which the material's law gives the bulk pressure P (Adami Eq. 28): the
// reference ρ0/α where P is at or below the law's pressure there (a wall's density is not
// lowered by tension), else the root above it, where p rises with ρ for every law with a
// reference density: Newton's method from the present density (a step away from the root, so
// two or three iterations), bisection should it stall. `rho` for a law without one.
double densityAtPressure(const EquationOfState& eos, double alpha, double u, double P, double rho) {
  const double rho0 = eos.referenceDensity();
  if (!(rho0 > 0.0))
    return rho;
  const double lo0 = rho0 / alpha;
  auto f = [&](double r) { return eos.pressure(alpha * r, u) / alpha - P; };
  if (!(f(lo0) < 0.0))
    return lo0;
  double x = std::max(rho, lo0);
  for (int k = 0; k < 20; ++k) {
    const double fx = f(x), dr = 1e-7 * x, slope = (f(x + dr) - fx) / dr;
    if (!(slope > 0.0))
      break;
    const double next = std::max(lo0, x - fx / slope);
    if (std::abs(next - x) <= 1e-12 * x)
      return next;
    x = next;
  }
  double lo = lo0, hi = 1.01 * lo0;
  for (int k = 0; k < 60 && f(hi) < 0.0; ++k)
    lo = hi, hi = lo0 + 2.0 * (hi - lo0);
  for (int k = 0; k < 60 && hi - lo > 1e-12 * lo0; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

template <class K>
void extrapolate(SphState& s, std::vector<double>& p, std::vector<double>& c, const SphParams& par,
                 const std::vector<std::uint32_t>& walls, const std::vector<std::uint32_t>& start,
                 const std::vector<std::uint32_t>& entry, const std::vector<char>* need) {
  std::vector<Rheology> rh;
  for (const Material& m : par.materials)
    rh.emplace_back(m);
  double period[3];
  for (int k = 0; k < 3; ++k)
    period[k] = par.periodic[k] ? par.boxHi[k] - par.boxLo[k] : 0.0;
  const std::size_t nw = walls.size();
  // Walls read only non-rigid particles and write only themselves: no race.
#pragma omp parallel for schedule(dynamic, 64) if (nw >= 256)
  for (std::size_t k = 0; k < nw; ++k) {
    const std::size_t w = walls[k], mw = static_cast<std::size_t>(s.material[w]);
    if (need && !(*need)[w])
      continue;
    const double* xw = &s.x[3 * w];
    double g[3];
    bodyForce(par, xw, g); // minus a_w = 0
    double sumW = 0.0, sumP = 0.0, sumRhoR[3] = {0, 0, 0}, minP = 0.0;
    for (std::uint32_t e = start[k]; e < start[k + 1]; ++e) {
      const std::uint32_t code = entry[e];
      const std::size_t f = code / 32;
      double r[3];
      for (int a = 0; a < 3; ++a)
        r[a] = xw[a] - s.x[3 * f + a];
      if (code % 32 != kNoShift) {
        const std::uint32_t sh = code % 32;
        r[0] -= (static_cast<int>(sh % 3) - 1) * period[0];
        r[1] -= (static_cast<int>(sh / 3 % 3) - 1) * period[1];
        r[2] -= (static_cast<int>(sh / 9) - 1) * period[2];
      }
      const double r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
      const double hb = 0.5 * (s.h[w] + s.h[f]);
      if (!(r2 < hb * hb))
        continue;
      const double W = K::W(std::sqrt(r2), hb);
      sumW += W;
      sumP += p[f] * W;
      minP = std::min(minP, p[f]);
      for (int a = 0; a < 3; ++a)
        sumRhoR[a] += s.rho[f] * r[a] * W;
    }
    if (!(sumW > 0.0))
      continue; // no neighbour inside the support now: keeps what its own state gives
    const double Pw = (sumP + g[0] * sumRhoR[0] + g[1] * sumRhoR[1] + g[2] * sumRhoR[2]) / sumW;
    // The wall's own deviatoric stress (its Hooke rate against the adjacent flow) within its
    // material's yield surface at the extrapolated pressure.
    p[w] = limitStress(rh[mw], s.damage[w], std::max(Pw, minP), &s.S[6 * w]);
    const Material& mat = par.materials[mw];
    s.rho[w] = densityAtPressure(mat.eos, s.alpha[w], s.u[w], p[w], s.rho[w]);
    c[w] = signalSpeed(rh[mw], mat.eos.soundSpeed(s.alpha[w] * s.rho[w], s.u[w]), s.rho[w]);
  }
}

} // namespace

void WallBoundary::compact(const SphState& s, const std::vector<char>& rigid,
                           const NeighbourList& nb) {
  wall_.clear(), start_.assign(1, 0), entry_.clear();
  for (std::size_t w = 0; w < s.size(); ++w) {
    if (!rigid[static_cast<std::size_t>(s.material[w])])
      continue;
    const std::size_t before = entry_.size();
    for (std::uint32_t e = nb.start()[w]; e < nb.start()[w + 1]; ++e) {
      const std::uint32_t code = nb.entry()[e];
      if (!rigid[static_cast<std::size_t>(s.material[code / 32])])
        entry_.push_back(code);
    }
    if (entry_.size() > before) {
      wall_.push_back(static_cast<std::uint32_t>(w));
      start_.push_back(static_cast<std::uint32_t>(entry_.size()));
    }
  }
  builds_ = nb.version(), size_ = s.size();
}

void WallBoundary::apply(SphState& s, std::vector<double>& p, std::vector<double>& c,
                         const SphParams& par, const NeighbourList& nb,
                         const std::vector<char>* need) {
  std::vector<char> rigid(par.materials.size());
  bool any = false;
  for (std::size_t m = 0; m < rigid.size(); ++m)
    any = any || (rigid[m] = par.materials[m].rigid);
  if (!any)
    return;
  if (nb.version() != builds_ || s.size() != size_) {
    bool changed = s.size() != size_; // only the rigid particles' lists count
    for (std::size_t w = 0; w < s.size() && !changed; ++w)
      changed = rigid[static_cast<std::size_t>(s.material[w])] && nb.stamp(w) > builds_;
    if (changed)
      compact(s, rigid, nb);
    else
      builds_ = nb.version();
  }
  if (par.kernel == SphParams::Kernel::WendlandC2)
    extrapolate<WendlandC2>(s, p, c, par, wall_, start_, entry_, need);
  else
    extrapolate<CubicSpline>(s, p, c, par, wall_, start_, entry_, need);
}

} // namespace craterkit

// The time-step control of SphSolver (docs/physics.md §2.8): the Courant and force limits
// (Monaghan 1989; Δt ≤ C h / v_sig and Δt ≤ f sqrt(h / |a|)), each particle's own limit (what
// individual time steps would allow it), and the error of Heun's step against its Euler
// predictor, relative to each particle's own scales, that decides whether a step is taken
// again, shorter (as miluphcuda's adaptive RK2 does).
#include "sph/SphSolver.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {

// Δt ≤ f sqrt(h / |a|) for a particle of smoothing length h and acceleration a (∞ at rest).
double forceLimit(const SphParams& par, double h, const double* a) {
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  return a2 > 0.0 ? par.forceFactor * std::sqrt(h / std::sqrt(a2)) : INFINITY;
}

} // namespace

double SphSolver::limitStep(const SphState& s, const Rates& r, double maxSignal) const {
  const double courant = maxSignal > 0.0 ? par_.courant / maxSignal : INFINITY;
  const long n = static_cast<long>(s.size());
  double dt = INFINITY; // a minimum: the same for any order
#pragma omp parallel for schedule(static) reduction(min : dt) if (n >= 4096)
  for (long i = 0; i < n; ++i)
    dt = std::min(dt, forceLimit(par_, s.h[i], &r.dv[3 * i]));
  return std::min(courant, dt);
}

// Particle i's Courant limit from its signal speed over h/2 in the last rates (∞ without one).
double SphSolver::courantLimit(std::size_t i) const {
  return i < signal_.size() && signal_[i] > 0.0 ? par_.courant / signal_[i] : INFINITY;
}

SphSolver::Limits SphSolver::limits() const {
  Limits l;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    if (courantLimit(i) < l.courant)
      l.courant = courantLimit(i), l.courantParticle = i;
    const double f = forceLimit(par_, s_.h[i], &k1_.dv[3 * i]);
    if (f < l.force)
      l.force = f, l.forceParticle = i;
  }
  return l;
}

double SphSolver::particleStep(std::size_t i) const {
  return std::min(courantLimit(i), forceLimit(par_, s_.h[i], &k1_.dv[3 * i]));
}

std::vector<double> SphSolver::particleSteps() const {
  std::vector<double> dt(s_.size());
  for (std::size_t i = 0; i < s_.size(); ++i)
    dt[i] = particleStep(i);
  return dt;
}

// Each thread's largest error at its lowest particle, merged keeping the larger error and the
// lower particle on a tie: the serial loop's result for any thread count.
double SphSolver::stepError(double dt, const Rates& k2, std::size_t& worst) const {
  const long n = static_cast<long>(s_.size());
  double err = 0.0;
  long at = 0;
#pragma omp parallel if (n >= 4096)
  {
    double mine = 0.0;
    long mineAt = 0;
#pragma omp for schedule(static) nowait
    for (long i = 0; i < n; ++i) {
      const double e = particleError(static_cast<std::size_t>(i), dt, k2);
      if (e > mine)
        mine = e, mineAt = i;
    }
#pragma omp critical(ck_sph_step_error)
    if (mine > err || (mine == err && mine > 0.0 && mineAt < at))
      err = mine, at = mineAt;
  }
  if (err > 0.0)
    worst = static_cast<std::size_t>(at);
  return err;
}

// Particle i's relative Euler–Heun difference.
double SphSolver::particleError(std::size_t i, double dt, const Rates& k2) const {
  double dv2 = 0.0, v2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = k2.dv[3 * i + k] - k1_.dv[3 * i + k];
    dv2 += d * d;
    v2 += s_.v[3 * i + k] * s_.v[3 * i + k];
  }
  const double c = c_[i];
  const double ev = 0.5 * dt * std::sqrt(dv2) / std::max({c, std::sqrt(v2), 1e-30});
  // Density: Heun's against Euler's, unless both come out below the floor and are held
  // there (material dilating past it sets no step); a step that would leave a density
  // without a floor at or below zero is taken again, shorter.
  double er = 0.0;
  if (!par_.summationDensity) {
    const double fl = floorOf(s_, i);
    const double heun = s_.rho[i] + 0.5 * dt * (k1_.drho[i] + k2.drho[i]);
    const double euler = s_.rho[i] + dt * k1_.drho[i];
    if (fl <= 0.0 && !(heun > 0.0))
      er = INFINITY;
    else if (!(fl > 0.0 && heun <= fl && euler <= fl))
      er = 0.5 * dt * std::abs(k2.drho[i] - k1_.drho[i]) / s_.rho[i];
  }
  const double eu = 0.5 * dt * std::abs(k2.du[i] - k1_.du[i]) / (s_.u[i] + c * c + 1e-30);
  return std::max({ev, er, eu});
}

} // namespace craterkit

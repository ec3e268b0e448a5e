// The two stages of SphSolver::step (docs/physics.md §2.8): the Euler predictor, mid = s + Δt k1,
// and Heun's corrector, s += Δt (k1 + k2) / 2, with the densities held at their floors and the
// energies at zero. Each particle's update reads only its own fields, so the loops run on every
// thread with the bits of a serial loop (static chunks; the corrector's check reports the lowest
// failing particle, as a serial loop would, with every particle updated: nothing resumes after
// it); at two threads a serial loop here left one thread waiting for the other at every stage.
#include "sph/SphSolver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace craterkit {

void SphSolver::predict(double dt) {
  const long n = static_cast<long>(s_.size());
  const bool xs = par_.xsph > 0.0;
  SphState& mid = mid_;
  if (mid.size() != s_.size())
    mid = s_; // once: masses and materials never change, h is set by settle; no copy per try
  mid.alpha = s_.alpha, mid.damage = s_.damage;
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (long i = 0; i < n; ++i) {
    for (long k = 3 * i; k < 3 * i + 3; ++k) {
      mid.x[k] = s_.x[k] + dt * (s_.v[k] + (xs ? k1_.dx[k] : 0.0));
      mid.v[k] = s_.v[k] + dt * k1_.dv[k];
    }
    mid.rho[i] = par_.summationDensity
                     ? s_.rho[i]
                     : std::max({floorOf(s_, i), 1e-6 * s_.rho[i], s_.rho[i] + dt * k1_.drho[i]});
    mid.u[i] = std::max(0.0, s_.u[i] + dt * k1_.du[i]);
    for (long k = 6 * i; k < 6 * i + 6; ++k)
      mid.S[k] = s_.S[k] + dt * k1_.dS[k];
  }
  GradyKippFracture::integrate(mid.damage, s_.damage, dt, k1_.damage, nullptr);
}

void SphSolver::correct(double dt) {
  const long n = static_cast<long>(s_.size());
  const bool xs = par_.xsph > 0.0;
  const SphState& mid = mid_;
  const Rates& k2 = k2_;
  long bad = n; // the lowest particle left with a non-positive or non-finite density or energy
#pragma omp parallel for schedule(static) reduction(min : bad) if (n >= 4096)
  for (long i = 0; i < n; ++i) {
    for (long k = 3 * i; k < 3 * i + 3; ++k) {
      // before v changes
      s_.x[k] += 0.5 * dt * (s_.v[k] + mid.v[k] + (xs ? k1_.dx[k] + k2.dx[k] : 0.0));
      s_.v[k] += 0.5 * dt * (k1_.dv[k] + k2.dv[k]);
    }
    if (!par_.summationDensity)
      s_.rho[i] = std::max(floorOf(s_, i), s_.rho[i] + 0.5 * dt * (k1_.drho[i] + k2.drho[i]));
    s_.u[i] = std::max(0.0, s_.u[i] + 0.5 * dt * (k1_.du[i] + k2.du[i]));
    s_.alpha[i] = mid.alpha[i]; // compaction is kept from the predictor and can go on below
    if (!(s_.rho[i] > 0.0) || !std::isfinite(s_.rho[i]) || !std::isfinite(s_.u[i]))
      bad = std::min(bad, i);
    for (long k = 6 * i; k < 6 * i + 6; ++k)
      s_.S[k] += 0.5 * dt * (k1_.dS[k] + k2.dS[k]);
  }
  if (bad < n)
    throw std::runtime_error("SPH: particle " + std::to_string(bad) +
                             " has a non-positive or non-finite density or energy at t = " +
                             std::to_string(time_ + dt) + " s");
  // reads each particle's start-of-step damage before writing it
  GradyKippFracture::integrate(s_.damage, s_.damage, dt, k1_.damage, &k2.damage);
}

} // namespace craterkit

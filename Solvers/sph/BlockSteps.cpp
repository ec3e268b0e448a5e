// Individual (block) time steps for the late stage of SphSolver (docs/physics.md §2.8).
//
// Hierarchical power-of-two steps as in Gadget-2 (Springel 2005, MNRAS 364:1105, §5): a cycle
// of 2^(L + kHeadroom) ticks, L = SphParams::blockStepLevels, whose length is 2^L times the
// smallest particle step at its start; each particle steps by 2^k ticks, the largest power of
// two within its own Courant and force limits (and at most twice its last step, less after a
// large error), started at a multiple of 2^k. At each event (the end of some particles' steps)
// every particle's state is predicted to that time from its last update (x = x0 + τ v0 +
// τ²/2 a0; v, ρ, u and S linear in τ with the rates of its last update), pressures and walls
// follow from the predicted state, and only the particles at the end of their step (the
// active ones) have their rates evaluated: k2 at x(dt). Their update is the kick-drift-kick
// leapfrog in Gadget's form, with the trapezoid for v, ρ, u, S and D: v = v0 + dt/2 (a0 +
// a(dt)), x = x0 + dt v0 + dt²/2 a0, which is Heun's step (sph/SphSolver.cpp) with its
// predictor's rates taken at the new positions, and whose end rates serve as the next step's
// start rates (one rate evaluation per particle step instead of Heun's two). Second order
// like Heun's; no step is taken again: the Euler–k2 difference (Heun's error measure) only
// shortens the particle's next step.
//
// The neighbour time-step limiter of Saitoh & Makino (2009, ApJ 697 L99): no listed neighbour
// of a particle has a step more than 4 times (2 levels above) its own; a particle whose step
// would break this is moved down at once: at the start of its step by a shorter step, in the
// middle of it by ending the step at the next multiple of the allowed one (woken). Checked for
// the active particles at every event, for all listed pairs after each full build of the lists
// and for the lists that gained pairs after a partial rebuild (sph/PartialRebuild.cpp).
//
// Used only after the late-stage switch, where the flow is slow and the shock has gone: the
// energy and momentum are then no longer conserved to round-off (a pair's two forces are
// taken at different times), and the error control cannot retake a step.
#include "sph/SphSolver.h"

#include "sph/Strength.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace craterkit {

namespace {
// Ticks below the cycle's smallest step at its start: a particle's limit may fall by this many
// powers of two within a cycle before its step overruns it (counted in BlockStats::overruns).
constexpr int kHeadroom = 6;

std::uint64_t ticks(int level) { return std::uint64_t{1} << level; }
} // namespace

// The largest level whose step fits `want` (seconds), starts at t and ends by the cycle's end.
int SphSolver::blockLevel(std::uint64_t t, double want) const {
  const int top = par_.blockStepLevels + kHeadroom;
  const double r = want / blk_.tick;
  int k = r >= 2.0 ? std::min(top, static_cast<int>(std::floor(std::log2(r)))) : 0;
  while (k > 0 && ((t & (ticks(k) - 1)) != 0 || t + ticks(k) > blk_.end))
    --k;
  return k;
}

void SphSolver::blockStart(double dtAsk) {
  Block& b = blk_;
  const std::size_t n = s_.size();
  if (b.cap.size() != n)
    b.cap.assign(n, 2.0 * stableStep_); // the first cycle grows from the last global step
  b.want.resize(n);
  double dmin = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    b.want[i] = std::min(particleStep(i), b.cap[i]);
    dmin = std::min(dmin, b.want[i]);
  }
  const double cycle =
      std::isfinite(dmin) ? std::min(dtAsk, std::ldexp(dmin, par_.blockStepLevels)) : dtAsk;
  b.end = ticks(par_.blockStepLevels + kHeadroom);
  b.tick = cycle / static_cast<double>(b.end);
  b.x = s_.x, b.v = s_.v, b.rho = s_.rho, b.u = s_.u, b.S = s_.S, b.damage = s_.damage;
  b.t0.assign(n, 0);
  b.t1.resize(n);
  b.level.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    b.level[i] = blockLevel(0, b.want[i]);
    b.t1[i] = ticks(b.level[i]);
  }
  blockLimit(0, nullptr);
}

void SphSolver::blockLimit(std::uint64_t t, const std::vector<std::uint32_t>* from) {
  Block& b = blk_;
  std::vector<std::uint32_t>& q = b.queue;
  if (!from) { // seeded with the particles that have a neighbour too far above them
    const std::size_t n = s_.size();
    std::vector<char>& seed = b.need;
    seed.assign(n, 0);
#pragma omp parallel for schedule(dynamic, 1024) if (n >= 4096)
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t e = nb_.start()[i]; e < nb_.start()[i + 1] && !seed[i]; ++e)
        seed[i] = b.level[nb_.entry()[e] / 32] > b.level[i] + 2;
    q.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (seed[i])
        q.push_back(static_cast<std::uint32_t>(i));
  } else {
    q = *from;
  }
  // j's step to at most level k from t (k ≥ the level of the particle that asks, which is
  // active at t, so t is a multiple of its step and the new end lies after t).
  const auto lower = [&](std::size_t j, int k) {
    if (b.t0[j] == t) {
      while (k > 0 && (t & (ticks(k) - 1)) != 0)
        --k;
      b.t1[j] = t + ticks(k);
    } else {
      b.t1[j] = std::min(b.t1[j], ((t >> k) + 1) << k);
      ++b.stats.wakes;
    }
    b.level[j] = k;
    q.push_back(static_cast<std::uint32_t>(j));
  };
  // Levels only fall, so the work list ends.
  for (std::size_t head = 0; head < q.size(); ++head) {
    const std::size_t i = q[head];
    const std::uint32_t first = nb_.start()[i], last = nb_.start()[i + 1];
    for (std::uint32_t e = first; e < last; ++e) {
      const std::size_t j = nb_.entry()[e] / 32;
      if (j != i && b.level[i] > b.level[j] + 2)
        lower(i, b.level[j] + 2);
    }
    for (std::uint32_t e = first; e < last; ++e) {
      const std::size_t j = nb_.entry()[e] / 32;
      if (j != i && b.level[j] > b.level[i] + 2)
        lower(j, b.level[i] + 2);
    }
  }
}

void SphSolver::blockPredict(std::uint64_t t) {
  Block& b = blk_;
  const std::size_t n = s_.size();
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(t - b.t0[i]) * b.tick;
    for (int k = 0; k < 3; ++k) {
      const std::size_t m = 3 * i + k;
      const double a = k1_.dv[m];
      s_.x[m] = b.x[m] + tau * (b.v[m] + 0.5 * tau * a);
      s_.v[m] = b.v[m] + tau * a;
    }
    s_.rho[i] = std::max({floorOf(s_, i), 1e-6 * b.rho[i], b.rho[i] + tau * k1_.drho[i]});
    s_.u[i] = std::max(0.0, b.u[i] + tau * k1_.du[i]);
    for (int k = 0; k < 6; ++k)
      s_.S[6 * i + k] = b.S[6 * i + k] + tau * k1_.dS[6 * i + k];
  }
}

// Particle i's update over dt with the rates of its last update (k1_) and of now (k2_), as
// Heun's corrector; k2_'s entries become its start rates. Returns the Euler–k2 difference
// relative to its own scales, as SphSolver::stepError.
double SphSolver::closeParticle(std::size_t i, double dt) {
  Block& b = blk_;
  const double h = 0.5 * dt;
  double dv2 = 0.0, v2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t m = 3 * i + k;
    const double d = k2_.dv[m] - k1_.dv[m];
    dv2 += d * d;
    v2 += b.v[m] * b.v[m];
    b.v[m] += h * (k1_.dv[m] + k2_.dv[m]);
    s_.v[m] = b.v[m], b.x[m] = s_.x[m];
    k1_.dv[m] = k2_.dv[m];
  }
  const double c = c_[i], fl = floorOf(s_, i);
  const double heun = b.rho[i] + h * (k1_.drho[i] + k2_.drho[i]);
  const double euler = b.rho[i] + dt * k1_.drho[i];
  double err = h * std::sqrt(dv2) / std::max({c, std::sqrt(v2), 1e-30});
  if (!(fl > 0.0 && heun <= fl && euler <= fl))
    err = std::max(err, h * std::abs(k2_.drho[i] - k1_.drho[i]) / b.rho[i]);
  err = std::max(err, h * std::abs(k2_.du[i] - k1_.du[i]) / (b.u[i] + c * c + 1e-30));
  b.rho[i] = std::max(fl, heun);
  b.u[i] = std::max(0.0, b.u[i] + h * (k1_.du[i] + k2_.du[i]));
  s_.rho[i] = b.rho[i], s_.u[i] = b.u[i];
  k1_.drho[i] = k2_.drho[i], k1_.du[i] = k2_.du[i];
  for (int k = 0; k < 6; ++k) {
    const std::size_t m = 6 * i + k;
    b.S[m] += h * (k1_.dS[m] + k2_.dS[m]);
    k1_.dS[m] = k2_.dS[m];
  }
  if (!k1_.damage.rate.empty()) { // as GradyKippFracture::integrate with both rates
    const double rate = 0.5 * (k1_.damage.rate[i] + k2_.damage.rate[i]);
    const double cap = std::max(k1_.damage.cap[i], k2_.damage.cap[i]);
    if (rate > 0.0) {
      const double cb = std::cbrt(b.damage[i]) + dt * rate;
      b.damage[i] = std::max(b.damage[i], std::min({cb * cb * cb, cap, 1.0}));
    }
    s_.damage[i] = b.damage[i];
    k1_.damage.rate[i] = k2_.damage.rate[i], k1_.damage.cap[i] = k2_.damage.cap[i];
  }
  // The yield limit at the new state, as settle applies it after Heun's step: the next
  // predictions start from a stress on or inside the yield surface.
  const Material& mat = par_.materials[static_cast<std::size_t>(s_.material[i])];
  const double a = s_.alpha[i];
  limitStress(Rheology(mat), b.damage[i], mat.eos.pressure(a * b.rho[i], b.u[i]) / a, &b.S[6 * i]);
  for (int k = 0; k < 6; ++k)
    s_.S[6 * i + k] = b.S[6 * i + k];
  return err;
}

double SphSolver::blockClose(std::uint64_t t) {
  Block& b = blk_;
  const std::vector<std::uint32_t>& act = b.active;
  const std::size_t na = act.size();
  double errMax = 0.0;
  bool bad = false;
#pragma omp parallel for schedule(static) reduction(max : errMax) reduction(|| : bad) if (na >= 512)
  for (std::size_t q = 0; q < na; ++q) {
    const std::size_t i = act[q];
    const double dt = static_cast<double>(t - b.t0[i]) * b.tick;
    const double err = closeParticle(i, dt);
    errMax = std::max(errMax, err);
    bad = bad || !(s_.rho[i] > 0.0) || !std::isfinite(s_.rho[i]) || !std::isfinite(s_.u[i]);
    const double grow = err > 0.0 ? std::min(2.0, 0.9 * std::sqrt(par_.errorTolerance / err)) : 2.0;
    b.cap[i] = dt * std::max(0.1, grow);
    b.want[i] = std::min(particleStep(i), b.cap[i]);
    b.t0[i] = t;
  }
  if (bad)
    throw std::runtime_error("SPH: a particle has a non-positive or non-finite density or energy "
                             "in a block step ending at t = " +
                             std::to_string(time_ + static_cast<double>(t) * b.tick) + " s");
  if (t == b.end) // the cycle is over: the levels stay those of the last steps
    return errMax;
  for (std::size_t q = 0; q < na; ++q) {
    const std::size_t i = act[q];
    b.level[i] = blockLevel(t, b.want[i]);
    b.t1[i] = t + ticks(b.level[i]);
    if (std::ldexp(b.tick, b.level[i]) > b.want[i])
      ++b.stats.overruns;
  }
  blockLimit(t, &b.active);
  return errMax;
}

double SphSolver::blockCycle(double dtAsk) {
  Block& b = blk_;
  blockStart(dtAsk);
  const std::size_t n = s_.size();
  double errMax = 0.0;
  for (std::uint64_t t = 0; t < b.end;) {
    std::uint64_t next = b.end;
    for (std::size_t i = 0; i < n; ++i)
      next = std::min(next, b.t1[i]);
    // The list must hold every pair over the motion to the next event; a new list brings pairs
    // the limiter has not seen.
    const double dt = static_cast<double>(next - t) * b.tick;
    if (!nb_.valid(s_, par_, k1_.dx, k1_.dv, dt)) {
      // First the movers' lists alone (sph/PartialRebuild.cpp; up to two more passes for the
      // particles whose clearance the one before lowered); the limiter then needs to see only the
      // lists that gained pairs.
      bool kept = false;
      for (int pass = 0; pass < 3 && !kept && nb_.refresh(s_, par_, k1_.dx, k1_.dv, dt); ++pass) {
        blockLimit(t, &nb_.changed());
        kept = nb_.valid(s_, par_, k1_.dx, k1_.dv, dt);
      }
      if (!kept) {
        nb_.build(s_, par_, k1_.dx, dt);
        blockLimit(t, nullptr);
      }
      next = b.end;
      for (std::size_t i = 0; i < n; ++i)
        next = std::min(next, b.t1[i]);
    }
    blockPredict(next);
    b.active.clear();
    b.need.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (b.t1[i] == next) {
        b.active.push_back(static_cast<std::uint32_t>(i));
        b.need[i] = 1;
        for (std::uint32_t e = nb_.start()[i]; e < nb_.start()[i + 1]; ++e)
          b.need[nb_.entry()[e] / 32] = 1;
      }
    settle(s_, p_, c_, &b.need); // the walls only where an update reads them
    computeRates(s_, p_, c_, k2_, &b.active);
    errMax = std::max(errMax, blockClose(next));
    ++b.stats.substeps;
    b.stats.updates += b.active.size();
    t = next;
  }
  settle(s_, p_, c_); // the pressures of the synchronised state
  double dmin = INFINITY;
  for (std::size_t i = 0; i < n; ++i)
    dmin = std::min(dmin, b.want[i]);
  const double cycle = static_cast<double>(b.end) * b.tick;
  stableStep_ = std::isfinite(dmin) ? std::ldexp(dmin, par_.blockStepLevels) : 2.0 * cycle;
  record_.attempts = 1, record_.error = errMax, record_.errorCapped = false;
  time_ += cycle;
  ++steps_;
  return cycle;
}

} // namespace craterkit

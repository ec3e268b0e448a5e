#include "sph/SphSolver.h"

#include "common/CellList.h"
#include "common/Error.h"
#include "sph/Kernels.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace craterkit {

void SphState::add(const double pos[3], const double vel[3], double m, double density, double energy, int mat) {
  for (int k = 0; k < 3; ++k) {
    x.push_back(pos[k]);
    v.push_back(vel[k]);
  }
  mass.push_back(m);
  rho.push_back(density);
  u.push_back(energy);
  h.push_back(0.0);
  material.push_back(mat);
}

void SphParams::validate() const {
  if (eos.empty())
    throw InputError("SPH: no equation of state");
  if (!(alpha >= 0.0) || !(beta >= 0.0))
    throw InputError("SPH: artificial viscosity alpha and beta must not be negative");
  if (!(kappa > 1.0 && kappa < 10.0))
    throw InputError("SPH: kappa (support radius over particle spacing) must be in (1, 10)");
  if (!(courant > 0.0 && courant <= 1.0))
    throw InputError("SPH: the Courant number must be in (0, 1]");
  for (int k = 0; k < 3; ++k)
    if (periodic[k] && !(boxHi[k] > boxLo[k]))
      throw InputError("SPH: a periodic axis needs boxHi > boxLo");
}

SphSolver::SphSolver(const SphState& initial, const SphParams& params) : s_(initial), par_(params) {
  par_.validate();
  for (EquationOfState& e : par_.eos)
    e.validate();
  const std::size_t n = s_.size();
  if (n == 0)
    throw InputError("SPH: no particles");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(s_.mass[i] > 0.0) || !(s_.rho[i] > 0.0) || !(s_.u[i] >= 0.0))
      throw InputError("SPH: particle " + std::to_string(i) + " has a non-positive mass or density or a negative energy");
    if (s_.material[i] < 0 || static_cast<std::size_t>(s_.material[i]) >= par_.eos.size())
      throw InputError("SPH: particle " + std::to_string(i) + " has an unknown material index");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s_.x[3 * i + k]) || !std::isfinite(s_.v[3 * i + k]))
        throw InputError("SPH: particle " + std::to_string(i) + " has a non-finite position or velocity");
  }
  settle(s_);
  Rates r;
  lastMaxSignal_ = computeRates(s_, r, p_, cs_);
}

void SphSolver::settle(SphState& s) const {
  wrap(s);
  updateSmoothing(s);
  if (par_.summationDensity)
    densityBySummation(s);
}


void SphSolver::updateSmoothing(SphState& s) const {
  for (std::size_t i = 0; i < s.size(); ++i)
    s.h[i] = par_.kappa * std::cbrt(s.mass[i] / s.rho[i]);
}

void SphSolver::wrap(SphState& s) const {
  for (int k = 0; k < 3; ++k) {
    if (!par_.periodic[k])
      continue;
    const double lo = par_.boxLo[k], L = par_.boxHi[k] - lo;
    for (std::size_t i = 0; i < s.size(); ++i) {
      double& x = s.x[3 * i + k];
      x = lo + (x - lo) - L * std::floor((x - lo) / L);
    }
  }
}

namespace {
// Real particles plus, for periodic axes, their images within one support radius of the box,
// in a cell list.
struct Neighbourhood {
  std::vector<double> pos;
  std::vector<std::size_t> origin;
  CellList cells;
  double hmax = 0.0;
  Neighbourhood(const SphState& s, const SphParams& par) {
    const std::size_t n = s.size();
    hmax = *std::max_element(s.h.begin(), s.h.end());
    pos = s.x;
    origin.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      origin[i] = i;
    for (int sx = -1; sx <= 1; ++sx)
      for (int sy = -1; sy <= 1; ++sy)
        for (int sz = -1; sz <= 1; ++sz) {
          const int shift[3] = {sx, sy, sz};
          bool ok = sx || sy || sz;
          for (int k = 0; k < 3 && ok; ++k)
            ok = shift[k] == 0 || par.periodic[k];
          if (!ok)
            continue;
          for (std::size_t i = 0; i < n; ++i) {
            double y[3];
            bool near = true;
            for (int k = 0; k < 3 && near; ++k) {
              y[k] = s.x[3 * i + k] + shift[k] * (par.boxHi[k] - par.boxLo[k]);
              near = y[k] >= par.boxLo[k] - hmax && y[k] <= par.boxHi[k] + hmax;
            }
            if (!near)
              continue;
            pos.insert(pos.end(), y, y + 3);
            origin.push_back(i);
          }
        }
    cells.build(pos.data(), origin.size(), hmax);
  }
};

// ρ_a = Σ_b m_b W(r_ab, h̄_ab), the particle itself included.
template <class K> void summationDensity(SphState& s, const SphParams& par) {
  const Neighbourhood nb(s, par);
  std::vector<double> rho(s.size(), 0.0);
  // One particle per iteration, its own sum: the same result for any thread count.
#pragma omp parallel for schedule(dynamic, 256) if (s.size() >= 512)
  for (std::size_t a = 0; a < s.size(); ++a) {
    const double* xa = &s.x[3 * a];
    double sum = 0.0;
    nb.cells.forEachCandidate(xa, nb.hmax, [&](std::size_t q) {
      const std::size_t b = nb.origin[q];
      const double* xb = &nb.pos[3 * q];
      const double r = std::sqrt((xa[0] - xb[0]) * (xa[0] - xb[0]) + (xa[1] - xb[1]) * (xa[1] - xb[1]) +
                                 (xa[2] - xb[2]) * (xa[2] - xb[2]));
      sum += s.mass[b] * K::W(r, 0.5 * (s.h[a] + s.h[b]));
    });
    rho[a] = sum;
  }
  s.rho = rho;
}

template <class K>
double rates(const SphState& s, const SphParams& par, const std::vector<double>& p, const std::vector<double>& c,
             std::vector<double>& dv, std::vector<double>& drho, std::vector<double>& du) {
  const std::size_t n = s.size();
  const Neighbourhood nb(s, par);
  const double hmax = nb.hmax;
  const std::vector<double>& pos = nb.pos;
  const std::vector<std::size_t>& origin = nb.origin;
  const CellList& cells = nb.cells;
  dv.assign(3 * n, 0.0);
  drho.assign(n, 0.0);
  du.assign(n, 0.0);
  double maxSignal = 0.0;
  // Each particle accumulates only its own rates (pairs are visited from both sides), so the
  // loop needs no atomics and gives the same bits for any thread count.
#pragma omp parallel for schedule(dynamic, 256) reduction(max : maxSignal) if (n >= 512)
  for (std::size_t a = 0; a < n; ++a) {
    const double* xa = &s.x[3 * a];
    const double* va = &s.v[3 * a];
    const double pa = p[a] / (s.rho[a] * s.rho[a]);
    double acc[3] = {0, 0, 0}, dr = 0.0, de = 0.0, signal = c[a];
    cells.forEachCandidate(xa, hmax, [&](std::size_t q) {
      const std::size_t b = origin[q];
      if (q == a)
        return;
      const double* xb = &pos[3 * q];
      const double rx = xa[0] - xb[0], ry = xa[1] - xb[1], rz = xa[2] - xb[2];
      const double r2 = rx * rx + ry * ry + rz * rz;
      const double hb = 0.5 * (s.h[a] + s.h[b]);
      if (r2 >= hb * hb || r2 == 0.0)
        return;
      const double r = std::sqrt(r2);
      const double g = K::dWdr(r, hb) / r; // ∇_a W = g r_ab
      const double* vb = &s.v[3 * b];
      const double vx = va[0] - vb[0], vy = va[1] - vb[1], vz = va[2] - vb[2];
      const double vr = vx * rx + vy * ry + vz * rz;
      double pi = 0.0;
      if (vr < 0.0) {
        const double mu = hb * vr / (r2 + 0.01 * hb * hb); // h̄ = support, as miluphcuda
        const double cbar = 0.5 * (c[a] + c[b]), rhobar = 0.5 * (s.rho[a] + s.rho[b]);
        pi = (-par.alpha * cbar * mu + par.beta * mu * mu) / rhobar;
        signal = std::max(signal, c[a] + c[b] - 3.0 * vr / r);
      }
      const double mb = s.mass[b];
      const double f = mb * (pa + p[b] / (s.rho[b] * s.rho[b]) + pi) * g;
      acc[0] -= f * rx;
      acc[1] -= f * ry;
      acc[2] -= f * rz;
      const double vgrad = vr * g; // v_ab · ∇_a W
      dr += mb * vgrad;
      de += mb * (pa + 0.5 * pi) * vgrad;
    });
    for (int k = 0; k < 3; ++k)
      dv[3 * a + k] = acc[k] + par.gravity[k];
    drho[a] = dr;
    du[a] = de;
    maxSignal = std::max(maxSignal, signal / (0.5 * s.h[a]));
  }
  return maxSignal;
}
} // namespace

double SphSolver::computeRates(const SphState& s, Rates& r, std::vector<double>& p, std::vector<double>& c) const {
  const std::size_t n = s.size();
  p.resize(n);
  c.resize(n);
#pragma omp parallel for schedule(static) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    const EquationOfState& e = par_.eos[static_cast<std::size_t>(s.material[i])];
    p[i] = e.pressure(s.rho[i], s.u[i]);
    c[i] = e.soundSpeed(s.rho[i], s.u[i]);
  }
  if (par_.kernel == SphParams::Kernel::WendlandC2)
    return rates<WendlandC2>(s, par_, p, c, r.dv, r.drho, r.du);
  return rates<CubicSpline>(s, par_, p, c, r.dv, r.drho, r.du);
}

void SphSolver::densityBySummation(SphState& s) const {
  if (par_.kernel == SphParams::Kernel::WendlandC2)
    summationDensity<WendlandC2>(s, par_);
  else
    summationDensity<CubicSpline>(s, par_);
  updateSmoothing(s);
}

double SphSolver::courantStep() const { return par_.courant / lastMaxSignal_; }

double SphSolver::step(double dt) {
  if (dt <= 0.0)
    dt = courantStep();
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::runtime_error("SPH: the time step collapsed at t = " + std::to_string(time_));
  Rates k1, k2;
  std::vector<double> p, c;
  computeRates(s_, k1, p, c);
  SphState mid = s_;
  const std::size_t n = s_.size();
  for (std::size_t i = 0; i < 3 * n; ++i) {
    mid.x[i] += dt * s_.v[i];
    mid.v[i] += dt * k1.dv[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    mid.rho[i] += dt * k1.drho[i];
    mid.u[i] = std::max(0.0, mid.u[i] + dt * k1.du[i]);
  }
  settle(mid);
  computeRates(mid, k2, p, c);
  for (std::size_t i = 0; i < 3 * n; ++i) {
    s_.x[i] += 0.5 * dt * (s_.v[i] + mid.v[i]); // before v is updated below
    s_.v[i] += 0.5 * dt * (k1.dv[i] + k2.dv[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    s_.rho[i] += 0.5 * dt * (k1.drho[i] + k2.drho[i]);
    s_.u[i] = std::max(0.0, s_.u[i] + 0.5 * dt * (k1.du[i] + k2.du[i]));
    if (!(s_.rho[i] > 0.0) || !std::isfinite(s_.rho[i]))
      throw std::runtime_error("SPH: particle " + std::to_string(i) + " has a non-positive density at t = " +
                               std::to_string(time_ + dt));
  }
  settle(s_);
  Rates r;
  lastMaxSignal_ = computeRates(s_, r, p_, cs_);
  time_ += dt;
  return dt;
}

void SphSolver::advanceTo(double t) {
  while (time_ < t) {
    const double dt = std::min(courantStep(), t - time_);
    step(dt);
  }
}

double SphSolver::totalEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double v2 = s_.v[3 * i] * s_.v[3 * i] + s_.v[3 * i + 1] * s_.v[3 * i + 1] + s_.v[3 * i + 2] * s_.v[3 * i + 2];
    e += s_.mass[i] * (0.5 * v2 + s_.u[i]);
  }
  return e;
}

void SphSolver::totalMomentum(double p[3]) const {
  p[0] = p[1] = p[2] = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i)
    for (int k = 0; k < 3; ++k)
      p[k] += s_.mass[i] * s_.v[3 * i + k];
}

} // namespace craterkit

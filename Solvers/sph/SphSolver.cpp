#include "sph/SphSolver.h"

#include "common/Error.h"
#include "common/Random.h"
#include "sph/Kernels.h"

#include <Eigen/Dense>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
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

void SphParams::validate() const {
  if (materials.empty())
    throw InputError("SPH: no material");
  if (!(alpha >= 0.0) || !(beta >= 0.0) || !std::isfinite(alpha) || !std::isfinite(beta))
    throw InputError("SPH: artificial viscosity alpha and beta must be finite and not negative");
  if (!(xsph >= 0.0 && xsph <= 1.0))
    throw InputError("SPH: the XSPH factor must be in [0, 1]");
  if (!(kappa > 1.0 && kappa < 10.0))
    throw InputError("SPH: kappa (support radius over particle spacing) must be in (1, 10)");
  if (!(courant > 0.0 && courant <= 1.0))
    throw InputError("SPH: the Courant number must be in (0, 1]");
  if (!(densityFloor < 1.0))
    throw InputError(
        "SPH: the density floor must be below 1 (a fraction of the reference bulk density)");
  if (!(forceFactor > 0.0 && forceFactor <= 1.0))
    throw InputError("SPH: the force time-step factor must be in (0, 1]");
  if (!(errorTolerance > 0.0 && errorTolerance <= 1.0))
    throw InputError("SPH: the error tolerance must be in (0, 1]");
  if (!(minTimeStep >= 0.0))
    throw InputError("SPH: the time-step floor must not be negative");
  if (!(maxSmoothingGrowth == 0.0 ||
        (maxSmoothingGrowth >= 1.0 && std::isfinite(maxSmoothingGrowth))))
    throw InputError("SPH: the smoothing-length growth cap must be 0 (none) or at least 1");
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(gravity[k]) || !std::isfinite(pointMassAt[k]))
      throw InputError("SPH: gravity must be finite");
    if (periodic[k] && !(boxHi[k] > boxLo[k]))
      throw InputError("SPH: a periodic axis needs boxHi > boxLo");
  }
  if (!(pointMassGM >= 0.0) || !std::isfinite(pointMassGM))
    throw InputError("SPH: the point mass GM must be finite and not negative");
  if (!(domainRadius >= 0.0) || !std::isfinite(domainRadius))
    throw InputError("SPH: the domain radius must be finite and not negative (0: no limit)");
  if (!std::isfinite(lateStageTime))
    throw InputError("SPH: the late-stage time must be finite (negative: no late stage)");
  if (lateStageTime >= 0.0 && !(lateStageSoundSpeed > 0.0 && std::isfinite(lateStageSoundSpeed)))
    throw InputError("SPH: the late-stage sound speed must be positive");
}

namespace {

constexpr std::uint32_t kNoShift =
    13;                        // image code (sx+1) + 3 (sy+1) + 9 (sz+1) of the particle itself
constexpr int kMaxLevels = 16; // levels of h in the neighbour grids (√2 apart)

// Loops cloned for x86-64-v4 (AVX-512) and chosen at run time where the processor has it;
// elsewhere the generic code runs. The two differ only by rounding.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#define CK_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "default")))
#else
#define CK_SIMD_CLONES
#endif

// A run of candidate partners of one particle, in the neighbour grid's sorted order.
struct CandidateRange {
  const double *x, *y, *z, *h, *margin;
  const std::uint32_t* entry; // index * 32 + image code
  std::uint32_t count;
};

// Which candidates particle a (at xa, with h and margin ha, ma; `self` its own entry) lists:
// those within grow max(h_a, h_b) plus the larger margin. keep[k] is 1 for those; returns true
// if one not listed lies within twice the margin (a near miss). One vector pass, no branches.
CK_SIMD_CLONES bool listCandidates(const CandidateRange& c, const double* xa, double ha, double ma,
                                   double grow, std::uint32_t self, std::uint8_t* keep) {
  const double x0 = xa[0], x1 = xa[1], x2 = xa[2];
  int nearMiss = 0;
#pragma omp simd reduction(| : nearMiss)
  for (std::uint32_t k = 0; k < c.count; ++k) {
    const double pairMu = std::max(ma, c.margin[k]);
    const double cut = grow * std::max(ha, c.h[k]) + pairMu;
    const double dx = x0 - c.x[k], dy = x1 - c.y[k], dz = x2 - c.z[k];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const bool other = c.entry[k] != self;
    const bool listed = (r2 < cut * cut) & other;
    keep[k] = listed;
    nearMiss |= !listed & other & (r2 < (cut + pairMu) * (cut + pairMu));
  }
  return nearMiss != 0;
}

// Derived constants of a material's strength and porosity model.
struct Rheology {
  enum Kind { Fluid, VonMises, DruckerPrager } kind = Fluid;
  double G = 0.0;
  double yield = 0.0;           // von Mises: uniaxial yield stress Y0 (√(3 J2) ≤ Y0)
  double dpK = 0.0, dpB3 = 0.0; // Drucker–Prager: √J2 ≤ k + 3B p
  double alpha0 = 1.0, pe = 0.0, ps = 1.0;
  explicit Rheology(const Material& m) {
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
  // α on the quadratic crush curve at bulk pressure p.
  double crushAlpha(double p) const {
    if (p <= pe)
      return alpha0;
    if (p >= ps)
      return 1.0;
    const double t = (ps - p) / (ps - pe);
    return 1.0 + (alpha0 - 1.0) * t * t;
  }
};

double dot6(const double* a,
            const double* b) { // A:B for symmetric tensors stored xx yy zz xy xz yz
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

} // namespace

SphSolver::SphSolver(const SphState& initial, const SphParams& params) : s_(initial), par_(params) {
  par_.validate();
  for (std::size_t m = 0; m < par_.materials.size(); ++m) {
    Material& mat = par_.materials[m];
    try {
      mat.eos.validate();
    } catch (const InputError& e) {
      throw InputError("SPH: material '" + mat.name + "': " + e.what());
    }
    if (mat.strength != Material::Strength::None && !(mat.shearModulus > 0.0))
      throw InputError("SPH: material '" + mat.name + "' has strength but no shear modulus");
    if (!(mat.crushPs > mat.crushPe) || !(mat.distention >= 1.0))
      throw InputError("SPH: material '" + mat.name + "' has a bad porosity model");
    double rho0 = 0.0;
    if (mat.eos.model == EquationOfState::Model::Tillotson)
      rho0 = mat.eos.tillotson.rho0;
    else if (mat.eos.model == EquationOfState::Model::Murnaghan)
      rho0 = mat.eos.murnaghanRho0;
    else if (mat.eos.model == EquationOfState::Model::StiffenedGas)
      rho0 = mat.eos.stiffRho0;
    hCapFactor_.push_back(rho0 > 0.0 && par_.maxSmoothingGrowth > 0.0
                              ? par_.maxSmoothingGrowth * par_.kappa *
                                    std::cbrt(mat.distention / rho0)
                              : 0.0);
    const double g = par_.maxSmoothingGrowth;
    const double fraction = par_.densityFloor >= 0.0 ? par_.densityFloor
                            : g > 0.0                ? std::min(0.5, 1.0 / (g * g * g))
                                                     : 0.0;
    rhoFloor_.push_back(rho0 > 0.0 ? fraction * rho0 / mat.distention : 0.0);
  }
  const std::size_t n = s_.size();
  if (n == 0)
    throw InputError("SPH: no particles");
  if (n >= (std::size_t(1) << 27))
    throw InputError("SPH: more than 2^27 particles");
  if (s_.x.size() != 3 * n || s_.v.size() != 3 * n || s_.rho.size() != n || s_.u.size() != n ||
      s_.S.size() != 6 * n || s_.alpha.size() != n || s_.damage.size() != n ||
      s_.material.size() != n)
    throw InputError("SPH: the particle arrays differ in length");
  s_.h.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string which = "SPH: particle " + std::to_string(i);
    if (!(s_.mass[i] > 0.0) || !(s_.rho[i] > 0.0) || !(s_.u[i] >= 0.0) ||
        !std::isfinite(s_.mass[i]) || !std::isfinite(s_.rho[i]) || !std::isfinite(s_.u[i]))
      throw InputError(which + " has a non-positive mass or density or a negative energy");
    if (s_.material[i] < 0 || static_cast<std::size_t>(s_.material[i]) >= par_.materials.size())
      throw InputError(which + " has an unknown material index");
    if (!(s_.alpha[i] >= 1.0) || !std::isfinite(s_.alpha[i]))
      throw InputError(which + " has a distention below 1");
    if (!(s_.damage[i] >= 0.0 && s_.damage[i] <= 1.0))
      throw InputError(which + " has a damage outside [0, 1]");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(s_.x[3 * i + k]) || !std::isfinite(s_.v[3 * i + k]))
        throw InputError(which + " has a non-finite position or velocity");
    if (par_.materials[static_cast<std::size_t>(s_.material[i])].rigid &&
        (s_.v[3 * i] != 0.0 || s_.v[3 * i + 1] != 0.0 || s_.v[3 * i + 2] != 0.0))
      throw InputError(which + " belongs to a rigid boundary but is moving");
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(s_.S[6 * i + k]))
        throw InputError(which + " has a non-finite stress");
  }
  for (std::size_t i = 0; i < n; ++i)
    s_.h[i] = smoothingLength(s_, i);
  assignFlaws();
  buildNeighbours(s_, 0.0, false);
  settle(s_, p_, c_);
  const double signal = computeRates(s_, p_, c_, k1_);
  stableStep_ = limitStep(s_, k1_, signal);
}

void SphSolver::imageShift(std::uint32_t code, double d[3]) const {
  const int sh[3] = {static_cast<int>(code % 3) - 1, static_cast<int>(code / 3 % 3) - 1,
                     static_cast<int>(code / 9) - 1};
  for (int k = 0; k < 3; ++k)
    d[k] = sh[k] * (par_.boxHi[k] - par_.boxLo[k]);
}

void SphSolver::assignFlaws() {
  // Benz & Asphaug (1995): N ln N flaws for the N particles of a brittle material, flaw j
  // activating at ε_j = (j / (k V))^{1/m} (V the material's volume), each given to a random
  // particle; a particle left without one gets the next. Thresholds are ascending per particle.
  const std::size_t n = s_.size();
  std::vector<std::vector<double>> flaws(n);
  Random rng(par_.fractureSeed);
  for (std::size_t m = 0; m < par_.materials.size(); ++m) {
    const Material& mat = par_.materials[m];
    if (!(mat.weibullK > 0.0))
      continue;
    std::vector<std::size_t> members;
    double volume = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (static_cast<std::size_t>(s_.material[i]) == m)
        members.push_back(i), volume += s_.mass[i] / s_.rho[i];
    if (members.empty())
      continue;
    const double count = static_cast<double>(members.size());
    const std::size_t total = static_cast<std::size_t>(std::max(count, count * std::log(count)));
    std::size_t j = 1;
    auto threshold = [&](std::size_t jj) {
      return std::pow(static_cast<double>(jj) / (mat.weibullK * volume), 1.0 / mat.weibullM);
    };
    for (; j <= total; ++j)
      flaws[members[std::min(members.size() - 1, static_cast<std::size_t>(rng.uniform() * count))]]
          .push_back(threshold(j));
    for (std::size_t i : members)
      if (flaws[i].empty())
        flaws[i].push_back(threshold(j++));
  }
  flawStart_.assign(n + 1, 0);
  flawEps_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    flawEps_.insert(flawEps_.end(), flaws[i].begin(), flaws[i].end());
    flawStart_[i + 1] = static_cast<std::uint32_t>(flawEps_.size());
  }
}

void SphSolver::integrateDamage(SphState& s, const SphState& from, double dt, const Rates& a,
                                const Rates* b) const {
  if (a.dDc.empty())
    return;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double rate = b ? 0.5 * (a.dDc[i] + b->dDc[i]) : a.dDc[i];
    if (rate <= 0.0)
      continue;
    const double cap = b ? std::max(a.capD[i], b->capD[i]) : a.capD[i];
    const double c = std::cbrt(from.damage[i]) + dt * rate;
    s.damage[i] = std::max(from.damage[i], std::min({c * c * c, cap, 1.0})); // damage never heals
  }
}

bool SphSolver::neighboursValid(const SphState& s, double dt) const {
  // Valid while no pair can have come within its listing range without being listed. A pair
  // closes in by at most the sum of its two particles' displacements D (since the build, plus
  // 1.5 dt |v| for the motion still to come in this step). An unlisted pair had at least the
  // larger of its two margins to spare; but a particle with a clearance C (no unlisted
  // particle within twice the margin at the build: ejecta in flight, alone or in small clumps)
  // had C to spare against everybody and needs only D + D_max < C. Such particles are left out
  // of the pairs' check, so that a few fast fragments do not force a new list for all. And no
  // h has grown past the allowance.
  const std::size_t n = s.size();
  if (nb_.x.size() != s.x.size() || par_.rebuildEveryStep)
    return false;
  const bool xs = !k1_.dx.empty();
  std::vector<double>& D = nbMoved_;
  D.assign(n, 0.0);
  double dAll = 0.0;
  bool hOk = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (nb_.out[i]) {
      if (!outside(s, i))
        return false; // back in the domain: it needs neighbours
      continue;
    }
    double moved2 = 0.0, v2 = 0.0, a2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = s.x[3 * i + k] - nb_.x[3 * i + k];
      // A particle wrapped through a periodic face since the build: its listed pairs carry
      // the image codes of the old side.
      if (par_.periodic[k] && std::abs(d) > 0.5 * (par_.boxHi[k] - par_.boxLo[k]))
        return false;
      moved2 += d * d;
      const double w = s.v[3 * i + k] + (xs ? k1_.dx[3 * i + k] : 0.0);
      v2 += w * w;
      if (k1_.dv.size() == s.v.size())
        a2 += k1_.dv[3 * i + k] * k1_.dv[3 * i + k];
    }
    // Motion still to come in the step: speed, with a margin, and what the acceleration adds.
    D[i] = std::sqrt(moved2) + 1.5 * dt * std::sqrt(v2) + dt * dt * std::sqrt(a2);
    dAll = std::max(dAll, D[i]);
    hOk = hOk && s.h[i] <= 0.98 * nb_.grow * nb_.h[i]; // room for the growth within this step
  }
  if (!hOk)
    return false;
  // A pair (a, b) is safe while D_a + D_b stays below the larger of their margins: so if both
  // have moved less than half their own. Those that have not are checked against every level
  // of h (its two largest D and smallest margin): against the largest D but their own. With
  // one margin for all this is "the two largest D below the margin".
  const std::size_t L = nb_.levels;
  std::array<double, kMaxLevels> d1{}, d2{}, muMin;
  std::array<std::size_t, kMaxLevels> top;
  muMin.fill(INFINITY);
  top.fill(n);
  auto excluded = [&](std::size_t i) { return nb_.out[i] || D[i] + dAll < nb_.clearance[i]; };
  for (std::size_t i = 0; i < n; ++i) {
    if (excluded(i))
      continue;
    const std::size_t l = nb_.level[i];
    if (D[i] > d1[l]) {
      d2[l] = d1[l], d1[l] = D[i], top[l] = i;
    } else if (D[i] > d2[l]) {
      d2[l] = D[i];
    }
    muMin[l] = std::min(muMin[l], nb_.margin[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (excluded(i) || D[i] < 0.5 * nb_.margin[i])
      continue;
    for (std::size_t l = 0; l < L; ++l)
      if (muMin[l] < INFINITY &&
          D[i] + (top[l] == i ? d2[l] : d1[l]) >= std::max(nb_.margin[i], muMin[l]))
        return false;
  }
  return true;
}

void SphSolver::buildNeighbours(const SphState& s, double dt, bool margins) {
  const std::size_t n = s.size();
  nb_.out.assign(n, 0);
  nb_.margin.assign(n, 0.0);
  double hmax = 0.0, hmin = INFINITY, muMax = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    nb_.out[i] = outside(s, i);
    if (!nb_.out[i]) {
      hmax = std::max(hmax, s.h[i]);
      hmin = std::min(hmin, s.h[i]);
      // Each particle's own: skin h, or for a fast one 16 steps of its motion (at most h/2), so
      // that its list lasts about 6 steps. In a graded target a coarse particle's list then
      // lasts as long as a fine one's, and a few fast ones do not force new lists for all.
      // (One margin for all, set by the finest h and the fastest particle, made every list of
      // a late-stage graded run last a step.)
      if (margins) {
        double w2 = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double w = s.v[3 * i + k] + (k1_.dx.size() == s.v.size() ? k1_.dx[3 * i + k] : 0.0);
          w2 += w * w;
        }
        nb_.margin[i] =
            std::max(par_.skin * s.h[i], std::min(16.0 * dt * std::sqrt(w2), 0.5 * s.h[i]));
      }
      muMax = std::max(muMax, nb_.margin[i]);
    }
  }
  const std::vector<double>& mu = nb_.margin;
  const double grow = 1.05; // h may grow this much before the list misses a pair
  const double reach = grow * hmax + muMax;
  nb_.x = s.x;
  nb_.h = s.h;
  nb_.grow = grow;
  std::vector<double> pos;
  std::vector<std::uint32_t> id;
  pos.reserve(3 * n);
  id.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!nb_.out[i]) {
      pos.insert(pos.end(), &s.x[3 * i], &s.x[3 * i] + 3);
      id.push_back(static_cast<std::uint32_t>(i * 32 + kNoShift));
    }
  for (int sx = -1; sx <= 1; ++sx)
    for (int sy = -1; sy <= 1; ++sy)
      for (int sz = -1; sz <= 1; ++sz) {
        const int shift[3] = {sx, sy, sz};
        bool ok = sx || sy || sz;
        for (int k = 0; k < 3 && ok; ++k)
          ok = shift[k] == 0 || par_.periodic[k];
        if (!ok)
          continue;
        const std::uint32_t code =
            static_cast<std::uint32_t>((sx + 1) + 3 * (sy + 1) + 9 * (sz + 1));
        for (std::size_t i = 0; i < n; ++i) {
          if (nb_.out[i])
            continue;
          double y[3];
          bool near = true;
          for (int k = 0; k < 3 && near; ++k) {
            y[k] = s.x[3 * i + k] + shift[k] * (par_.boxHi[k] - par_.boxLo[k]);
            near = !par_.periodic[k] ||
                   (y[k] >= par_.boxLo[k] - reach && y[k] <= par_.boxHi[k] + reach);
          }
          if (!near)
            continue;
          pos.insert(pos.end(), y, y + 3);
          id.push_back(static_cast<std::uint32_t>(i * 32 + code));
        }
      }
  // Levels of smoothing length, a factor of √2 apart (level 0 holds the largest h). With one
  // grid sized by the largest h, a graded target (h ten times larger at its edge than at the
  // impact point) or a spray of expanded ejecta would make every fine particle scan a thousand
  // times its own neighbourhood. Each level has its own grid; a particle scans its own level
  // and the coarser ones (cells sized for them, so a few per axis), and the pairs with finer
  // particles reach it from their side: the finer partner lists the pair and hands it over.
  // The pairs are those of one grid: r below grow max(h_a, h_b) plus the larger margin.
  int levels = 1;
  if (hmax > std::sqrt(2.0) * hmin)
    levels = std::min(kMaxLevels, 1 + static_cast<int>(std::floor(2.0 * std::log2(hmax / hmin))));
  auto levelOf = [&](double h) {
    return levels == 1
               ? 0
               : std::clamp(static_cast<int>(std::floor(2.0 * std::log2(hmax / h))), 0, levels - 1);
  };
  nb_.levels = static_cast<std::size_t>(levels);
  nb_.level.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    nb_.level[i] = static_cast<std::uint8_t>(levelOf(s.h[i]));
  const std::size_t m = id.size();
  std::vector<std::uint8_t> level(m);
  std::vector<double> levelH(static_cast<std::size_t>(levels), 0.0);  // largest h of each level
  std::vector<double> levelMu(static_cast<std::size_t>(levels), 0.0); // and largest margin
  std::vector<std::size_t> levelSize(static_cast<std::size_t>(levels) + 1, 0);
  for (std::size_t q = 0; q < m; ++q) {
    const double h = s.h[id[q] / 32];
    const int l = nb_.level[id[q] / 32];
    level[q] = static_cast<std::uint8_t>(l);
    levelH[static_cast<std::size_t>(l)] = std::max(levelH[static_cast<std::size_t>(l)], h);
    levelMu[static_cast<std::size_t>(l)] =
        std::max(levelMu[static_cast<std::size_t>(l)], mu[id[q] / 32]);
    ++levelSize[static_cast<std::size_t>(l) + 1];
  }
  // Sparse grids: cells of half the level's reach, keyed (z, y, x) in 64 bits and sorted, so
  // memory and cost do not depend on how far ejecta have flown (a dense grid over a spray
  // kilometres wide would have to coarsen its cells for everyone). Candidate positions are
  // copied in (level, cell) order, so a scan reads memory sequentially.
  std::vector<double> cellSize(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l)
    cellSize[static_cast<std::size_t>(l)] =
        0.5 * (grow * levelH[static_cast<std::size_t>(l)] + levelMu[static_cast<std::size_t>(l)]);
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  for (std::size_t q = 0; q < m; ++q)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(pos[3 * q + k]))
        throw std::runtime_error("SPH: particle " + std::to_string(id[q] / 32) +
                                 " has a non-finite position");
      lo[k] = std::min(lo[k], pos[3 * q + k]);
    }
  constexpr std::int64_t kAxis = (std::int64_t(1) << 21) - 1;
  auto coord = [&](double v, int k, int l) {
    return static_cast<std::int64_t>(
        std::clamp(std::floor((v - lo[k]) / cellSize[static_cast<std::size_t>(l)]), 0.0,
                   static_cast<double>(kAxis)));
  };
  auto key = [](std::int64_t cx, std::int64_t cy, std::int64_t cz) {
    return (cz << 42) | (cy << 21) | cx;
  };
  for (int l = 0; l < levels; ++l)
    levelSize[static_cast<std::size_t>(l) + 1] += levelSize[static_cast<std::size_t>(l)];
  std::vector<std::pair<std::int64_t, std::uint32_t>> order(m);
  {
    std::vector<std::size_t> at(levelSize.begin(), levelSize.end() - 1);
    for (std::size_t q = 0; q < m; ++q) {
      const int l = level[q];
      order[at[static_cast<std::size_t>(l)]++] = {
          key(coord(pos[3 * q], 0, l), coord(pos[3 * q + 1], 1, l), coord(pos[3 * q + 2], 2, l)),
          static_cast<std::uint32_t>(q)};
    }
  }
  for (int l = 0; l < levels; ++l)
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(levelSize[static_cast<std::size_t>(l)]),
              order.begin() +
                  static_cast<std::ptrdiff_t>(levelSize[static_cast<std::size_t>(l) + 1]));
  std::vector<double> spx(m), spy(m), spz(m), sh(m),
      smu(m); // positions, h and margins in (level, cell) order
  std::vector<std::uint32_t> sid(m);
  std::vector<std::int64_t> cellKey;    // distinct cells, ascending per level
  std::vector<std::uint32_t> cellStart; // their first entry in the sorted arrays, plus the end
  std::vector<std::size_t> levelCells(static_cast<std::size_t>(levels) + 1,
                                      0); // each level's range in cellKey
  for (int l = 0; l < levels; ++l) {
    for (std::size_t r = levelSize[static_cast<std::size_t>(l)];
         r < levelSize[static_cast<std::size_t>(l) + 1]; ++r) {
      const std::uint32_t q = order[r].second;
      spx[r] = pos[3 * q], spy[r] = pos[3 * q + 1], spz[r] = pos[3 * q + 2];
      sid[r] = id[q];
      sh[r] = s.h[id[q] / 32];
      smu[r] = mu[id[q] / 32];
      if (r == levelSize[static_cast<std::size_t>(l)] || order[r].first != order[r - 1].first) {
        cellKey.push_back(order[r].first);
        cellStart.push_back(static_cast<std::uint32_t>(r));
      }
    }
    levelCells[static_cast<std::size_t>(l) + 1] = cellKey.size();
  }
  cellStart.push_back(static_cast<std::uint32_t>(m));
  // Calls f(begin, end) for the sorted entries of level l in the cells within R of x.
  auto empty = [&](int l) {
    return levelSize[static_cast<std::size_t>(l)] == levelSize[static_cast<std::size_t>(l) + 1];
  };
  auto forCells = [&](const double* x, double R, int l, auto&& f) {
    if (empty(l))
      return;
    std::int64_t c0[3], c1[3];
    for (int k = 0; k < 3; ++k) {
      c0[k] = coord(x[k] - R, k, l);
      c1[k] = coord(x[k] + R, k, l);
    }
    const auto first =
        cellKey.begin() + static_cast<std::ptrdiff_t>(levelCells[static_cast<std::size_t>(l)]);
    const auto end =
        cellKey.begin() + static_cast<std::ptrdiff_t>(levelCells[static_cast<std::size_t>(l) + 1]);
    for (std::int64_t cz = c0[2]; cz <= c1[2]; ++cz)
      for (std::int64_t cy = c0[1]; cy <= c1[1]; ++cy) {
        // The row's cells are contiguous in key order: one search for its first.
        auto it = std::lower_bound(first, end, key(c0[0], cy, cz));
        const std::int64_t last = key(c1[0], cy, cz);
        auto stop = it;
        while (stop != end && *stop <= last)
          ++stop;
        if (stop != it)
          f(cellStart[static_cast<std::size_t>(it - cellKey.begin())],
            cellStart[static_cast<std::size_t>(stop - cellKey.begin())]);
      }
  };
  struct Handed {
    std::uint32_t to, entry;
  };
  std::vector<std::vector<std::uint8_t>> keepOf(
      static_cast<std::size_t>(omp_get_max_threads())); // per thread: which candidates are listed
  // Lists a's neighbours in its own and the coarser levels (the pairs with coarser ones also
  // into `handed`, as entries of the partner's list); true if an unlisted particle came within
  // twice the margin.
  auto visit = [&](std::size_t a, std::vector<std::uint32_t>& out, std::vector<Handed>& handed) {
    bool nearMiss = false;
    const double* xa = &s.x[3 * a];
    const double ha = s.h[a], ma = mu[a];
    const int la = nb_.level[a];
    const std::uint32_t self = static_cast<std::uint32_t>(a * 32 + kNoShift);
    for (int l = 0; l <= la; ++l) {
      const double R = grow * std::max(ha, levelH[static_cast<std::size_t>(l)]) +
                       std::max(ma, levelMu[static_cast<std::size_t>(l)]);
      forCells(xa, R, l, [&](std::uint32_t begin, std::uint32_t end) {
        // The candidates' tests in one vector pass, then the list advances past those in
        // range (branch-free: every candidate is written).
        const std::uint32_t count = end - begin;
        std::vector<std::uint8_t>& keep = keepOf[omp_get_thread_num()];
        if (keep.size() < count)
          keep.resize(count);
        const CandidateRange cr{spx.data() + begin,
                                spy.data() + begin,
                                spz.data() + begin,
                                sh.data() + begin,
                                smu.data() + begin,
                                sid.data() + begin,
                                count};
        nearMiss |= listCandidates(cr, xa, ha, ma, grow, self, keep.data());
        std::size_t at = out.size();
        out.resize(at + count);
        std::uint32_t* o = out.data();
        for (std::uint32_t k = 0; k < count; ++k) {
          o[at] = sid[begin + k];
          at += keep[k];
        }
        out.resize(at);
        if (l < la) // b's image at the opposite shift is near a
          for (std::uint32_t k = 0; k < count; ++k)
            if (keep[k]) {
              const std::uint32_t e = sid[begin + k];
              handed.push_back({e / 32, static_cast<std::uint32_t>(a * 32 + (26 - e % 32))});
            }
      });
    }
    return nearMiss;
  };
  // A particle with no unlisted particle within twice the margin gets its clearance: how far
  // the nearest unlisted particle is beyond the pair's listing range without the margin. Each
  // level is searched to twice its reach from a (the finer ones to three margins beyond a's
  // own range, unless that spans too many of their cells); anybody farther has at least that
  // search radius minus the level's largest range to spare.
  const double far = 4.0 * reach;
  auto clearanceOf = [&](std::size_t a) {
    const double* xa = &s.x[3 * a];
    for (int k = 0; k < 3; ++k) // periodic images are listed only within one reach of the box
      if (par_.periodic[k] && (xa[k] < par_.boxLo[k] + far || xa[k] > par_.boxHi[k] - far))
        return 0.0;
    const double ha = s.h[a], ma = mu[a];
    const int la = nb_.level[a];
    double spare = INFINITY;
    for (int l = 0; l < levels; ++l) {
      if (empty(l))
        continue;
      const double range = grow * std::max(ha, levelH[static_cast<std::size_t>(l)]);
      const double ml = std::max(ma, levelMu[static_cast<std::size_t>(l)]);
      const double R = l <= la ? 2.0 * (range + ml) : range + 3.0 * ml;
      if (R >
          8.0 * cellSize[static_cast<std::size_t>(l)]) { // a level far finer than a: too many cells
        spare = std::min(spare, ma); // to search; every unlisted pair has a's margin
        continue;
      }
      spare = std::min(spare, R - range);
      forCells(xa, R, l, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t r = begin; r < end; ++r) {
          const std::uint32_t e = sid[r];
          if (e / 32 == a && e % 32 == kNoShift)
            continue;
          const double d =
              std::sqrt((xa[0] - spx[r]) * (xa[0] - spx[r]) + (xa[1] - spy[r]) * (xa[1] - spy[r]) +
                        (xa[2] - spz[r]) * (xa[2] - spz[r]));
          const double pairRange = grow * std::max(ha, sh[r]);
          if (d >= pairRange + std::max(ma, smu[r])) // listed ones are not spare
            spare = std::min(spare, d - pairRange);
        }
      });
    }
    return std::max(spare, ma); // unlisted: at least a's margin
  };
  // One pass: each thread lists a contiguous block of particles into its own buffer (in the
  // grids' order, the same for any thread count), then the blocks are copied into place and
  // the pairs handed over from finer particles are appended to their partners' lists, in the
  // order of the finer particles (again the same for any thread count).
  ++builds_;
  nb_.start.assign(n + 1, 0);
  nb_.clearance.assign(n, 0.0);
  const int threads = n >= 1024 ? omp_get_max_threads() : 1;
  std::vector<std::vector<std::uint32_t>> buffers(static_cast<std::size_t>(threads));
  std::vector<std::vector<Handed>> handedBy(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num()),
                      nt = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t a0 = n * t / nt, a1 = n * (t + 1) / nt;
    std::vector<std::uint32_t>& out = buffers[t];
    std::vector<Handed>& handed = handedBy[t];
    out.clear();
    handed.clear();
    for (std::size_t a = a0; a < a1; ++a) {
      const std::size_t before = out.size();
      if (!nb_.out[a]) {
        if (!visit(a, out, handed) && margins) // with no margin the list is rebuilt at once anyway
          nb_.clearance[a] = clearanceOf(a);
      }
      nb_.start[a + 1] = static_cast<std::uint32_t>(out.size() - before);
    }
  }
  std::size_t total = 0;
  for (const auto& b : buffers)
    total += b.size();
  for (const auto& h : handedBy)
    total += h.size();
  if (total > 0xF0000000u)
    throw std::runtime_error(
        "SPH: too many neighbour pairs (the smoothing lengths have grown too large)");
  std::vector<std::uint32_t> own(nb_.start.begin() + 1, nb_.start.end());
  for (const auto& h : handedBy)
    for (const Handed& p : h)
      ++nb_.start[p.to + 1];
  for (std::size_t a = 0; a < n; ++a)
    nb_.start[a + 1] += nb_.start[a];
  nb_.entry.resize(total);
  // Own entries: the buffers, read in thread order, hold them in ascending a. Then `own`
  // counts on as each list's fill.
  std::size_t bi = 0, k = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (own[a] == 0)
      continue;
    while (k == buffers[bi].size())
      ++bi, k = 0;
    std::copy(buffers[bi].begin() + static_cast<std::ptrdiff_t>(k),
              buffers[bi].begin() + static_cast<std::ptrdiff_t>(k + own[a]),
              nb_.entry.begin() + static_cast<std::ptrdiff_t>(nb_.start[a]));
    k += own[a];
  }
  for (const auto& h : handedBy)
    for (const Handed& p : h)
      nb_.entry[nb_.start[p.to] + own[p.to]++] = p.entry;
}

std::vector<std::uint32_t> SphSolver::neighboursOf(std::size_t a) const {
  std::vector<std::uint32_t> list(nb_.entry.begin() + nb_.start[a],
                                  nb_.entry.begin() + nb_.start[a + 1]);
  std::sort(list.begin(), list.end());
  return list;
}

void SphSolver::settle(SphState& s, std::vector<double>& p, std::vector<double>& c) const {
  const std::size_t n = s.size();
  for (int k = 0; k < 3; ++k) {
    if (!par_.periodic[k])
      continue;
    const double lo = par_.boxLo[k], L = par_.boxHi[k] - lo;
    for (std::size_t i = 0; i < n; ++i) {
      double& x = s.x[3 * i + k];
      x = lo + (x - lo) - L * std::floor((x - lo) / L);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    s.h[i] = smoothingLength(s, i);
  if (par_.summationDensity)
    densityBySummation(s);
  eosAndYield(s, p, c);
}

void SphSolver::eosAndYield(SphState& s, std::vector<double>& p, std::vector<double>& c) const {
  const std::size_t n = s.size();
  p.resize(n);
  c.resize(n);
  std::vector<Rheology> rh;
  for (const Material& m : par_.materials)
    rh.emplace_back(m);
#pragma omp parallel for schedule(static) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    const Material& mat = par_.materials[static_cast<std::size_t>(s.material[i])];
    const Rheology& r = rh[static_cast<std::size_t>(s.material[i])];
    const double rho = s.rho[i], u = s.u[i];
    double& a = s.alpha[i];
    auto bulkPressure = [&](double al) { return mat.eos.pressure(al * rho, u) / al; };
    double P = bulkPressure(a);
    if (!late_ && a > 1.0 && a > r.crushAlpha(P)) {
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
      P = bulkPressure(a);
    }
    const double D = s.damage[i];
    if (P < 0.0)
      P *= 1.0 - D;
    double* S = &s.S[6 * i];
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
    p[i] = P;
    // Solids carry shear waves too: the signal speed is the longitudinal one, c² = c_s² + 4G/(3ρ),
    // or the time step is too long for a stiff solid (and much too long for a porous one).
    const double cs = mat.eos.soundSpeed(a * rho, u);
    c[i] = r.kind == Rheology::Fluid ? cs : std::sqrt(cs * cs + 4.0 * r.G / (3.0 * rho));
  }
}

template <class K> void SphSolver::summation(SphState& s) const {
  const std::size_t n = s.size();
  std::vector<double> rho(n);
#pragma omp parallel for schedule(dynamic, 256) if (n >= 512)
  for (std::size_t a = 0; a < n; ++a) {
    const double* xa = &s.x[3 * a];
    double sum = s.mass[a] * K::W(0.0, s.h[a]);
    for (std::uint32_t e = nb_.start[a]; e < nb_.start[a + 1]; ++e) {
      const std::uint32_t code = nb_.entry[e];
      const std::size_t b = code / 32;
      double d[3] = {0, 0, 0};
      if (code % 32 != kNoShift)
        imageShift(code % 32, d);
      const double* xb = &s.x[3 * b];
      const double rx = xa[0] - xb[0] - d[0], ry = xa[1] - xb[1] - d[1], rz = xa[2] - xb[2] - d[2];
      const double hb = 0.5 * (s.h[a] + s.h[b]);
      const double r2 = rx * rx + ry * ry + rz * rz;
      if (r2 < hb * hb)
        sum += s.mass[b] * K::W(std::sqrt(r2), hb);
    }
    rho[a] = sum;
  }
  s.rho.swap(rho);
}

void SphSolver::densityBySummation(SphState& s) const {
  if (par_.kernel == SphParams::Kernel::WendlandC2)
    summation<WendlandC2>(s);
  else
    summation<CubicSpline>(s);
  for (std::size_t i = 0; i < s.size(); ++i)
    s.h[i] = smoothingLength(s, i);
}

bool SphSolver::outside(const SphState& s, std::size_t i) const {
  if (par_.domainRadius <= 0.0)
    return false;
  const double* x = &s.x[3 * i];
  const double dx = x[0] - par_.domainCentre[0], dy = x[1] - par_.domainCentre[1],
               dz = x[2] - par_.domainCentre[2];
  return dx * dx + dy * dy + dz * dz > par_.domainRadius * par_.domainRadius;
}

double SphSolver::smoothingLength(const SphState& s, std::size_t i) const {
  const double m3 = std::cbrt(s.mass[i]), h = par_.kappa * m3 / std::cbrt(s.rho[i]);
  const double f = hCapFactor_[static_cast<std::size_t>(s.material[i])];
  return f > 0.0 ? std::min(h, f * m3) : h;
}

namespace {
// What a particle's neighbours read of it, packed in one place (144 bytes) instead of eight
// scattered arrays.
struct Packed {
  double x[3], v[3];
  double h, rho, m, vol; // vol = m/ρ
  double pr;             // p/ρ²
  double c;
  double s[6]; // S/ρ²
};
// Per-thread buffers of one particle's interacting neighbours.
struct Scratch {
  std::vector<std::uint32_t> idx;
  std::vector<double> rx, ry, rz, r2;
  void resize(std::size_t n) {
    idx.resize(n), rx.resize(n), ry.resize(n), rz.resize(n), r2.resize(n);
  }
};

// What one particle's neighbours add up to (§2.2, §2.3).
struct PairSums {
  double acc[3], dr, de, grad[9], xs[3], sig;
};

struct PairConstants {
  double av, bv, xsph, stressOn, gradOn;
  bool periodic;
  double period[3]; // box lengths of the periodic axes
};

// The pair terms of particle A over its listed neighbours `entries` (index * 32 + image
// code). Cloned for x86-64-v4 (AVX-512), chosen at run time where the processor has it: its 32
// vector registers hold the loop's 17 sums and temporaries, so the pair loop runs eight pairs
// wide (27 % less time for the SCI-like run here; AVX2, with 16 registers, spills and gains
// nothing). Elsewhere the generic code runs. The two differ only by rounding.
template <class K, bool Xsph>
CK_SIMD_CLONES PairSums pairSums(const Packed* Pp, const Packed& A, const std::uint32_t* entries,
                                 std::uint32_t count, Scratch& w, const PairConstants& pc) {
  // Pass 1: the listed neighbours inside the pair's support, with their separations.
  if (w.idx.size() < count)
    w.resize(count);
  std::size_t m = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t code = entries[k];
    const Packed& B = Pp[code >> 5];
    double rx = A.x[0] - B.x[0], ry = A.x[1] - B.x[1], rz = A.x[2] - B.x[2];
    if (pc.periodic && (code & 31u) != kNoShift) {
      const std::uint32_t c = code & 31u;
      rx -= (static_cast<int>(c % 3) - 1) * pc.period[0];
      ry -= (static_cast<int>(c / 3 % 3) - 1) * pc.period[1];
      rz -= (static_cast<int>(c / 9) - 1) * pc.period[2];
    }
    const double r2 = rx * rx + ry * ry + rz * rz;
    const double hb = 0.5 * (A.h + B.h);
    // Written always, kept only inside the support: no branch to mispredict (about a third
    // of the listed pairs are in the list's margin).
    w.idx[m] = code >> 5;
    w.rx[m] = rx, w.ry[m] = ry, w.rz[m] = rz, w.r2[m] = r2;
    m += (r2 < hb * hb) & (r2 != 0.0);
  }
  // Pass 2: the pair terms, branch-free so that the compiler vectorises the loop.
  double acc0 = 0, acc1 = 0, acc2 = 0, dr = 0, de = 0, sig = 0;
  double g0 = 0, g1 = 0, g2 = 0, g3 = 0, g4 = 0, g5 = 0, g6 = 0, g7 = 0, g8 = 0, xs0 = 0, xs1 = 0,
         xs2 = 0;
  const std::uint32_t* idx = w.idx.data();
  const double *RX = w.rx.data(), *RY = w.ry.data(), *RZ = w.rz.data(), *R2 = w.r2.data();
  const double* sa = A.s;
  const double sa0 = sa[0], sa1 = sa[1], sa2 = sa[2], sa3 = sa[3], sa4 = sa[4], sa5 = sa[5];
  const double av = pc.av, bv = pc.bv, xsph = pc.xsph, stressOn = pc.stressOn, gradOn = pc.gradOn;
#pragma omp simd reduction(+ : acc0, acc1, acc2, dr, de, g0, g1, g2, g3, g4, g5, g6, g7, g8, xs0, xs1, xs2) reduction(max : sig)
  for (std::size_t k = 0; k < m; ++k) {
    const Packed& B = Pp[idx[k]];
    const double rx = RX[k], ry = RY[k], rz = RZ[k], r2 = R2[k];
    const double hb = 0.5 * (A.h + B.h), ih = 1.0 / hb;
    const double rr = std::sqrt(r2), rinv = 1.0 / rr;
    const double g = Branchless<K>::gradOverR(rr * ih, ih, hb * rinv); // ∇_a W = g r_ab
    const double vx = A.v[0] - B.v[0], vy = A.v[1] - B.v[1], vz = A.v[2] - B.v[2];
    const double vr = vx * rx + vy * ry + vz * rz;
    const double mu = hb * vr / (r2 + 0.01 * hb * hb); // h̄ = support, as miluphcuda
    const double piRaw = (-av * (A.c + B.c) * mu + 2.0 * bv * mu * mu) / (A.rho + B.rho);
    const double pi = vr < 0.0 ? piRaw : 0.0;
    const double sgn = vr < 0.0 ? A.c + B.c - 3.0 * vr * rinv : 0.0;
    sig = sig > sgn ? sig : sgn;
    const double mg = B.m * g;
    const double f = mg * (A.pr + B.pr + pi);
    // (S_a/ρ_a² + S_b/ρ_b²) · ∇_a W, and the stress power with the same pair terms so that
    // energy is conserved exactly: −Σ m_b (S_a/ρ_a²) : (v_ab ⊗ ∇_a W).
    const double t0 = sa0 + B.s[0], t1 = sa1 + B.s[1], t2 = sa2 + B.s[2];
    const double t3 = sa3 + B.s[3], t4 = sa4 + B.s[4], t5 = sa5 + B.s[5];
    const double ms = mg * stressOn;
    acc0 += -f * rx + ms * (t0 * rx + t3 * ry + t4 * rz);
    acc1 += -f * ry + ms * (t3 * rx + t1 * ry + t5 * rz);
    acc2 += -f * rz + ms * (t4 * rx + t5 * ry + t2 * rz);
    dr += mg * vr; // m_b v_ab · ∇_a W
    de += mg * (A.pr + 0.5 * pi) * vr -
          ms * (sa0 * vx * rx + sa1 * vy * ry + sa2 * vz * rz + sa3 * (vx * ry + vy * rx) +
                sa4 * (vx * rz + vz * rx) + sa5 * (vy * rz + vz * ry));
    const double wv = -B.vol * g * gradOn; // ∂_β v^α ≈ −Σ (m_b/ρ_b) v_ab^α ∂_β W
    const double wx = wv * vx, wy = wv * vy, wz = wv * vz;
    g0 += wx * rx, g1 += wx * ry, g2 += wx * rz;
    g3 += wy * rx, g4 += wy * ry, g5 += wy * rz;
    g6 += wz * rx, g7 += wz * ry, g8 += wz * rz;
    if constexpr (Xsph) {
      const double wx2 = xsph * B.m / (0.5 * (A.rho + B.rho)) * Branchless<K>::value(rr * ih, ih);
      xs0 -= wx2 * vx, xs1 -= wx2 * vy, xs2 -= wx2 * vz;
    }
  }
  return PairSums{{acc0, acc1, acc2}, dr, de, {g0, g1, g2, g3, g4, g5, g6, g7, g8},
                  {xs0, xs1, xs2},    sig};
}
} // namespace

template <class K, bool Xsph>
double SphSolver::rates(const SphState& s, const std::vector<double>& p,
                        const std::vector<double>& c, Rates& r) const {
  const std::size_t n = s.size();
  r.dx.assign(par_.xsph > 0.0 ? 3 * n : 0, 0.0);
  r.dv.resize(3 * n);
  r.drho.resize(n);
  r.du.resize(n);
  r.dS.resize(6 * n);
  const bool hasFlaws = !flawEps_.empty();
  r.dDc.assign(hasFlaws ? n : 0, 0.0);
  r.capD.assign(hasFlaws ? n : 0, 0.0);
  std::vector<double> G(par_.materials.size());
  for (std::size_t m = 0; m < G.size(); ++m)
    G[m] = par_.materials[m].strength == Material::Strength::None ? 0.0
                                                                  : par_.materials[m].shearModulus;
  std::vector<char> rigidMat(par_.materials.size());
  for (std::size_t m = 0; m < rigidMat.size(); ++m)
    rigidMat[m] = par_.materials[m].rigid;
  static thread_local std::vector<Packed>
      P; // reused: no allocation in the step loop; workers use Pp
  P.resize(n);
  Packed* const Pw = P.data();
  bool anyStress = false;
#pragma omp parallel for schedule(static) reduction(|| : anyStress) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) {
    Packed& q = Pw[i];
    const double ir2 = 1.0 / (s.rho[i] * s.rho[i]);
    for (int k = 0; k < 3; ++k)
      q.x[k] = s.x[3 * i + k], q.v[k] = s.v[3 * i + k];
    q.h = s.h[i], q.rho = s.rho[i], q.m = s.mass[i], q.vol = s.mass[i] / s.rho[i];
    q.pr = p[i] * ir2;
    q.c = c[i];
    for (int k = 0; k < 6; ++k) {
      q.s[k] = s.S[6 * i + k] * ir2;
      anyStress = anyStress || q.s[k] != 0.0;
    }
    anyStress = anyStress || G[static_cast<std::size_t>(s.material[i])] > 0.0;
  }
  const Packed* Pp = Pw;
  static thread_local std::vector<Scratch>
      scratchOfCaller; // the calling thread's; workers use the pointer
  scratchOfCaller.resize(static_cast<std::size_t>(omp_get_max_threads()));
  Scratch* const scratch = scratchOfCaller.data();
  PairConstants pc{par_.alpha,
                   par_.beta,
                   par_.xsph,
                   anyStress ? 1.0 : 0.0,
                   0.0,
                   par_.periodic[0] || par_.periodic[1] || par_.periodic[2],
                   {0.0, 0.0, 0.0}};
  for (int k = 0; k < 3; ++k)
    pc.period[k] = par_.periodic[k] ? par_.boxHi[k] - par_.boxLo[k] : 0.0;
  double maxSignal = 0.0;
  // Each particle accumulates only its own rates (pairs are visited from both sides), so the
  // loop needs no atomics and gives the same bits for any thread count.
#pragma omp parallel for schedule(dynamic, 256) reduction(max : maxSignal) if (n >= 512)
  for (std::size_t a = 0; a < n; ++a) {
    const Packed& A = Pp[a];
    const bool solid = G[static_cast<std::size_t>(s.material[a])] > 0.0;
    double signal = A.c;
    PairConstants pcA = pc;
    pcA.gradOn = solid ? 1.0 : 0.0;
    const std::uint32_t first = nb_.start[a];
    const PairSums sums =
        pairSums<K, Xsph>(Pp, A, nb_.entry.data() + first, nb_.start[a + 1] - first,
                          scratch[omp_get_thread_num()], pcA);
    const double* acc = sums.acc;
    const double* xs = sums.xs;
    const double* grad = sums.grad;
    signal = std::max(signal, sums.sig);
    const double* xa = A.x;
    const double* Sa = &s.S[6 * a];
    double ext[3] = {par_.gravity[0], par_.gravity[1], par_.gravity[2]};
    if (par_.pointMassGM > 0.0) {
      const double dx = xa[0] - par_.pointMassAt[0], dy = xa[1] - par_.pointMassAt[1],
                   dz = xa[2] - par_.pointMassAt[2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 > 0.0) {
        const double k = -par_.pointMassGM / (r2 * std::sqrt(r2));
        ext[0] += k * dx, ext[1] += k * dy, ext[2] += k * dz;
      }
    }
    const bool rigid = rigidMat[static_cast<std::size_t>(s.material[a])];
    for (int k = 0; k < 3; ++k)
      r.dv[3 * a + k] = rigid ? 0.0 : acc[k] + ext[k];
    if (par_.xsph > 0.0)
      for (int k = 0; k < 3; ++k)
        r.dx[3 * a + k] = rigid ? 0.0 : xs[k];
    r.drho[a] = sums.dr;
    r.du[a] = sums.de;
    double* dS = &r.dS[6 * a];
    if (solid) {
      const double Gm = G[static_cast<std::size_t>(s.material[a])];
      // Strain rate ε̇ = sym(∇v), rotation rate R^{αβ} = ½(∂_β v^α − ∂_α v^β).
      const double exx = grad[0], eyy = grad[4], ezz = grad[8];
      const double exy = 0.5 * (grad[1] + grad[3]), exz = 0.5 * (grad[2] + grad[6]),
                   eyz = 0.5 * (grad[5] + grad[7]);
      const double wxy = 0.5 * (grad[1] - grad[3]), wxz = 0.5 * (grad[2] - grad[6]),
                   wyz = 0.5 * (grad[5] - grad[7]);
      const double tr = (exx + eyy + ezz) / 3.0;
      // Full tensors for R S − S R (R antisymmetric, S symmetric: the result is symmetric).
      const double Sm[3][3] = {{Sa[0], Sa[3], Sa[4]}, {Sa[3], Sa[1], Sa[5]}, {Sa[4], Sa[5], Sa[2]}};
      const double R[3][3] = {{0.0, wxy, wxz}, {-wxy, 0.0, wyz}, {-wxz, -wyz, 0.0}};
      auto rot = [&](int i, int j) {
        double v = 0.0;
        for (int k = 0; k < 3; ++k)
          v += R[i][k] * Sm[k][j] - Sm[i][k] * R[k][j];
        return v;
      };
      dS[0] = 2.0 * Gm * (exx - tr) + rot(0, 0);
      dS[1] = 2.0 * Gm * (eyy - tr) + rot(1, 1);
      dS[2] = 2.0 * Gm * (ezz - tr) + rot(2, 2);
      dS[3] = 2.0 * Gm * exy + rot(0, 1);
      dS[4] = 2.0 * Gm * exz + rot(0, 2);
      dS[5] = 2.0 * Gm * eyz + rot(1, 2);
    } else {
      for (int k = 0; k < 6; ++k)
        dS[k] = 0.0;
    }
    if (hasFlaws && flawStart_[a + 1] > flawStart_[a]) {
      // Grady–Kipp: local strain from the largest principal (tensile) stress.
      const Material& mat = par_.materials[static_cast<std::size_t>(s.material[a])];
      Eigen::Matrix3d sigma;
      sigma << Sa[0] - p[a], Sa[3], Sa[4], Sa[3], Sa[1] - p[a], Sa[5], Sa[4], Sa[5], Sa[2] - p[a];
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
      eig.computeDirect(sigma, Eigen::EigenvaluesOnly);
      const double s1 = eig.eigenvalues()(2), D = s.damage[a];
      const double Kb = mat.bulkModulus, Gm = mat.shearModulus, E = 9.0 * Kb * Gm / (3.0 * Kb + Gm);
      double rate = 0.0, cap = 0.0;
      if (s1 > 0.0 && D < 1.0) {
        const double eps = s1 / ((1.0 - D) * E);
        const double* f0 = &flawEps_[flawStart_[a]];
        const double* f1 = &flawEps_[flawStart_[a + 1]];
        const std::size_t active = static_cast<std::size_t>(std::upper_bound(f0, f1, eps) - f0);
        if (active > 0) {
          const double cg = 0.4 * std::sqrt((Kb + 4.0 * Gm / 3.0) / s.rho[a]);
          const double Rs = std::cbrt(3.0 * s.mass[a] / (4.0 * M_PI * s.rho[a]));
          rate = static_cast<double>(active) * cg / Rs;
          cap = static_cast<double>(active) / static_cast<double>(f1 - f0);
        }
      }
      r.dDc[a] = rate;
      r.capD[a] = cap;
    }
    maxSignal = std::max(maxSignal, signal / (0.5 * s.h[a]));
  }
  return maxSignal;
}

double SphSolver::computeRates(const SphState& s, const std::vector<double>& p,
                               const std::vector<double>& c, Rates& r) const {
  if (par_.kernel == SphParams::Kernel::WendlandC2)
    return par_.xsph > 0.0 ? rates<WendlandC2, true>(s, p, c, r)
                           : rates<WendlandC2, false>(s, p, c, r);
  return par_.xsph > 0.0 ? rates<CubicSpline, true>(s, p, c, r)
                         : rates<CubicSpline, false>(s, p, c, r);
}

double SphSolver::limitStep(const SphState& s, const Rates& r, double maxSignal) const {
  double dt = maxSignal > 0.0 ? par_.courant / maxSignal : INFINITY;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double a2 = r.dv[3 * i] * r.dv[3 * i] + r.dv[3 * i + 1] * r.dv[3 * i + 1] +
                      r.dv[3 * i + 2] * r.dv[3 * i + 2];
    if (a2 > 0.0)
      dt = std::min(dt, par_.forceFactor * std::sqrt(s.h[i] / std::sqrt(a2)));
  }
  return dt;
}

void SphSolver::restore(double time, std::size_t steps, double nextStep) {
  time_ = time, steps_ = steps;
  if (!late_ && par_.lateStageTime >= 0.0 && time_ >= par_.lateStageTime)
    enterLateStage(false);
  if (nextStep > 0.0)
    stableStep_ = nextStep;
}

void SphSolver::enterLateStage(bool scaleStress) {
  const double c = par_.lateStageSoundSpeed;
  std::vector<double> scale(par_.materials.size(), 1.0);
  for (std::size_t m = 0; m < par_.materials.size(); ++m) {
    Material& mat = par_.materials[m];
    EquationOfState& eos = mat.eos;
    double rho0;
    if (eos.model == EquationOfState::Model::Tillotson)
      rho0 = eos.tillotson.rho0;
    else if (eos.model == EquationOfState::Model::Murnaghan)
      rho0 = eos.murnaghanRho0;
    else
      continue; // gases keep their law
    const double Kold = mat.bulkModulus > 0.0                            ? mat.bulkModulus
                        : eos.model == EquationOfState::Model::Tillotson ? eos.tillotson.A
                                                                         : eos.murnaghanK0;
    const double K = rho0 * c * c;
    eos.model = EquationOfState::Model::Murnaghan;
    eos.murnaghanRho0 = rho0;
    eos.murnaghanK0 = K;
    eos.murnaghanN = 1.0;
    eos.soundSpeedFloor = 0.01 * c;
    if (mat.shearModulus > 0.0) {
      const double G = mat.shearModulus, nu = (3.0 * Kold - 2.0 * G) / (2.0 * (3.0 * Kold + G));
      const double Gnew = 3.0 * K * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu));
      scale[m] = Gnew / G;
      mat.shearModulus = Gnew;
    }
    mat.bulkModulus = K;
  }
  if (scaleStress)
    for (std::size_t i = 0; i < s_.size(); ++i) {
      const double f = scale[static_cast<std::size_t>(s_.material[i])];
      for (int k = 0; k < 6; ++k)
        s_.S[6 * i + k] *= f;
    }
  late_ = true;
  settle(s_, p_, c_);
  const double signal = computeRates(s_, p_, c_, k1_);
  stableStep_ = limitStep(s_, k1_, signal);
}

double SphSolver::step(double dt) {
  if (dt <= 0.0)
    dt = stableStep_;
  if (!late_ && par_.lateStageTime >= 0.0 && time_ + dt > par_.lateStageTime) {
    if (par_.lateStageTime - time_ <= 1e-9 * dt) {
      enterLateStage(true);
      dt = std::min(dt, stableStep_);
    } else {
      dt = par_.lateStageTime - time_; // the switch happens at its time exactly
    }
  }
  const std::size_t n = s_.size();
  const bool xs = par_.xsph > 0.0;
  // The predictor's state and rates live in members, so a step allocates nothing.
  SphState& mid = mid_;
  Rates& k2 = k2_;
  std::vector<double>& pm = pm_;
  std::vector<double>& cm = cm_;
  double err = 0.0;
  std::size_t worst = 0;
  for (int attempt = 0;; ++attempt) {
    if (!(dt > 0.0) || !std::isfinite(dt) || dt < par_.minTimeStep || attempt > 60)
      throw std::runtime_error("SPH: the time step collapsed to " + std::to_string(dt) +
                               " s at t = " + std::to_string(time_) + " s near particle " +
                               std::to_string(worst) + " (x = " + std::to_string(s_.x[3 * worst]) +
                               ", " + std::to_string(s_.x[3 * worst + 1]) + ", " +
                               std::to_string(s_.x[3 * worst + 2]) + " m, material " +
                               std::to_string(s_.material[worst]) + ")");
    // Rebuild the list when this step's motion (dt |v|, plus what the velocity gains) could
    // bring an unlisted pair into range; the margin covers several steps.
    if (!neighboursValid(s_, dt))
      buildNeighbours(s_, dt);
    mid = s_;
    for (std::size_t i = 0; i < 3 * n; ++i) {
      mid.x[i] += dt * (s_.v[i] + (xs ? k1_.dx[i] : 0.0));
      mid.v[i] += dt * k1_.dv[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!par_.summationDensity)
        mid.rho[i] = std::max({floorOf(s_, i), 1e-6 * s_.rho[i], mid.rho[i] + dt * k1_.drho[i]});
      mid.u[i] = std::max(0.0, mid.u[i] + dt * k1_.du[i]);
    }
    for (std::size_t i = 0; i < 6 * n; ++i)
      mid.S[i] += dt * k1_.dS[i];
    integrateDamage(mid, s_, dt, k1_, nullptr);
    settle(mid, pm, cm);
    computeRates(mid, pm, cm, k2);
    // Error of the Euler predictor against Heun's step, relative to each particle's own
    // scales (speed: its signal speed; density; energy: its energy plus c²). Steps above the
    // tolerance are taken again, shorter (as miluphcuda's adaptive RK2 does).
    err = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
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
      const double e = std::max({ev, er, eu});
      if (e > err)
        err = e, worst = i;
    }
    if (err <= par_.errorTolerance)
      break;
    dt *= std::max(0.1, 0.9 * std::sqrt(par_.errorTolerance / err));
  }
  for (std::size_t i = 0; i < 3 * n; ++i) {
    s_.x[i] +=
        0.5 * dt * (s_.v[i] + mid.v[i] + (xs ? k1_.dx[i] + k2.dx[i] : 0.0)); // before v changes
    s_.v[i] += 0.5 * dt * (k1_.dv[i] + k2.dv[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!par_.summationDensity)
      s_.rho[i] = std::max(floorOf(s_, i), s_.rho[i] + 0.5 * dt * (k1_.drho[i] + k2.drho[i]));
    s_.u[i] = std::max(0.0, s_.u[i] + 0.5 * dt * (k1_.du[i] + k2.du[i]));
    s_.alpha[i] = mid.alpha[i]; // compaction is kept from the predictor and can go on below
    if (!(s_.rho[i] > 0.0) || !std::isfinite(s_.rho[i]) || !std::isfinite(s_.u[i]))
      throw std::runtime_error("SPH: particle " + std::to_string(i) +
                               " has a non-positive or non-finite density or energy at t = " +
                               std::to_string(time_ + dt) + " s");
  }
  for (std::size_t i = 0; i < 6 * n; ++i)
    s_.S[i] += 0.5 * dt * (k1_.dS[i] + k2.dS[i]);
  integrateDamage(s_, s_, dt, k1_,
                  &k2); // reads each particle's start-of-step damage before writing it
  settle(s_, p_, c_);
  const double signal = computeRates(s_, p_, c_, k1_);
  const double grow = err > 0.0 ? std::min(2.0, 0.9 * std::sqrt(par_.errorTolerance / err)) : 2.0;
  stableStep_ = std::min(limitStep(s_, k1_, signal), dt * std::max(grow, 1.0));
  time_ += dt;
  ++steps_;
  return dt;
}

void SphSolver::advanceTo(double t) {
  while (time_ < t) {
    const double dt = std::min(stableStep_, t - time_);
    step(dt);
  }
}

double SphSolver::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i)
    e += 0.5 * s_.mass[i] *
         (s_.v[3 * i] * s_.v[3 * i] + s_.v[3 * i + 1] * s_.v[3 * i + 1] +
          s_.v[3 * i + 2] * s_.v[3 * i + 2]);
  return e;
}

double SphSolver::internalEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i)
    e += s_.mass[i] * s_.u[i];
  return e;
}

double SphSolver::potentialEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double* x = &s_.x[3 * i];
    e -= s_.mass[i] * (par_.gravity[0] * x[0] + par_.gravity[1] * x[1] + par_.gravity[2] * x[2]);
    if (par_.pointMassGM > 0.0) {
      const double dx = x[0] - par_.pointMassAt[0], dy = x[1] - par_.pointMassAt[1],
                   dz = x[2] - par_.pointMassAt[2];
      e -= s_.mass[i] * par_.pointMassGM / std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  return e;
}

void SphSolver::totalMomentum(double p[3]) const {
  p[0] = p[1] = p[2] = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i)
    for (int k = 0; k < 3; ++k)
      p[k] += s_.mass[i] * s_.v[3 * i + k];
}

void SphSolver::totalAngularMomentum(double L[3]) const {
  L[0] = L[1] = L[2] = 0.0;
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double* x = &s_.x[3 * i];
    const double* v = &s_.v[3 * i];
    const double m = s_.mass[i];
    L[0] += m * (x[1] * v[2] - x[2] * v[1]);
    L[1] += m * (x[2] * v[0] - x[0] * v[2]);
    L[2] += m * (x[0] * v[1] - x[1] * v[0]);
  }
}

} // namespace craterkit

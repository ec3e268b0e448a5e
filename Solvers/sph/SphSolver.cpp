#include "sph/SphSolver.h"
#include "sph/ImpactorStop.h"
#include "sph/LateStageSchedule.h"

#include "common/Error.h"
#include "common/SimdClones.h"
#include "sph/Kernels.h"
#include "sph/Overburden.h"
#include "sph/PairTerms.h"
#include "sph/Strength.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace craterkit {

SphSolver::SphSolver(const SphState& initial, const SphParams& params, const SphClock& clock)
    : s_(initial), par_(params), earlyAlpha_(params.alpha) {
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
    const double rho0 = mat.eos.referenceDensity();
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
  checkState(s_, par_);
  const std::size_t n = s_.size();
  massCbrt_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    massCbrt_[i] = std::cbrt(s_.mass[i]);
  s_.h.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s_.h[i] = smoothingLength(s_, i);
  fracture_.assignFlaws(s_, par_.materials, par_.fractureSeed);
  time_ = clock.time, steps_ = clock.steps;
  // Switched before the first settle: with the early stage's law, settle() would read the late
  // stage's small strains as gigapascals, compact the pores (α) for good and clip the stress.
  if (par_.lateStageTime >= 0.0 && time_ > par_.lateStageTime) {
    switchMaterials(lateStageSoundSpeedAt(par_, time_)); // the stage the state was written in
    late_ = true;
  }
  nb_.build(s_, par_, k1_.dx, 0.0, false);
  settle(s_, p_, c_);
  const double signal = computeRates(s_, p_, c_, k1_);
  stableStep_ = clock.nextStep > 0.0 ? clock.nextStep : limitStep(s_, k1_, signal);
}

void SphSolver::imageShift(std::uint32_t code, double d[3]) const {
  const int sh[3] = {static_cast<int>(code % 3) - 1, static_cast<int>(code / 3 % 3) - 1,
                     static_cast<int>(code / 9) - 1};
  for (int k = 0; k < 3; ++k)
    d[k] = sh[k] * (par_.boxHi[k] - par_.boxLo[k]);
}

void SphSolver::settle(SphState& s, std::vector<double>& p, std::vector<double>& c,
                       const std::vector<char>* need) const {
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
  if (par_.summationDensity) {
    for (std::size_t i = 0; i < n; ++i)
      s.h[i] = smoothingLength(s, i);
    densityBySummation(s);
  }
  eosAndYield(s, p, c, !par_.summationDensity);
  if (par_.walls == SphParams::Walls::Extrapolated)
    walls_.apply(s, p, c, par_, nb_, need);
}

void SphSolver::eosAndYield(SphState& s, std::vector<double>& p, std::vector<double>& c,
                            bool withH) const {
  const std::size_t n = s.size();
  p.resize(n);
  c.resize(n);
  std::vector<Rheology> rh;
  for (const Material& m : par_.materials)
    rh.emplace_back(m);
    // Dynamic chunks: on a shared machine a thread that starts late does not hold up the other.
#pragma omp parallel for schedule(dynamic, 1024) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    if (withH)
      s.h[i] = smoothingLength(s, i);
    const Material& mat = par_.materials[static_cast<std::size_t>(s.material[i])];
    const Rheology& r = rh[static_cast<std::size_t>(s.material[i])];
    const double rho = s.rho[i], u = s.u[i];
    double& a = s.alpha[i];
    double P = mat.eos.pressure(a * rho, u) / a;
    if (!late_)
      P = compactDistention(r, mat.eos, rho, u, a, P);
    p[i] = limitStress(r, s.damage[i], P, &s.S[6 * i]);
    c[i] = signalSpeed(r, mat.eos.soundSpeed(a * rho, u), rho);
  }
}

template <class K> void SphSolver::summation(SphState& s) const {
  const std::size_t n = s.size();
  std::vector<double> rho(n);
#pragma omp parallel for schedule(dynamic, 256) if (n >= 512)
  for (std::size_t a = 0; a < n; ++a) {
    const double* xa = &s.x[3 * a];
    double sum = s.mass[a] * K::W(0.0, s.h[a]);
    for (std::uint32_t e = nb_.start()[a]; e < nb_.start()[a + 1]; ++e) {
      const std::uint32_t code = nb_.entry()[e];
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

double SphSolver::smoothingLength(const SphState& s, std::size_t i) const {
  const double m3 = massCbrt_[i], h = par_.kappa * m3 / std::cbrt(s.rho[i]);
  const double f = hCapFactor_[static_cast<std::size_t>(s.material[i])];
  return f > 0.0 ? std::min(h, f * m3) : h;
}

namespace {
using Packed = PairRecord;
using Scratch = PairScratch;
constexpr std::size_t kLanes = kPairLanes;

// Pass 1 of the pair terms: the entries of `entries` (index * 32 + image code) inside the pair's
// support, with their separations, packed into w and padded to whole vectors; returns their
// number with the padding. A function of its own so that its few pointers stay in registers
// (inside pairSums they were reloaded from the stack at every entry).
template <bool Periodic>
std::size_t supportStream(const PairPosition* Xp, std::uint32_t self, const std::uint32_t* entries,
                          std::uint32_t count, Scratch& w, const PairConstants& pc) {
  if (w.idx.size() < count + kLanes)
    w.resize(count + kLanes);
  std::uint64_t* __restrict wi = w.idx.data();
  double* __restrict wx = w.rx.data();
  double* __restrict wy = w.ry.data();
  double* __restrict wz = w.rz.data();
  double* __restrict w2 = w.r2.data();
  const PairPosition& A = Xp[self];
  const double ax = A.x[0], ay = A.x[1], az = A.x[2], ah = A.h;
  std::size_t m = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::uint32_t code = entries[k];
    const PairPosition& B = Xp[code >> 5];
    double rx = ax - B.x[0], ry = ay - B.x[1], rz = az - B.x[2];
    if (Periodic && (code & 31u) != kNoShift) {
      const std::uint32_t c = code & 31u;
      rx -= (static_cast<int>(c % 3) - 1) * pc.period[0];
      ry -= (static_cast<int>(c / 3 % 3) - 1) * pc.period[1];
      rz -= (static_cast<int>(c / 9) - 1) * pc.period[2];
    }
    const double r2 = rx * rx + ry * ry + rz * rz;
    const double hb = 0.5 * (ah + B.h);
    // Written always, kept only inside the support: no branch to mispredict (about a third
    // of the listed pairs are in the list's margin).
    wi[m] = code >> 5;
    wx[m] = rx, wy[m] = ry, wz[m] = rz, w2[m] = r2;
    m += (r2 < hb * hb) & (r2 != 0.0);
  }
  // Padded so that pass 2 never runs its scalar remainder (which took a fifth of its time): the
  // particle itself at zero separation, with r2 = (h/2)² only to keep the kernel finite. Each
  // of its terms carries a factor r_ab or v_ab, so it adds exact zeros.
  for (; m % kLanes != 0; ++m)
    wi[m] = self, wx[m] = 0.0, wy[m] = 0.0, wz[m] = 0.0, w2[m] = 0.25 * ah * ah;
  return m;
}

// Pass 2: the pair terms of particle A over the m pairs of supportStream in w. Where
// PairTermsWide.cpp is compiled (GCC 12+ on x86-64) and the processor has x86-64-v4, that
// version runs instead. The AVX-512 clone (common/SimdClones.h) serves builds without it (other
// compilers): its 32 vector registers hold the loop's 17 sums and temporaries, so the loop runs
// eight pairs wide (27 % less time than the generic code for the SCI-like run, 2026-12-01;
// benchmarks/JOURNAL.md). All versions differ only by rounding.
template <class K, bool Xsph> CK_SIMD_CLONES PairSums pairSums(const Packed* Pp, const Packed& A,
                                                               std::size_t m, const Scratch& w,
                                                               const PairConstants& pc) {
  // Branch-free so that the compiler vectorises the loop.
  double acc0 = 0, acc1 = 0, acc2 = 0, dr = 0, de = 0, sig = 0;
  double g0 = 0, g1 = 0, g2 = 0, g3 = 0, g4 = 0, g5 = 0, g6 = 0, g7 = 0, g8 = 0, xs0 = 0, xs1 = 0,
         xs2 = 0;
  const std::uint64_t* idx = w.idx.data();
  const double *RX = w.rx.data(), *RY = w.ry.data(), *RZ = w.rz.data(), *R2 = w.r2.data();
  const double* sa = A.s;
  const double sa0 = sa[0], sa1 = sa[1], sa2 = sa[2], sa3 = sa[3], sa4 = sa[4], sa5 = sa[5];
  const double av = pc.av, bv = pc.bv, xsph = pc.xsph, stressOn = pc.stressOn, gradOn = pc.gradOn;
  const double wallVisc1 = pc.wallViscosity - 1.0;
#pragma omp simd reduction(+ : acc0, acc1, acc2, dr, de, g0, g1, g2, g3, g4, g5, g6, g7, g8, \
                               xs0, xs1, xs2) reduction(max : sig)
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
    const double mix = A.rigid - B.rigid; // ±1 between a wall and the material, else 0
    const double pi = (vr < 0.0 ? piRaw : 0.0) * (1.0 + wallVisc1 * mix * mix);
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
                        const std::vector<double>& c, Rates& r,
                        const std::vector<std::uint32_t>* active) const {
  const std::size_t n = s.size();
  r.dx.assign(par_.xsph > 0.0 ? 3 * n : 0, 0.0);
  r.dv.resize(3 * n);
  r.drho.resize(n);
  r.du.resize(n);
  r.dS.resize(6 * n);
  const bool hasFlaws = !fracture_.empty();
  // Particles without flaws keep the zeros of the first call; the others are set below.
  if (r.damage.rate.size() != (hasFlaws ? n : 0)) {
    r.damage.rate.assign(hasFlaws ? n : 0, 0.0);
    r.damage.cap.assign(hasFlaws ? n : 0, 0.0);
  }
  signal_.resize(n);
  double* const sigOut = signal_.data();
  std::vector<double> G(par_.materials.size());
  for (std::size_t m = 0; m < G.size(); ++m)
    G[m] = par_.materials[m].strength == Material::Strength::None ? 0.0
                                                                  : par_.materials[m].shearModulus;
  std::vector<char> rigidMat(par_.materials.size());
  for (std::size_t m = 0; m < rigidMat.size(); ++m)
    rigidMat[m] = par_.materials[m].rigid;
  if (rigidBuild_ != nb_.version())
    filterRigidPairs(s);
  const std::int32_t* const rigidSlot = rigidSlot_.empty() ? nullptr : rigidSlot_.data();
  // reused: no allocation in the step loop; workers use Pp and Xp
  static thread_local std::vector<Packed> P;
  static thread_local std::vector<PairPosition> X;
  P.resize(n);
  X.resize(n);
  Packed* const Pw = P.data();
  PairPosition* const Xw = X.data();
  bool anyStress = false;
#pragma omp parallel for schedule(static) reduction(|| : anyStress) if (n >= 4096)
  for (std::size_t i = 0; i < n; ++i) {
    Packed& q = Pw[i];
    const double ir2 = 1.0 / (s.rho[i] * s.rho[i]);
    for (int k = 0; k < 3; ++k)
      Xw[i].x[k] = s.x[3 * i + k], q.v[k] = s.v[3 * i + k];
    Xw[i].h = s.h[i];
    q.h = s.h[i], q.rho = s.rho[i], q.m = s.mass[i], q.vol = s.mass[i] / s.rho[i];
    q.pr = p[i] * ir2;
    q.c = c[i];
    q.rigid = rigidMat[static_cast<std::size_t>(s.material[i])] ? 1.0 : 0.0;
    for (int k = 0; k < 6; ++k) {
      q.s[k] = s.S[6 * i + k] * ir2;
      anyStress = anyStress || q.s[k] != 0.0;
    }
    anyStress = anyStress || G[static_cast<std::size_t>(s.material[i])] > 0.0;
  }
  const Packed* Pp = Pw;
  const PairPosition* Xp = Xw;
  const bool wide = wideKernelAvailable();
  static thread_local std::vector<Scratch>
      scratchOfCaller; // the calling thread's; workers use the pointer
  scratchOfCaller.resize(static_cast<std::size_t>(omp_get_max_threads()));
  Scratch* const scratch = scratchOfCaller.data();
  PairConstants pc{par_.alpha,
                   par_.beta,
                   par_.xsph,
                   anyStress ? 1.0 : 0.0,
                   0.0,
                   par_.wallViscosity,
                   par_.periodic[0] || par_.periodic[1] || par_.periodic[2],
                   {0.0, 0.0, 0.0}};
  for (int k = 0; k < 3; ++k)
    pc.period[k] = par_.periodic[k] ? par_.boxHi[k] - par_.boxLo[k] : 0.0;
  double maxSignal = 0.0;
  // Each particle accumulates only its own rates (pairs are visited from both sides), so the
  // loop needs no atomics and gives the same bits for any thread count.
  const std::size_t updated = active ? active->size() : n;
  const std::uint32_t* const which = active ? active->data() : nullptr;
#pragma omp parallel for schedule(dynamic, 256) reduction(max : maxSignal) if (updated >= 512)
  for (std::size_t q = 0; q < updated; ++q) {
    const std::size_t a = which ? which[q] : q;
    const Packed& A = Pp[a];
    const bool solid = G[static_cast<std::size_t>(s.material[a])] > 0.0;
    double signal = A.c;
    PairConstants pcA = pc;
    pcA.gradOn = solid ? 1.0 : 0.0;
    Scratch& w = scratch[omp_get_thread_num()];
    const std::int32_t slot = rigidSlot ? rigidSlot[a] : -1;
    const std::uint32_t first =
        slot < 0 ? nb_.start()[a] : rigidStart_[static_cast<std::size_t>(slot)];
    const std::uint32_t* entries = (slot < 0 ? nb_.entry().data() : rigidEntry_.data()) + first;
    const std::uint32_t last =
        slot < 0 ? nb_.start()[a + 1] : rigidStart_[static_cast<std::size_t>(slot) + 1];
    const std::uint32_t count = last - first, self = static_cast<std::uint32_t>(a);
    const std::size_t m = pc.periodic ? supportStream<true>(Xp, self, entries, count, w, pc)
                          : wide      ? supportStreamWide(Xp, self, entries, count, w)
                                      : supportStream<false>(Xp, self, entries, count, w, pc);
    const PairSums sums =
        wide ? pairSumsWide<K, Xsph>(Pp, A, m, w, pcA) : pairSums<K, Xsph>(Pp, A, m, w, pcA);
    const double* acc = sums.acc;
    const double* xs = sums.xs;
    const double* grad = sums.grad;
    signal = std::max(signal, sums.sig);
    const double* xa = Xp[a].x;
    const double* Sa = &s.S[6 * a];
    double ext[3];
    bodyForce(par_, xa, ext);
    const bool rigid = rigidMat[static_cast<std::size_t>(s.material[a])];
    for (int k = 0; k < 3; ++k)
      r.dv[3 * a + k] = rigid ? 0.0 : acc[k] + ext[k];
    if (par_.xsph > 0.0)
      for (int k = 0; k < 3; ++k)
        r.dx[3 * a + k] = rigid ? 0.0 : xs[k];
    r.drho[a] = sums.dr;
    r.du[a] = sums.de;
    double* dS = &r.dS[6 * a];
    if (solid)
      deviatoricStressRate(G[static_cast<std::size_t>(s.material[a])], grad, Sa, dS);
    else
      for (int k = 0; k < 6; ++k)
        dS[k] = 0.0;
    if (hasFlaws && fracture_.hasFlaws(a))
      fracture_.damageRate(a, par_.materials[static_cast<std::size_t>(s.material[a])], Sa, p[a],
                           s.damage[a], s.rho[a], s.mass[a], r.damage.rate[a], r.damage.cap[a]);
    sigOut[a] = signal / (0.5 * s.h[a]);
    maxSignal = std::max(maxSignal, sigOut[a]);
  }
  return maxSignal;
}

void SphSolver::filterRigidPairs(const SphState& s) const {
  const std::size_t n = s.size();
  std::vector<char> rigidMat(par_.materials.size());
  bool any = false;
  for (std::size_t m = 0; m < rigidMat.size(); ++m)
    any = any || (rigidMat[m] = par_.materials[m].rigid);
  if (any && rigidSlot_.size() == n) { // only the rigid particles' lists count
    bool changed = false;
    for (std::size_t a = 0; a < n && !changed; ++a)
      changed = rigidSlot_[a] >= 0 && nb_.stamp(a) > rigidBuild_;
    if (!changed) {
      rigidBuild_ = nb_.version();
      return;
    }
  }
  rigidBuild_ = nb_.version();
  rigidSlot_.assign(any ? n : 0, -1);
  rigidStart_.assign(1, 0);
  rigidEntry_.clear();
  if (!any)
    return;
  // Rigid particles keep their velocity (their acceleration is zero), so a pair of them at the
  // same velocity has v_ab = 0 exactly for as long as the list lasts: every pair term carries
  // v_ab (continuity, energy, velocity gradient, the viscosity and its signal) or is discarded
  // (the acceleration of a rigid particle), so it adds exact zeros. In a container three
  // spacings thick such pairs are about a fifth of all listed ones.
  const auto isRigid = [&](std::size_t i) {
    return rigidMat[static_cast<std::size_t>(s.material[i])] != 0;
  };
  const auto sameVelocity = [&](std::size_t a, std::size_t b) {
    return s.v[3 * a] == s.v[3 * b] && s.v[3 * a + 1] == s.v[3 * b + 1] &&
           s.v[3 * a + 2] == s.v[3 * b + 2];
  };
  for (std::size_t a = 0; a < n; ++a) {
    if (!isRigid(a))
      continue;
    rigidSlot_[a] = static_cast<std::int32_t>(rigidStart_.size() - 1);
    for (std::uint32_t e = nb_.start()[a]; e < nb_.start()[a + 1]; ++e) {
      const std::size_t b = nb_.entry()[e] / 32;
      if (!isRigid(b) || !sameVelocity(a, b))
        rigidEntry_.push_back(nb_.entry()[e]);
    }
    rigidStart_.push_back(static_cast<std::uint32_t>(rigidEntry_.size()));
  }
}

double SphSolver::computeRates(const SphState& s, const std::vector<double>& p,
                               const std::vector<double>& c, Rates& r,
                               const std::vector<std::uint32_t>* active) const {
  if (par_.kernel == SphParams::Kernel::WendlandC2)
    return par_.xsph > 0.0 ? rates<WendlandC2, true>(s, p, c, r, active)
                           : rates<WendlandC2, false>(s, p, c, r, active);
  return par_.xsph > 0.0 ? rates<CubicSpline, true>(s, p, c, r, active)
                         : rates<CubicSpline, false>(s, p, c, r, active);
}

std::vector<double> SphSolver::switchMaterials(double c) {
  std::vector<double> scale(par_.materials.size(), 1.0);
  for (std::size_t m = 0; m < par_.materials.size(); ++m)
    scale[m] = par_.materials[m].switchToLateStage(c, par_.lateStagePoissonRatio);
  lateC_ = c;
  // The artificial viscosity's linear term goes as α c h: above the final c it would make the
  // flow's numerical viscosity a choice of the schedule, so α keeps the final c's α c.
  par_.alpha = earlyAlpha_ * std::min(1.0, par_.lateStageSoundSpeed / c);
  return scale;
}

void SphSolver::enterLateStage() {
  if (par_.lateStageStopMaterial >= 0)
    stopInFlow(s_, par_.lateStageStopMaterial, par_.materials);
  late_ = true;
  const double signal = switchState(lateStageSoundSpeedAt(par_, par_.lateStageTime));
  stableStep_ = limitStep(s_, k1_, signal);
}

double SphSolver::switchState(double c) {
  const std::vector<double> earlyK = earlyBulkModuli(par_.materials);
  const std::vector<double> scale = switchMaterials(c);
  keepOverburden(s_, par_, earlyK);
  for (std::size_t i = 0; i < s_.size(); ++i) {
    const double f = scale[static_cast<std::size_t>(s_.material[i])];
    for (int k = 0; k < 6; ++k)
      s_.S[6 * i + k] *= f;
  }
  settle(s_, p_, c_);
  return computeRates(s_, p_, c_, k1_);
}

void SphSolver::followSchedule() {
  const double c = lateStageSoundSpeedAt(par_, time_);
  if (!(c < lateC_))
    return;
  const double signal = switchState(c);
  // One step for all: the new law's limit. Block steps keep the cycle they asked for: the
  // particles' own limits only grow as c falls, and each grows its step by at most 2 per cycle.
  if (par_.blockStepLevels == 0)
    stableStep_ = limitStep(s_, k1_, signal);
}

double SphSolver::step(double dt) {
  if (dt <= 0.0)
    dt = stableStep_;
  if (late_ && par_.blockStepLevels > 0) {
    const double cycle = blockCycle(dt);
    followSchedule();
    return cycle;
  }
  bool toSwitch = false;
  if (!late_ && par_.lateStageTime >= 0.0 && time_ + dt > par_.lateStageTime) {
    if (par_.lateStageTime - time_ <= 1e-9 * dt) {
      enterLateStage();
      dt = std::min(dt, stableStep_);
    } else {
      dt = par_.lateStageTime - time_; // the switch happens at its time exactly
      toSwitch = true;
    }
  }
  const double asked = dt;
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
    if (!nb_.valid(s_, par_, k1_.dx, k1_.dv, dt))
      nb_.build(s_, par_, k1_.dx, dt);
    // The predictor's state and rates live in members, so a step allocates nothing.
    predict(dt); // into mid_
    settle(mid_, pm_, cm_);
    computeRates(mid_, pm_, cm_, k2_);
    // Error of the Euler predictor against Heun's step, relative to each particle's own
    // scales (speed: its signal speed; density; energy: its energy plus c²). Steps above the
    // tolerance are taken again, shorter (as miluphcuda's adaptive RK2 does).
    err = stepError(dt, k2_, worst);
    record_.attempts = attempt + 1;
    if (err <= par_.errorTolerance)
      break;
    dt *= std::max(0.1, 0.9 * std::sqrt(par_.errorTolerance / err));
  }
  correct(dt); // from mid_ and k2_
  settle(s_, p_, c_);
  const double signal = computeRates(s_, p_, c_, k1_);
  const double grow = err > 0.0 ? std::min(2.0, 0.9 * std::sqrt(par_.errorTolerance / err)) : 2.0;
  const double limit = limitStep(s_, k1_, signal);
  stableStep_ = std::min(limit, dt * std::max(grow, 1.0));
  record_.error = err, record_.worst = worst, record_.errorCapped = stableStep_ < limit;
  // The step cut to the switch, taken whole, ends on its time to the bit (time_ + dt can round
  // past it where time_ < lateStageTime / 2): a restored solver tells the stages apart by the
  // clock.
  time_ = toSwitch && dt == asked ? par_.lateStageTime : time_ + dt;
  ++steps_;
  if (late_)
    followSchedule();
  return dt;
}

bool SphSolver::reached(double t) const {
  // A remainder within the clock's rounding (the steps' sum can end an ulp short of t, and an
  // output time k × interval an ulp past the switch the run stopped at) or below the shortest
  // step allowed is not a step: it would be refused as a collapsed time step.
  const double slack = 4.0 * std::numeric_limits<double>::epsilon() * std::abs(t);
  return t - time_ <= std::max(slack, par_.minTimeStep);
}

void SphSolver::advanceTo(double t) {
  while (!reached(t)) {
    const double dt = std::min(stableStep_, t - time_);
    step(dt);
  }
}

} // namespace craterkit
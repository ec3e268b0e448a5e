#include "bonded/BondedForces.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#define CK_BONDED_AVX512 1
#include <immintrin.h>
#endif

#include <algorithm>
#include <cassert>

namespace craterkit {
namespace bondedpass {

#ifdef CK_BONDED_AVX512

bool avx512Available() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("x86-64-v4"); // the level the code below is compiled for
}

// Everything below is compiled for x86-64-v4 and called only where avx512Available().
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
// GCC 12's own intrinsics (_mm512_sqrt_pd starts from an undefined register)
// trip this warning; nothing here reads an uninitialised value.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"

namespace {

// x, y and z of the eight particles `ids` (AoS, three doubles each), one scalar load each:
// hardware gathers and 256-bit loads of each particle transposed measured slower on this pass.
inline void loadPositions(const double* x, __m256i ids, __m512d& px, __m512d& py, __m512d& pz) {
  alignas(32) std::uint32_t j[kLanes];
  _mm256_store_si256(reinterpret_cast<__m256i*>(j), ids);
  const double* q[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l)
    q[l] = x + 3 * std::size_t(j[l]);
  px = _mm512_setr_pd(q[0][0], q[1][0], q[2][0], q[3][0], q[4][0], q[5][0], q[6][0], q[7][0]);
  py = _mm512_setr_pd(q[0][1], q[1][1], q[2][1], q[3][1], q[4][1], q[5][1], q[6][1], q[7][1]);
  pz = _mm512_setr_pd(q[0][2], q[1][2], q[2][2], q[3][2], q[4][2], q[5][2], q[6][2], q[7][2]);
}

// Eight particles' 24 consecutive coordinates (coordinate k of particle l at lane (3 l + k) % 8 of
// a[(3 l + k) / 8]) from their x, y and z: the inverse of transpose below.
inline void interleave(__m512d x, __m512d y, __m512d z, __m512d a[3]) {
  const __m512i a0 = _mm512_setr_epi64(0, 8, 0, 1, 9, 0, 2, 10),
                b0 = _mm512_setr_epi64(0, 1, 8, 3, 4, 9, 6, 7);
  const __m512i a1 = _mm512_setr_epi64(0, 3, 11, 0, 4, 12, 0, 5),
                b1 = _mm512_setr_epi64(10, 1, 2, 11, 4, 5, 12, 7);
  const __m512i a2 = _mm512_setr_epi64(13, 0, 6, 14, 0, 7, 15, 0),
                b2 = _mm512_setr_epi64(0, 13, 2, 3, 14, 5, 6, 15);
  a[0] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a0, y), b0, z);
  a[1] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a1, y), b1, z);
  a[2] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a2, y), b2, z);
}

// Eight particles' x, y and z from their 24 consecutive coordinates a0, a1, a2 (coordinate c at
// lane c % 8 of a[c / 8]): coordinate k of particle l is c = 3 l + k.
inline void transpose(__m512d a0, __m512d a1, __m512d a2, __m512d& x, __m512d& y, __m512d& z) {
  const __m512i x01 = _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0),
                x2 = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13);
  const __m512i y01 = _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0),
                y2 = _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14);
  const __m512i z01 = _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0),
                z2 = _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15);
  x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, x01, a1), x2, a2);
  y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, y01, a1), y2, a2);
  z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, z01, a1), z2, a2);
}

// The velocities' spread over eight lanes (the operations of VelocitySpread::add, unfused).
struct LaneSpread {
  __m512d speed2, lo[3], hi[3];
  LaneSpread() { // written out: an implicit constructor is not compiled for x86-64-v4
    speed2 = _mm512_setzero_pd();
    for (int k = 0; k < 3; ++k)
      lo[k] = _mm512_set1_pd(kNoBond), hi[k] = _mm512_set1_pd(-kNoBond);
  }
  void add(__m512d vx, __m512d vy, __m512d vz) {
    speed2 = _mm512_max_pd(
        speed2, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(vx, vx), _mm512_mul_pd(vy, vy)),
                              _mm512_mul_pd(vz, vz)));
    lo[0] = _mm512_min_pd(lo[0], vx), lo[1] = _mm512_min_pd(lo[1], vy);
    lo[2] = _mm512_min_pd(lo[2], vz);
    hi[0] = _mm512_max_pd(hi[0], vx), hi[1] = _mm512_max_pd(hi[1], vy);
    hi[2] = _mm512_max_pd(hi[2], vz);
  }
  void mergeInto(VelocitySpread& spread) const {
    VelocitySpread lanes;
    lanes.speed2 = _mm512_reduce_max_pd(speed2);
    for (int k = 0; k < 3; ++k)
      lanes.lo[k] = _mm512_reduce_min_pd(lo[k]), lanes.hi[k] = _mm512_reduce_max_pd(hi[k]);
    spread.merge(lanes);
  }
};

// The kick-drift of the eight particles from `i` (all of them exist) on their forces f and
// positions x still in registers, lane l particle i + l: the operations of driftOne per
// coordinate, the velocities loaded and stored as 24 consecutive coordinates.
inline void driftBlock(const DriftPass& d, std::size_t i, const __m512d f[3], const __m512d x[3],
                       LaneSpread& spread) {
  const __m512d h = _mm512_div_pd(_mm512_set1_pd(d.halfStep), _mm512_loadu_pd(d.m + i));
  const __m512d dt = _mm512_set1_pd(d.dt);
  __m512d v[3], xn[3], a[3];
  transpose(_mm512_loadu_pd(d.v + 3 * i), _mm512_loadu_pd(d.v + 3 * i + kLanes),
            _mm512_loadu_pd(d.v + 3 * i + 2 * kLanes), v[0], v[1], v[2]);
  for (int k = 0; k < 3; ++k) {
    if (d.pending)
      v[k] = _mm512_fmadd_pd(h, f[k], v[k]);
    v[k] = _mm512_add_pd(v[k], _mm512_mul_pd(h, f[k]));
    xn[k] = _mm512_add_pd(x[k], _mm512_mul_pd(dt, v[k]));
  }
  spread.add(v[0], v[1], v[2]);
  interleave(v[0], v[1], v[2], a);
  for (int r = 0; r < 3; ++r)
    _mm512_storeu_pd(d.v + 3 * i + kLanes * r, a[r]);
  interleave(xn[0], xn[1], xn[2], a);
  for (int r = 0; r < 3; ++r)
    _mm512_storeu_pd(d.xOut + 3 * i + kLanes * r, a[r]);
}

// The lane loop of the generic pass, operation for operation (see the header on the fused
// multiply-adds), over the wide or (kCompact) the compact lists; with `d`, each full block's
// kick-drift (driftBlock) right after its forces, a part-full last block's by driftAvx512 on the
// stored forces.
template <bool kDrift, bool kCompact> long passAvx512(const BlockPass& p, const DriftPass* d,
                                                      std::size_t b0, std::size_t b1,
                                                      VelocitySpread* spread) {
  const double* x = p.x;
  const __m512d sigma2 = _mm512_set1_pd(p.terms.sigma2), rEq2 = _mm512_set1_pd(p.terms.rEq2);
  const __m512d kappa = _mm512_set1_pd(p.terms.kappa), rCut2 = _mm512_set1_pd(p.rCut2);
  const __m512d c24 = _mm512_set1_pd(24.0 * p.terms.epsilon);
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0);
  const __m512d noBond = _mm512_set1_pd(kNoBond), breaking = _mm512_set1_pd(kBreaking);
  const __m512d restRef = _mm512_set1_pd(p.restRef);
  const __m256 breakingOffset = _mm256_set1_ps(kBreakingOffset);
  const __m256i laneIds = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i last = _mm256_set1_epi32(static_cast<int>(p.n - 1));
  LaneSpread lanes;
  long total = 0;
  for (std::size_t b = b0; b < b1; ++b) {
    const __m256i self = _mm256_min_epu32(
        _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(b * kLanes)), laneIds), last);
    __m512d xi, yi, zi;
    loadPositions(x, self, xi, yi, zi);
    __m512d fx = zero, fy = zero, fz = zero;
    std::uint32_t broke = 0;
    for (std::size_t e = p.blockStart[b]; e < p.blockStart[b + 1]; e += kLanes) {
      __m512d xj, yj, zj;
      loadPositions(x, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p.partner + e)), xj, yj,
                    zj);
      const __m512d dx = _mm512_sub_pd(xi, xj), dy = _mm512_sub_pd(yi, yj),
                    dz = _mm512_sub_pd(zi, zj);
      const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dx, dx, _mm512_mul_pd(dy, dy)));
      // r0 = restRef + offset (exact, converted from float) in the compact lists.
      const __m512d r0 =
          kCompact ? _mm512_add_pd(restRef, _mm512_cvtps_pd(_mm256_loadu_ps(p.offset + e)))
                   : _mm512_loadu_pd(p.rest + e);
      const __mmask8 breaks = _mm512_cmp_pd_mask(r0, noBond, _CMP_LT_OQ) &
                              _mm512_cmp_pd_mask(r2, rCut2, _CMP_GT_OQ); // for good
      if (breaks) {
        if constexpr (kCompact)
          _mm256_mask_storeu_ps(p.offset + e, breaks, breakingOffset);
        else
          _mm512_mask_storeu_pd(p.rest + e, breaks, breaking);
        broke += static_cast<std::uint32_t>(__builtin_popcount(breaks));
      }
      const __m512d r0e = _mm512_mask_blend_pd(breaks, r0, noBond);
      const __m512d inv = _mm512_div_pd(one, r2);
      const __mmask8 near =
          _mm512_cmp_pd_mask(r2, rEq2, _CMP_LT_OQ) & _mm512_cmp_pd_mask(r2, zero, _CMP_GT_OQ);
      const __m512d s2 = _mm512_mul_pd(sigma2, inv);
      const __m512d s6 = _mm512_mul_pd(_mm512_mul_pd(s2, s2), s2);
      const __m512d repel = _mm512_maskz_mul_pd(
          near, _mm512_mul_pd(_mm512_mul_pd(c24, s6), _mm512_sub_pd(_mm512_mul_pd(two, s6), one)),
          inv);
      const __m512d r = _mm512_sqrt_pd(r2);
      const __mmask8 pull = _mm512_cmp_pd_mask(r, r0e, _CMP_GT_OQ);
      const __m512d f = _mm512_mask3_fnmadd_pd(_mm512_mul_pd(kappa, _mm512_sub_pd(r, r0e)),
                                               _mm512_mul_pd(r, inv), repel, pull);
      fx = _mm512_fmadd_pd(f, dx, fx);
      fy = _mm512_fmadd_pd(f, dy, fy);
      fz = _mm512_fmadd_pd(f, dz, fz);
    }
    p.breaks[b] = broke;
    total += broke;
    if (b * kLanes + kLanes <= p.n && !p.v) {
      // A full block without the half kick here: its forces stored as 24 coordinates.
      __m512d a[3];
      interleave(fx, fy, fz, a);
      for (int r = 0; r < 3; ++r)
        _mm512_storeu_pd(p.force + 3 * b * kLanes + kLanes * r, a[r]);
      if constexpr (kDrift) {
        const __m512d fb[3] = {fx, fy, fz}, xb[3] = {xi, yi, zi};
        driftBlock(*d, b * kLanes, fb, xb, lanes);
      }
      continue;
    }
    alignas(64) double f[3][kLanes];
    _mm512_store_pd(f[0], fx);
    _mm512_store_pd(f[1], fy);
    _mm512_store_pd(f[2], fz);
    const std::size_t count = std::min(kLanes, p.n - b * kLanes);
    for (std::size_t l = 0; l < count; ++l) {
      const std::size_t i = b * kLanes + l;
      for (int k = 0; k < 3; ++k)
        p.force[3 * i + k] = f[k][l];
      if (p.v) {
        const double h = p.halfStep / p.m[i];
        for (int k = 0; k < 3; ++k)
          p.v[3 * i + k] = __builtin_fma(h, f[k][l], p.v[3 * i + k]);
      }
    }
    if constexpr (kDrift)
      driftAvx512(*d, b * kLanes, b * kLanes + count, *spread);
  }
  if constexpr (kDrift)
    lanes.mergeInto(*spread);
  return total;
}

} // namespace

long blockForcesAvx512(const BlockPass& p, std::size_t b0, std::size_t b1) {
  return p.rest ? passAvx512<false, false>(p, nullptr, b0, b1, nullptr)
                : passAvx512<false, true>(p, nullptr, b0, b1, nullptr);
}

long blockForcesDriftAvx512(const BlockPass& p, const DriftPass& d, std::size_t b0, std::size_t b1,
                            VelocitySpread& spread) {
  // Full blocks take their positions and forces from the pass and drift into a buffer the pass
  // does not read; the half kick is the drift's (p.v null), or it would be done twice.
  assert(!p.v && d.x == p.x && d.f == p.force && d.xOut != p.x);
  return p.rest ? passAvx512<true, false>(p, &d, b0, b1, &spread)
                : passAvx512<true, true>(p, &d, b0, b1, &spread);
}

namespace {

// One particle of the kick-drift, its velocity after the kicks added to `spread`.
inline void driftOne(const DriftPass& p, std::size_t i, VelocitySpread& spread) {
  const double h = p.halfStep / p.m[i];
  double w[3];
  for (int k = 0; k < 3; ++k) {
    const std::size_t c = 3 * i + k;
    double v = p.v[c];
    if (p.pending)
      v = __builtin_fma(h, p.f[c], v);
    v += h * p.f[c]; // not fused: this file is compiled with -ffp-contract=off
    p.v[c] = v;
    p.xOut[c] = p.x[c] + p.dt * v; // x += Δt v where xOut is x
    w[k] = v;
  }
  spread.add(w[0], w[1], w[2]);
}

} // namespace

// Eight particles at a time (their 24 coordinates are three registers, each coordinate's kicks
// and drift the scalar operations of driftOne), the rest one by one. The spread's extremes are
// exact whatever the order they are taken in.
void driftAvx512(const DriftPass& p, std::size_t i0, std::size_t i1, VelocitySpread& spread) {
  VelocitySpread mine = spread; // a local: the stores to x and v may not alias it (registers)
  const __m512d halfStep = _mm512_set1_pd(p.halfStep), dt = _mm512_set1_pd(p.dt);
  // Each particle's h for its three coordinates: particle c / 3 at coordinate c.
  const __m512i h0 = _mm512_setr_epi64(0, 0, 0, 1, 1, 1, 2, 2),
                h1 = _mm512_setr_epi64(2, 3, 3, 3, 4, 4, 4, 5),
                h2 = _mm512_setr_epi64(5, 5, 6, 6, 6, 7, 7, 7);
  LaneSpread lanes;
  std::size_t i = i0;
  for (; i + kLanes <= i1; i += kLanes) {
    const __m512d h = _mm512_div_pd(halfStep, _mm512_loadu_pd(p.m + i));
    const __m512d hc[3] = {_mm512_permutexvar_pd(h0, h), _mm512_permutexvar_pd(h1, h),
                           _mm512_permutexvar_pd(h2, h)};
    __m512d w[3];
    for (int r = 0; r < 3; ++r) {
      const std::size_t c = 3 * i + kLanes * r;
      const __m512d f = _mm512_loadu_pd(p.f + c);
      __m512d v = _mm512_loadu_pd(p.v + c);
      if (p.pending)
        v = _mm512_fmadd_pd(hc[r], f, v);
      v = _mm512_add_pd(v, _mm512_mul_pd(hc[r], f));
      _mm512_storeu_pd(p.v + c, v);
      _mm512_storeu_pd(p.xOut + c, _mm512_add_pd(_mm512_loadu_pd(p.x + c), _mm512_mul_pd(dt, v)));
      w[r] = v;
    }
    __m512d vx, vy, vz;
    transpose(w[0], w[1], w[2], vx, vy, vz);
    lanes.add(vx, vy, vz);
  }
  for (; i < i1; ++i)
    driftOne(p, i, mine);
  lanes.mergeInto(mine);
  spread = mine;
}

std::size_t nearCandidatesAvx512(const NearScan& s, std::size_t begin, std::size_t end,
                                 const double xi[3], std::uint32_t self, std::uint32_t* out) {
  const __m512d x = _mm512_set1_pd(xi[0]), y = _mm512_set1_pd(xi[1]), z = _mm512_set1_pd(xi[2]);
  const __m512d reach2 = _mm512_set1_pd(s.reach2);
  const __m256i me = _mm256_set1_epi32(static_cast<int>(self));
  std::size_t count = 0;
  for (std::size_t k = begin; k < end; k += kLanes) {
    const __mmask8 in = end - k >= kLanes ? 0xFF : static_cast<__mmask8>((1u << (end - k)) - 1);
    const __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(in, s.x + k), x);
    const __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(in, s.y + k), y);
    const __m512d dz = _mm512_sub_pd(_mm512_maskz_loadu_pd(in, s.z + k), z);
    const __m512d r2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                     _mm512_mul_pd(dz, dz));
    const __m256i ids = _mm256_maskz_loadu_epi32(in, s.id + k);
    const __mmask8 near =
        in & _mm512_cmp_pd_mask(r2, reach2, _CMP_LT_OQ) & _mm256_cmpneq_epi32_mask(ids, me);
    // Compressed in a register and stored whole (the memory form is slow on some processors).
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + count),
                        _mm256_maskz_compress_epi32(near, ids));
    count += static_cast<std::size_t>(__builtin_popcount(near));
  }
  return count;
}

void halfKickAvx512(const DriftPass& p, std::size_t i0, std::size_t i1) {
  for (std::size_t i = i0; i < i1; ++i) {
    const double h = p.halfStep / p.m[i];
    for (int k = 0; k < 3; ++k)
      p.v[3 * i + k] = __builtin_fma(h, p.f[3 * i + k], p.v[3 * i + k]);
  }
}

#pragma GCC diagnostic pop
#pragma GCC pop_options

#else

bool avx512Available() { return false; }
long blockForcesAvx512(const BlockPass&, std::size_t, std::size_t) { return 0; }
void driftAvx512(const DriftPass&, std::size_t, std::size_t, VelocitySpread&) {}
long blockForcesDriftAvx512(const BlockPass&, const DriftPass&, std::size_t, std::size_t,
                            VelocitySpread&) {
  return 0;
}
void halfKickAvx512(const DriftPass&, std::size_t, std::size_t) {}
std::size_t nearCandidatesAvx512(const NearScan&, std::size_t, std::size_t, const double[3],
                                 std::uint32_t, std::uint32_t*) {
  return 0;
}

#endif

} // namespace bondedpass
} // namespace craterkit

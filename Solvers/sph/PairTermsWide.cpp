// The SPH pair loop for AVX-512, eight pairs per vector, the neighbours' records transposed in
// registers instead of loaded lane by lane (sph/PairTerms.h). The terms are SphSolver.cpp's
// pairSums, written with vector types in the same order.
#include "sph/PairTerms.h"

#include "sph/Kernels.h"

#include <cmath>
#include <stdexcept>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#define CK_WIDE_PAIRS 1
#include <immintrin.h>
// GCC 12's AVX-512 headers start some intrinsics from an undefined vector on purpose.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace craterkit {

#ifdef CK_WIDE_PAIRS

// The whole x86-64-v4 level (AVX-512 F, CD, BW, DQ, VL), a superset of what CK_WIDE enables.
bool wideKernelAvailable() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("x86-64-v4");
}

#define CK_WIDE __attribute__((target("avx512f,avx512dq,avx512vl,avx2,fma")))

namespace {
using V = __m512d;

CK_WIDE inline V bc(double a) { return _mm512_set1_pd(a); }
// a < b ? x : y, lane by lane
CK_WIDE inline V selectLess(V a, V b, V x, V y) {
  return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ), y, x);
}

// Transposes eight rows of eight doubles (r[j] = lane j's eight fields) into eight columns
// (c[f] = field f of the eight lanes).
CK_WIDE inline void transpose8(const V r[8], V c[8]) {
  V t[8];
  for (int j = 0; j < 8; j += 2) {
    t[j] = _mm512_unpacklo_pd(r[j], r[j + 1]);     // a0 b0 a2 b2 a4 b4 a6 b6
    t[j + 1] = _mm512_unpackhi_pd(r[j], r[j + 1]); // a1 b1 a3 b3 a5 b5 a7 b7
  }
  const __m512i lo = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i hi = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  V u[8];
  for (int j = 0; j < 8; j += 4) {
    u[j] = _mm512_permutex2var_pd(t[j], lo, t[j + 2]);         // a0 b0 c0 d0 a4 b4 c4 d4
    u[j + 1] = _mm512_permutex2var_pd(t[j + 1], lo, t[j + 3]); // …1, …5
    u[j + 2] = _mm512_permutex2var_pd(t[j], hi, t[j + 2]);     // …2, …6
    u[j + 3] = _mm512_permutex2var_pd(t[j + 1], hi, t[j + 3]); // …3, …7
  }
  for (int f = 0; f < 4; ++f) {
    c[f] = _mm512_shuffle_f64x2(u[f], u[f + 4], 0x44);
    c[f + 4] = _mm512_shuffle_f64x2(u[f], u[f + 4], 0xEE);
  }
}

// Branch-free kernels (sph/Kernels.h's Branchless), eight lanes.
template <class K> struct WideKernel;
template <> struct WideKernel<CubicSpline> {
  CK_WIDE static V gradOverR(V q, V ih, V iq) {
    const V ih2 = ih * ih, s = bc(8.0 / M_PI) * ih2 * ih2 * ih;
    const V t = bc(1.0) - q;
    const V inner = bc(18.0) * q - bc(12.0);
    const V outer = bc(-6.0) * t * t * iq;
    return s * selectLess(q, bc(0.5), inner, outer);
  }
  CK_WIDE static V value(V q, V ih) {
    const V s = bc(8.0 / M_PI) * ih * ih * ih, t = bc(1.0) - q;
    const V inner = bc(6.0) * q * q * q - bc(6.0) * q * q + bc(1.0), outer = bc(2.0) * t * t * t;
    return s * selectLess(q, bc(0.5), inner, outer);
  }
};
template <> struct WideKernel<WendlandC2> {
  CK_WIDE static V gradOverR(V q, V ih, V) {
    const V t = bc(1.0) - q, ih2 = ih * ih;
    return bc(21.0 / (2.0 * M_PI)) * ih2 * ih2 * ih * (bc(-20.0) * t * t * t);
  }
  CK_WIDE static V value(V q, V ih) {
    const V t = bc(1.0) - q;
    return bc(21.0 / (2.0 * M_PI)) * ih * ih * ih * t * t * t * t * (bc(1.0) + bc(4.0) * q);
  }
};

// 1/x to about one rounding (the 14-bit estimate and two Newton steps), without the divider.
CK_WIDE inline V recip(V x) {
  V y = _mm512_rcp14_pd(x);
  y = _mm512_fmadd_pd(y, _mm512_fnmadd_pd(x, y, bc(1.0)), y);
  return _mm512_fmadd_pd(y, _mm512_fnmadd_pd(x, y, bc(1.0)), y);
}
// 1/√x likewise (the estimate and two Newton steps: y (3 − x y²)/2).
CK_WIDE inline V rsqrt(V x) {
  V y = _mm512_rsqrt14_pd(x);
  y = bc(0.5) * y * (bc(3.0) - x * y * y);
  return bc(0.5) * y * (bc(3.0) - x * y * y);
}

// The sums run in registers (locals, not a struct in memory: a struct kept them on the stack).
template <class K, bool Xsph>
CK_WIDE PairSums pairSumsAvx512(const PairRecord* records, const PairRecord& A, std::size_t m,
                                const PairScratch& w, const PairConstants& pc) {
  const V zero = _mm512_setzero_pd();
  V acc0 = zero, acc1 = zero, acc2 = zero, dr = zero, de = zero, sig = zero;
  V g0 = zero, g1 = zero, g2 = zero, g3 = zero, g4 = zero, g5 = zero, g6 = zero, g7 = zero,
    g8 = zero, xs0 = zero, xs1 = zero, xs2 = zero;
  const V sa0 = bc(A.s[0]), sa1 = bc(A.s[1]), sa2 = bc(A.s[2]);
  const V sa3 = bc(A.s[3]), sa4 = bc(A.s[4]), sa5 = bc(A.s[5]);
  const V ah = bc(A.h), arho = bc(A.rho), apr = bc(A.pr), ac = bc(A.c);
  const V avx = bc(A.v[0]), avy = bc(A.v[1]), avz = bc(A.v[2]);
  const V nav = bc(-pc.av), bv2 = bc(2.0 * pc.bv), stressOn = bc(pc.stressOn);
  const V gradOn = bc(pc.gradOn), xsph = bc(pc.xsph), wallVisc1 = bc(pc.wallViscosity - 1.0);
  const std::uint64_t* idx = w.idx.data();
  for (std::size_t k = 0; k < m; k += kPairLanes) {
    V row[8], lo[8], hi[8];
    for (int j = 0; j < 8; ++j)
      row[j] = _mm512_load_pd(&records[idx[k + j]].v[0]);
    transpose8(row, lo); // vx vy vz h rho m vol pr
    for (int j = 0; j < 8; ++j)
      row[j] = _mm512_load_pd(&records[idx[k + j]].c);
    transpose8(row, hi); // c s0 … s5 rigid
    const V rx = _mm512_loadu_pd(&w.rx[k]), ry = _mm512_loadu_pd(&w.ry[k]);
    const V rz = _mm512_loadu_pd(&w.rz[k]), r2 = _mm512_loadu_pd(&w.r2[k]);
    const V hb = bc(0.5) * (ah + lo[3]), ih = recip(hb);
    const V rinv = rsqrt(r2), rr = r2 * rinv;
    const V g = WideKernel<K>::gradOverR(rr * ih, ih, hb * rinv); // ∇_a W = g r_ab
    const V vx = avx - lo[0], vy = avy - lo[1], vz = avz - lo[2];
    const V vr = vx * rx + vy * ry + vz * rz;
    const V mu = hb * vr * recip(r2 + bc(0.01) * hb * hb); // h̄ = support, as miluphcuda
    const V csum = ac + hi[0], irho = recip(arho + lo[4]);
    const V piRaw = (nav * csum * mu + bv2 * mu * mu) * irho;
    const V mix = bc(A.rigid) - hi[7]; // ±1 between a wall and the material, else 0
    const V pi = selectLess(vr, zero, piRaw, zero) * (bc(1.0) + wallVisc1 * mix * mix);
    const V sgn = selectLess(vr, zero, csum - bc(3.0) * vr * rinv, zero);
    sig = _mm512_max_pd(sig, sgn);
    const V mg = lo[5] * g;
    const V f = mg * (apr + lo[7] + pi);
    // (S_a/ρ_a² + S_b/ρ_b²) · ∇_a W, and the stress power with the same pair terms so that
    // energy is conserved exactly: −Σ m_b (S_a/ρ_a²) : (v_ab ⊗ ∇_a W).
    const V t0 = sa0 + hi[1], t1 = sa1 + hi[2], t2 = sa2 + hi[3];
    const V t3 = sa3 + hi[4], t4 = sa4 + hi[5], t5 = sa5 + hi[6];
    const V ms = mg * stressOn;
    acc0 += -f * rx + ms * (t0 * rx + t3 * ry + t4 * rz);
    acc1 += -f * ry + ms * (t3 * rx + t1 * ry + t5 * rz);
    acc2 += -f * rz + ms * (t4 * rx + t5 * ry + t2 * rz);
    dr += mg * vr; // m_b v_ab · ∇_a W
    de += mg * (apr + bc(0.5) * pi) * vr -
          ms * (sa0 * vx * rx + sa1 * vy * ry + sa2 * vz * rz + sa3 * (vx * ry + vy * rx) +
                sa4 * (vx * rz + vz * rx) + sa5 * (vy * rz + vz * ry));
    const V wv = -lo[6] * g * gradOn; // ∂_β v^α ≈ −Σ (m_b/ρ_b) v_ab^α ∂_β W
    const V wx = wv * vx, wy = wv * vy, wz = wv * vz;
    g0 += wx * rx, g1 += wx * ry, g2 += wx * rz;
    g3 += wy * rx, g4 += wy * ry, g5 += wy * rz;
    g6 += wz * rx, g7 += wz * ry, g8 += wz * rz;
    if constexpr (Xsph) {
      const V wx2 = xsph * lo[5] * (bc(2.0) * irho) * WideKernel<K>::value(rr * ih, ih);
      xs0 -= wx2 * vx, xs1 -= wx2 * vy, xs2 -= wx2 * vz;
    }
  }
  PairSums r;
  r.acc[0] = _mm512_reduce_add_pd(acc0);
  r.acc[1] = _mm512_reduce_add_pd(acc1);
  r.acc[2] = _mm512_reduce_add_pd(acc2);
  r.dr = _mm512_reduce_add_pd(dr);
  r.de = _mm512_reduce_add_pd(de);
  const V gs[9] = {g0, g1, g2, g3, g4, g5, g6, g7, g8};
  for (int j = 0; j < 9; ++j)
    r.grad[j] = _mm512_reduce_add_pd(gs[j]);
  r.xs[0] = _mm512_reduce_add_pd(xs0);
  r.xs[1] = _mm512_reduce_add_pd(xs1);
  r.xs[2] = _mm512_reduce_add_pd(xs2);
  r.sig = _mm512_reduce_max_pd(sig);
  return r;
}
// The support pass for eight listed neighbours at a time: their position records loaded whole
// and transposed, the kept ones compressed to the front of the vector and stored.
CK_WIDE std::size_t supportAvx512(const PairPosition* X, std::uint32_t self,
                                  const std::uint32_t* entries, std::uint32_t count,
                                  PairScratch& w) {
  if (w.idx.size() < count + 2 * kPairLanes)
    w.resize(count + 2 * kPairLanes); // each store writes eight lanes
  std::uint64_t* wi = w.idx.data();
  double *wx = w.rx.data(), *wy = w.ry.data(), *wz = w.rz.data(), *w2 = w.r2.data();
  const PairPosition& A = X[self];
  const V ax = bc(A.x[0]), ay = bc(A.x[1]), az = bc(A.x[2]), ah = bc(A.h), zero = bc(0.0);
  const __m512i selectEven = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i selectOdd = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  std::size_t m = 0;
  for (std::uint32_t k = 0; k < count; k += 8) {
    // The indices as a vector straight from the list (scalar stores read back as one vector
    // would stall on store forwarding); past the end: A itself, dropped by the mask.
    const __mmask8 valid = count - k >= 8 ? 0xFF : static_cast<__mmask8>((1u << (count - k)) - 1);
    const __m256i codes = _mm256_maskz_loadu_epi32(valid, entries + k);
    const __m256i idv = _mm256_mask_blend_epi32(valid, _mm256_set1_epi32(static_cast<int>(self)),
                                                _mm256_srli_epi32(codes, 5));
    std::uint32_t id[8];
    for (std::uint32_t j = 0; j < 8; ++j)
      id[j] = k + j < count ? entries[k + j] >> 5 : self;
    V R[4];
    for (int j = 0; j < 4; ++j)
      R[j] = _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_load_pd(X[id[j]].x)),
                                _mm256_load_pd(X[id[j + 4]].x), 1); // record j, then j + 4
    const V lo01 = _mm512_unpacklo_pd(R[0], R[1]), hi01 = _mm512_unpackhi_pd(R[0], R[1]);
    const V lo23 = _mm512_unpacklo_pd(R[2], R[3]), hi23 = _mm512_unpackhi_pd(R[2], R[3]);
    const V bx = _mm512_permutex2var_pd(lo01, selectEven, lo23);
    const V bz = _mm512_permutex2var_pd(lo01, selectOdd, lo23);
    const V by = _mm512_permutex2var_pd(hi01, selectEven, hi23);
    const V bh = _mm512_permutex2var_pd(hi01, selectOdd, hi23);
    const V rx = ax - bx, ry = ay - by, rz = az - bz;
    const V r2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(rx, rx), _mm512_mul_pd(ry, ry)),
                               _mm512_mul_pd(rz, rz));
    const V hb = bc(0.5) * (ah + bh);
    const __mmask8 in = _mm512_cmp_pd_mask(r2, hb * hb, _CMP_LT_OQ) &
                        _mm512_cmp_pd_mask(r2, zero, _CMP_NEQ_OQ) & valid;
    const __m512i ids = _mm512_cvtepu32_epi64(idv);
    _mm512_storeu_si512(wi + m, _mm512_maskz_compress_epi64(in, ids));
    _mm512_storeu_pd(wx + m, _mm512_maskz_compress_pd(in, rx));
    _mm512_storeu_pd(wy + m, _mm512_maskz_compress_pd(in, ry));
    _mm512_storeu_pd(wz + m, _mm512_maskz_compress_pd(in, rz));
    _mm512_storeu_pd(w2 + m, _mm512_maskz_compress_pd(in, r2));
    m += static_cast<std::size_t>(__builtin_popcount(in));
  }
  // Padded to whole vectors as SphSolver.cpp's supportStream does: A itself at zero
  // separation, r2 = (h/2)² only to keep the kernel finite; each term then adds exact zeros.
  for (; m % kPairLanes != 0; ++m)
    wi[m] = self, wx[m] = 0.0, wy[m] = 0.0, wz[m] = 0.0, w2[m] = 0.25 * A.h * A.h;
  return m;
}

} // namespace

template <class K, bool Xsph> PairSums pairSumsWide(const PairRecord* records, const PairRecord& A,
                                                    std::size_t m, const PairScratch& w,
                                                    const PairConstants& pc) {
  return pairSumsAvx512<K, Xsph>(records, A, m, w, pc);
}

std::size_t supportStreamWide(const PairPosition* positions, std::uint32_t self,
                              const std::uint32_t* entries, std::uint32_t count, PairScratch& w) {
  return supportAvx512(positions, self, entries, count, w);
}

#else

bool wideKernelAvailable() { return false; }

std::size_t supportStreamWide(const PairPosition*, std::uint32_t, const std::uint32_t*,
                              std::uint32_t, PairScratch&) {
  throw std::logic_error("SPH: the AVX-512 support pass is not in this build");
}

template <class K, bool Xsph> PairSums pairSumsWide(const PairRecord*, const PairRecord&,
                                                    std::size_t, const PairScratch&,
                                                    const PairConstants&) {
  throw std::logic_error("SPH: the AVX-512 pair loop is not in this build");
}

#endif

template PairSums pairSumsWide<CubicSpline, false>(const PairRecord*, const PairRecord&,
                                                   std::size_t, const PairScratch&,
                                                   const PairConstants&);
template PairSums pairSumsWide<CubicSpline, true>(const PairRecord*, const PairRecord&, std::size_t,
                                                  const PairScratch&, const PairConstants&);
template PairSums pairSumsWide<WendlandC2, false>(const PairRecord*, const PairRecord&, std::size_t,
                                                  const PairScratch&, const PairConstants&);
template PairSums pairSumsWide<WendlandC2, true>(const PairRecord*, const PairRecord&, std::size_t,
                                                 const PairScratch&, const PairConstants&);

} // namespace craterkit

// The cluster-pair kernel (sph/ClusterPairs.h) for AVX-512: particle i of cluster I against the
// eight lanes of cluster J, each pair once. The terms are those of SphSolver.cpp's pairSums
// (docs/physics.md §2.2, §2.3), split into what the pair shares and what each side weighs it
// with: with r = x_i − x_j, v = v_i − v_j and ∇_i W = g r,
//   momentum   F = g (−(p_i/ρ_i² + p_j/ρ_j² + Π) r + (S_i/ρ_i² + S_j/ρ_j²) r):
//              i gains m_j F, j gains −m_i F;
//   continuity g v·r, weighted by m_j for i and m_i for j;
//   energy     g (p_i/ρ_i² + Π/2) v·r − g (S_i/ρ_i²) : (v ⊗ r) for i (weight m_j), the same with
//              j's fields for j (weight m_i): v_ji ⊗ r_ji = v ⊗ r;
//   velocity gradient −g v ⊗ r, weighted by m_j/ρ_j for i and m_i/ρ_i for j;
//   XSPH       −ε 2 W v / (ρ_i + ρ_j), weighted by m_j for i and −m_i for j.
#include "sph/ClusterPairs.h"

#include "sph/Kernels.h"
#include "sph/WideMath.h"

#include <algorithm>
#include <stdexcept>

namespace craterkit {

#ifdef CK_WIDE_PAIRS
namespace {
using namespace wide;

CK_WIDE inline V blend(__mmask8 m, V x, V y) { return _mm512_mask_blend_pd(m, y, x); } // m ? x : y
CK_WIDE inline V lanes(const ClusterBlock& c, int f) { return _mm512_load_pd(c.f[f]); }
CK_WIDE inline V one(const ClusterBlock& c, int f, int l) { return bc(c.f[f][l]); }

template <class K, bool Xsph>
CK_WIDE void sumsAvx512(const ClusterBlock* blocks, const std::uint32_t* start,
                        const std::uint32_t* partner, std::uint32_t first, std::uint32_t last,
                        ClusterSums* sums, const PairConstants& pc) {
  const V zero = _mm512_setzero_pd(), nav = bc(-pc.av), bv2 = bc(2.0 * pc.bv);
  const V stressOn = bc(pc.stressOn), xsph2 = bc(2.0 * pc.xsph);
  const __m512i lane = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
  alignas(64) V ai[8][kClusterSums]; // I's particles' sums, eight lanes each
  for (std::uint32_t I = first; I < last; ++I) {
    const ClusterBlock& ci = blocks[I];
    for (auto& row : ai)
      for (V& a : row)
        a = zero;
    for (std::uint32_t e = start[I]; e < start[I + 1]; ++e) {
      const std::uint32_t J = partner[e];
      const ClusterBlock& cj = blocks[J];
      V bj[kClusterSums]; // J's sums from I, eight lanes
      for (V& b : bj)
        b = zero;
      for (int il = 0; il < 8; ++il) {
        const V rx = one(ci, kCx, il) - lanes(cj, kCx), ry = one(ci, kCy, il) - lanes(cj, kCy),
                rz = one(ci, kCz, il) - lanes(cj, kCz);
        const V r2 = rx * rx + ry * ry + rz * rz,
                hb = bc(0.5) * (one(ci, kCh, il) + lanes(cj, kCh));
        __mmask8 in = _mm512_cmp_pd_mask(r2, hb * hb, _CMP_LT_OQ);
        if (I == J) // each pair of a cluster once
          in &= _mm512_cmp_epi64_mask(lane, _mm512_set1_epi64(il), _MM_CMPINT_GT);
        if (!in)
          continue;
        // Lanes outside: finite stand-ins, then zeros through g, W, Π and the signal.
        const V r2s = blend(in, r2, hb * hb), ih = recip(hb), rinv = rsqrt(r2s), rr = r2s * rinv;
        const V g = blend(in, WideKernel<K>::gradOverR(rr * ih, ih, hb * rinv), zero);
        const V vx = one(ci, kCvx, il) - lanes(cj, kCvx), vy = one(ci, kCvy, il) - lanes(cj, kCvy),
                vz = one(ci, kCvz, il) - lanes(cj, kCvz);
        const V vr = vx * rx + vy * ry + vz * rz;
        const V mu = hb * vr * recip(r2s + bc(0.01) * hb * hb);
        const V csum = one(ci, kCc, il) + lanes(cj, kCc),
                irho = recip(one(ci, kCrho, il) + lanes(cj, kCrho));
        const __mmask8 closing = _mm512_cmp_pd_mask(vr, zero, _CMP_LT_OQ) & in;
        const V pi = blend(closing, (nav * csum * mu + bv2 * mu * mu) * irho, zero);
        const V sgn = blend(closing, csum - bc(3.0) * vr * rinv, zero);
        const V P = one(ci, kCpr, il) + lanes(cj, kCpr) + pi, gs = g * stressOn;
        V t[6];
        for (int k = 0; k < 6; ++k)
          t[k] = one(ci, kCs0 + k, il) + lanes(cj, kCs0 + k);
        const V Fx = -g * P * rx + gs * (t[0] * rx + t[3] * ry + t[4] * rz);
        const V Fy = -g * P * ry + gs * (t[3] * rx + t[1] * ry + t[5] * rz);
        const V Fz = -g * P * rz + gs * (t[4] * rx + t[5] * ry + t[2] * rz);
        const V gvr = g * vr, hpi = bc(0.5) * pi;
        const V q[6] = {vx * rx,           vy * ry,          vz * rz, vx * ry + vy * rx,
                        vx * rz + vz * rx, vy * rz + vz * ry}; // v ⊗ r against a symmetric tensor
        V sI = zero, sJ = zero;
        for (int k = 0; k < 6; ++k)
          sI += one(ci, kCs0 + k, il) * q[k], sJ += lanes(cj, kCs0 + k) * q[k];
        const V eI = gvr * (one(ci, kCpr, il) + hpi) - gs * sI,
                eJ = gvr * (lanes(cj, kCpr) + hpi) - gs * sJ;
        const V gx = g * vx, gy = g * vy, gz = g * vz;
        const V G[9] = {gx * rx, gx * ry, gx * rz, gy * rx, gy * ry,
                        gy * rz, gz * rx, gz * ry, gz * rz};
        const V mj = lanes(cj, kCm), mi = one(ci, kCm, il), volj = lanes(cj, kCvol),
                voli = one(ci, kCvol, il);
        V* a = ai[il];
        a[0] += mj * Fx, a[1] += mj * Fy, a[2] += mj * Fz, a[3] += mj * gvr, a[4] += mj * eI;
        bj[0] -= mi * Fx, bj[1] -= mi * Fy, bj[2] -= mi * Fz, bj[3] += mi * gvr, bj[4] += mi * eJ;
        for (int k = 0; k < 9; ++k)
          a[5 + k] -= volj * G[k], bj[5 + k] -= voli * G[k];
        if constexpr (Xsph) {
          const V w = blend(in, xsph2 * irho * WideKernel<K>::value(rr * ih, ih), zero);
          const V wx = w * vx, wy = w * vy, wz = w * vz;
          a[14] -= mj * wx, a[15] -= mj * wy, a[16] -= mj * wz;
          bj[14] += mi * wx, bj[15] += mi * wy, bj[16] += mi * wz;
        }
        a[17] = _mm512_max_pd(a[17], sgn), bj[17] = _mm512_max_pd(bj[17], sgn);
      }
      double* to = &sums[J].a[0][0];
      for (int k = 0; k < kClusterSums - 1; ++k)
        _mm512_store_pd(to + 8 * k, _mm512_load_pd(to + 8 * k) + bj[k]);
      _mm512_store_pd(to + 8 * 17, _mm512_max_pd(_mm512_load_pd(to + 8 * 17), bj[17]));
    }
    ClusterSums& own = sums[I];
    for (int l = 0; l < 8; ++l) {
      for (int k = 0; k < kClusterSums - 1; ++k)
        own.a[k][l] += _mm512_reduce_add_pd(ai[l][k]);
      own.a[17][l] = std::max(own.a[17][l], _mm512_reduce_max_pd(ai[l][17]));
    }
  }
}
} // namespace

template <class K, bool Xsph>
void clusterPairSums(const ClusterBlock* blocks, const std::uint32_t* start,
                     const std::uint32_t* partner, std::uint32_t first, std::uint32_t last,
                     ClusterSums* sums, const PairConstants& pc) {
  sumsAvx512<K, Xsph>(blocks, start, partner, first, last, sums, pc);
}
#else
template <class K, bool Xsph>
void clusterPairSums(const ClusterBlock*, const std::uint32_t*, const std::uint32_t*, std::uint32_t,
                     std::uint32_t, ClusterSums*, const PairConstants&) {
  throw std::logic_error("SPH: the AVX-512 cluster kernel is not in this build");
}
#endif

#define CK_CLUSTER_SUMS(K, X)                                                                      \
  template void clusterPairSums<K, X>(const ClusterBlock*, const std::uint32_t*,                   \
                                      const std::uint32_t*, std::uint32_t, std::uint32_t,          \
                                      ClusterSums*, const PairConstants&);
CK_CLUSTER_SUMS(CubicSpline, false)
CK_CLUSTER_SUMS(CubicSpline, true)
CK_CLUSTER_SUMS(WendlandC2, false)
CK_CLUSTER_SUMS(WendlandC2, true)
#undef CK_CLUSTER_SUMS

} // namespace craterkit

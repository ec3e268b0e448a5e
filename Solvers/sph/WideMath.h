// AVX-512 arithmetic shared by the SPH pair loops (PairTermsWide.cpp: a particle against its
// kept neighbours; ClusterPairsWide.cpp: a particle against a cluster of eight): eight-lane
// helpers, the branch-free kernels, and reciprocals without the divider.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#define CK_WIDE_PAIRS 1
#include <immintrin.h>
// GCC 12's AVX-512 headers start some intrinsics from an undefined vector on purpose.
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#ifdef CK_WIDE_PAIRS
#include "sph/Kernels.h"

#define CK_WIDE __attribute__((target("avx512f,avx512dq,avx512vl,avx2,fma")))

namespace craterkit::wide {
using V = __m512d;

CK_WIDE inline V bc(double a) { return _mm512_set1_pd(a); }
// a < b ? x : y, lane by lane
CK_WIDE inline V selectLess(V a, V b, V x, V y) {
  return _mm512_mask_blend_pd(_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ), y, x);
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

} // namespace craterkit::wide
#endif

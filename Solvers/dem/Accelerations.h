// The DEM's accelerations from a particle's summed force and torque (Newton-Euler for a sphere:
// a = F/m + g, alpha = T/I; Schwartz, Richardson & Michel 2012, §2.3).
//
// Six divisions per particle and step (7 % of the force gather's samples at commit 7828800,
// benchmarks/JOURNAL.md) run two at a time (SSE2 is part of every x86-64), so that they do
// not wait for each other. Each quotient is the correctly rounded one, as the scalar
// division's: the same bits.
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace craterkit {

inline void sphereAccelerations(const double f[3], const double t[3], double m, double inertia,
                                const double g[3], double a[3], double alpha[3]) {
#if defined(__SSE2__)
  double q[6];
  _mm_storeu_pd(q, _mm_div_pd(_mm_set_pd(f[1], f[0]), _mm_set1_pd(m)));
  _mm_storeu_pd(q + 2, _mm_div_pd(_mm_set_pd(t[0], f[2]), _mm_set_pd(inertia, m)));
  _mm_storeu_pd(q + 4, _mm_div_pd(_mm_set_pd(t[2], t[1]), _mm_set1_pd(inertia)));
  for (int k = 0; k < 3; ++k) {
    a[k] = q[k] + g[k];
    alpha[k] = q[3 + k];
  }
#else
  for (int k = 0; k < 3; ++k) {
    a[k] = f[k] / m + g[k];
    alpha[k] = t[k] / inertia;
  }
#endif
}

} // namespace craterkit

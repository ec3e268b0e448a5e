#include "bonded/BondedForces.h"

#include "common/SimdClones.h"

#include <algorithm>

namespace craterkit {
namespace bondedpass {

namespace {

// The pass over the wide (kCompact false) or the compact lists; inlined into each clone of
// blockForces, so that it is compiled for the clone's target.
template <bool kCompact> __attribute__((always_inline)) inline long
passOf(const BlockPass& p, std::size_t b0, std::size_t b1) {
  constexpr std::size_t L = kLanes;
  const double* x = p.x;
  const ws2017::PairTerms terms = p.terms;
  const double rCut2 = p.rCut2, restRef = p.restRef;
  long total = 0;
  for (std::size_t b = b0; b < b1; ++b) {
    double xi[L], yi[L], zi[L], fx[L], fy[L], fz[L];
    for (std::size_t l = 0; l < L; ++l) {
      const std::size_t i = std::min(p.n - 1, b * L + l);
      xi[l] = x[3 * i], yi[l] = x[3 * i + 1], zi[l] = x[3 * i + 2];
      fx[l] = fy[l] = fz[l] = 0.0;
    }
    std::uint32_t broke = 0;
    for (std::size_t e = p.blockStart[b]; e < p.blockStart[b + 1]; e += L) {
      const std::uint32_t* J = p.partner + e;
      double* R0 = kCompact ? nullptr : p.rest + e;
      float* O = kCompact ? p.offset + e : nullptr;
#pragma omp simd reduction(+ : broke)
      for (std::size_t l = 0; l < L; ++l) {
        const std::size_t j = J[l];
        const double dx = xi[l] - x[3 * j], dy = yi[l] - x[3 * j + 1], dz = zi[l] - x[3 * j + 2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double r0 = kCompact ? restRef + static_cast<double>(O[l]) : R0[l];
        const bool breaks = (r0 < kNoBond) & (r2 > rCut2); // Section 2.2.2: for good
        const double f = ws2017::pairForceOverR(r2, breaks ? kNoBond : r0, terms);
        if (breaks) {
          if constexpr (kCompact)
            O[l] = kBreakingOffset;
          else
            R0[l] = kBreaking;
        }
        broke += breaks;
        fx[l] += f * dx;
        fy[l] += f * dy;
        fz[l] += f * dz;
      }
    }
    p.breaks[b] = broke;
    total += broke;
    const std::size_t lanes = std::min(L, p.n - b * L);
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::size_t i = b * L + l;
      double* f = p.force + 3 * i;
      f[0] = fx[l], f[1] = fy[l], f[2] = fz[l];
      if (p.v) {
        const double h = p.halfStep / p.m[i];
        for (int k = 0; k < 3; ++k)
          p.v[3 * i + k] += h * f[k];
      }
    }
  }
  return total;
}

} // namespace

// Cloned (common/SimdClones.h) for x86-64-v4, whose clone's operations BondedForcesAvx512.cpp
// repeats; where the processor has x86-64-v4 and the build has that file (GCC 12+), the
// solver runs it instead. The clone serves builds without it.
CK_SIMD_CLONES long blockForces(const BlockPass& p, std::size_t b0, std::size_t b1) {
  return p.rest ? passOf<false>(p, b0, b1) : passOf<true>(p, b0, b1);
}

std::size_t nearCandidates(const NearScan& s, std::size_t begin, std::size_t end,
                           const double xi[3], std::uint32_t self, std::uint32_t* out) {
  std::size_t count = 0;
  for (std::size_t k = begin; k < end; ++k) {
    const double dx = s.x[k] - xi[0], dy = s.y[k] - xi[1], dz = s.z[k] - xi[2];
    out[count] = s.id[k];
    count += (dx * dx + dy * dy + dz * dz < s.reach2) & (s.id[k] != self);
  }
  return count;
}

} // namespace bondedpass
} // namespace craterkit

// The cluster-pair kernel (sph/ClusterPairs.h), each pair once, against the per-particle pair
// loop (sph/PairTerms.h) that computes every pair from both sides: the same sums to rounding,
// the same bits on one and two threads, and the fallback where a body is too short for slabs.
#include "sph/ClusterPairs.h"
#include "sph/Kernels.h"
#include "sph/NeighbourList.h"
#include "sph/SupportList.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using namespace craterkit;

namespace {
struct Body {
  std::vector<PairPosition> pos;
  std::vector<PairRecord> rec;
  std::vector<std::vector<std::uint32_t>> verlet; // every pair within 1.3 max h
};

// A jittered lattice of nx × ny × nz sites of spacing 1, h from 2.1 to 2.3, random velocities
// (some closing pairs: artificial viscosity), densities, pressures and stresses.
Body makeBody(int nx, int ny, int nz, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Body b;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        PairPosition p;
        PairRecord r{};
        p.x[0] = i + 0.1 * u(rng), p.x[1] = j + 0.1 * u(rng), p.x[2] = k + 0.1 * u(rng);
        p.h = r.h = 2.2 + 0.1 * u(rng);
        for (double& v : r.v)
          v = 50.0 * u(rng);
        r.rho = 2000.0 + 500.0 * u(rng), r.m = 2000.0 * (1.0 + 0.2 * u(rng)), r.vol = r.m / r.rho;
        r.pr = 1e9 * (1.0 + u(rng)) / (r.rho * r.rho), r.c = 3000.0 + 500.0 * u(rng);
        for (double& s : r.s)
          s = 1e8 * u(rng) / (r.rho * r.rho);
        b.pos.push_back(p), b.rec.push_back(r);
      }
  const std::size_t n = b.pos.size();
  b.verlet.resize(n);
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t c = 0; c < n; ++c) {
      double r2 = 0.0;
      for (int k = 0; k < 3; ++k)
        r2 += (b.pos[a].x[k] - b.pos[c].x[k]) * (b.pos[a].x[k] - b.pos[c].x[k]);
      if (c != a && r2 < 1.69 * 2.3 * 2.3)
        b.verlet[a].push_back(c * 32 + kNoShift);
    }
  return b;
}

SupportList supportOf(const Body& b) {
  SupportList list;
  const double none[3] = {0.0, 0.0, 0.0};
  list.follow(b.pos.data(), b.pos.size(), 1, none,
              [&](std::size_t a, const std::uint32_t*& e, std::uint32_t& m) {
                e = b.verlet[a].data(), m = static_cast<std::uint32_t>(b.verlet[a].size());
              });
  return list;
}

std::vector<double> flat(const PairSums& s) {
  std::vector<double> v(s.acc, s.acc + 3);
  v.push_back(s.dr), v.push_back(s.de);
  v.insert(v.end(), s.grad, s.grad + 9);
  v.insert(v.end(), s.xs, s.xs + 3);
  v.push_back(s.sig);
  return v;
}

template <class K, bool Xsph> void expectTheTwoSidedSums(const Body& b) {
  const std::size_t n = b.pos.size();
  const SupportList list = supportOf(b);
  ClusterPairs clusters;
  ASSERT_TRUE(clusters.follow(b.pos.data(), n, list));
  PairConstants pc{1.0, 1.5, Xsph ? 0.5 : 0.0, 1.0, 1.0, 1.0, false, {0.0, 0.0, 0.0}};
  clusters.evaluate<K, Xsph>(b.rec.data(), b.pos.data(), pc);
  std::vector<std::vector<double>> ref(n), got(n);
  std::vector<double> scale(18, 0.0);
  PairScratch w;
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::size_t m = supportStreamWide(b.pos.data(), a, list.entries(a), list.count(a), w);
    ref[a] = flat(pairSumsWide<K, Xsph>(b.rec.data(), b.rec[a], m, w, pc));
    got[a] = flat(clusters.of(a));
    for (int k = 0; k < 18; ++k)
      scale[k] = std::max(scale[k], std::abs(ref[a][k]));
  }
  // The sums of about 30 pairs in another order: the difference is rounding, far below 1e-11
  // of the largest sum of each kind (a missing or doubled pair would be of order 1e-2).
  for (std::size_t a = 0; a < n; ++a)
    for (int k = 0; k < 18; ++k)
      ASSERT_NEAR(got[a][k], ref[a][k], 1e-11 * scale[k] + 1e-300)
          << "particle " << a << ", sum " << k;
}
} // namespace

TEST(SphClusterPairs, EachPairOnceGivesTheTwoSidedSums) {
  if (!wideKernelAvailable())
    GTEST_SKIP() << "no AVX-512 on this processor";
  const Body b = makeBody(26, 9, 7, 3); // 1,638 particles: not a multiple of eight
  expectTheTwoSidedSums<WendlandC2, true>(b);
  expectTheTwoSidedSums<CubicSpline, false>(b);
}

TEST(SphClusterPairs, SameBitsOnOneAndTwoThreads) {
  if (!wideKernelAvailable())
    GTEST_SKIP() << "no AVX-512 on this processor";
  const Body b = makeBody(40, 8, 8, 5);
  const std::size_t n = b.pos.size();
  const SupportList list = supportOf(b);
  const PairConstants pc{1.0, 1.5, 0.5, 1.0, 1.0, 1.0, false, {0.0, 0.0, 0.0}};
  std::vector<std::vector<double>> run[2];
  const int before = omp_get_max_threads();
  for (int t = 0; t < 2; ++t) {
    omp_set_num_threads(t + 1);
    ClusterPairs clusters;
    ASSERT_TRUE(clusters.follow(b.pos.data(), n, list));
    clusters.evaluate<WendlandC2, true>(b.rec.data(), b.pos.data(), pc);
    for (std::size_t a = 0; a < n; ++a)
      run[t].push_back(flat(clusters.of(a)));
  }
  omp_set_num_threads(before);
  for (std::size_t a = 0; a < n; ++a)
    ASSERT_EQ(0, std::memcmp(run[0][a].data(), run[1][a].data(), 18 * sizeof(double)))
        << "particle " << a;
}

TEST(SphClusterPairs, ABodyShorterThanFourSlabsIsLeftToThePerParticleLoop) {
  const Body b = makeBody(9, 9, 9, 7); // 9 sites: three slabs of 2.53
  const SupportList list = supportOf(b);
  ClusterPairs clusters;
  EXPECT_FALSE(clusters.follow(b.pos.data(), b.pos.size(), list));
}

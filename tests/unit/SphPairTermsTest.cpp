// The AVX-512 SPH pair loop (sph/PairTerms.h) against the same terms evaluated pair by pair in
// plain scalar code: the support pass keeps exactly the listed neighbours inside ½(h_a + h_b),
// in list order, and the vector sums equal the scalar sums to rounding.
#include "sph/Kernels.h"
#include "sph/NeighbourList.h"
#include "sph/PairTerms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace craterkit;

namespace {
struct Cloud {
  std::vector<PairPosition> pos;
  std::vector<PairRecord> rec;
  std::vector<std::uint32_t> entries; // every other particle, in a shuffled order
};

// n particles in a unit cube with h from 0.2 to 0.5 (so that some pairs are in and some out),
// random velocities, densities, pressures and stresses; particle `self` lists all others.
Cloud makeCloud(std::size_t n, std::uint32_t self, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Cloud c;
  c.pos.resize(n);
  c.rec.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    PairPosition& p = c.pos[i];
    PairRecord& r = c.rec[i];
    for (int k = 0; k < 3; ++k)
      p.x[k] = u(rng), r.v[k] = 100.0 * (u(rng) - 0.5);
    p.h = r.h = 0.2 + 0.3 * u(rng);
    r.rho = 1000.0 + 2000.0 * u(rng), r.m = 0.5 + u(rng), r.vol = r.m / r.rho;
    r.pr = 1e9 * u(rng) / (r.rho * r.rho), r.c = 1000.0 + 3000.0 * u(rng);
    for (double& s : r.s)
      s = 1e8 * (u(rng) - 0.5) / (r.rho * r.rho);
    r.rigid = i % 3 == 0 ? 1.0 : 0.0; // some walls: the viscosity's wall factor acts
  }
  for (std::uint32_t b = 0; b < n; ++b)
    if (b != self)
      c.entries.push_back(b * 32 + kNoShift);
  std::shuffle(c.entries.begin(), c.entries.end(), rng);
  return c;
}
} // namespace

TEST(SphPairTerms, WideSupportPassKeepsThePairsInsideTheSupportInListOrder) {
  if (!wideKernelAvailable())
    GTEST_SKIP() << "no AVX-512 on this processor";
  for (std::uint32_t count : {0u, 1u, 7u, 8u, 13u, 299u}) {
    const std::uint32_t self = 3;
    const Cloud c = makeCloud(300, self, 7 + count);
    PairScratch w;
    const std::size_t m = supportStreamWide(c.pos.data(), self, c.entries.data(), count, w);
    const PairPosition& A = c.pos[self];
    std::size_t kept = 0;
    for (std::uint32_t k = 0; k < count; ++k) {
      const PairPosition& B = c.pos[c.entries[k] >> 5];
      const double rx = A.x[0] - B.x[0], ry = A.x[1] - B.x[1], rz = A.x[2] - B.x[2];
      const double r2 = rx * rx + ry * ry + rz * rz, hb = 0.5 * (A.h + B.h);
      if (!(r2 < hb * hb))
        continue;
      ASSERT_LT(kept, m);
      EXPECT_EQ(w.idx[kept], c.entries[k] >> 5);
      EXPECT_EQ(w.rx[kept], rx); // one subtraction each: exact
      EXPECT_EQ(w.ry[kept], ry);
      EXPECT_EQ(w.rz[kept], rz);
      EXPECT_NEAR(w.r2[kept], r2, 1e-15 * r2); // may be fused: one rounding apart
      ++kept;
    }
    if (count > 50)
      EXPECT_GT(kept, 20u) << "the test needs pairs inside the support";
    // padded to whole vectors with the particle itself at r² = (h/2)²
    EXPECT_EQ(m, (kept + kPairLanes - 1) / kPairLanes * kPairLanes);
    for (std::size_t k = kept; k < m; ++k) {
      EXPECT_EQ(w.idx[k], self);
      EXPECT_EQ(w.rx[k], 0.0);
      EXPECT_EQ(w.r2[k], 0.25 * A.h * A.h);
    }
  }
}

namespace {
// The pair terms of SphSolver.cpp (docs/physics.md §2.2, §2.3), one pair at a time.
template <class K> PairSums scalarSums(const Cloud& c, std::uint32_t self, const PairScratch& w,
                                       std::size_t m, const PairConstants& pc) {
  const PairRecord& A = c.rec[self];
  PairSums s{};
  for (std::size_t k = 0; k < m; ++k) {
    const PairRecord& B = c.rec[w.idx[k]];
    const double rx = w.rx[k], ry = w.ry[k], rz = w.rz[k], r2 = w.r2[k];
    const double hb = 0.5 * (A.h + B.h), rr = std::sqrt(r2);
    const double g = K::dWdr(rr, hb) / rr;
    const double vx = A.v[0] - B.v[0], vy = A.v[1] - B.v[1], vz = A.v[2] - B.v[2];
    const double vr = vx * rx + vy * ry + vz * rz;
    const double mu = hb * vr / (r2 + 0.01 * hb * hb);
    const double wall = A.rigid != B.rigid ? pc.wallViscosity : 1.0;
    const double pi =
        vr < 0.0 ? wall * (-pc.av * (A.c + B.c) * mu + 2.0 * pc.bv * mu * mu) / (A.rho + B.rho)
                 : 0.0;
    if (vr < 0.0)
      s.sig = std::max(s.sig, A.c + B.c - 3.0 * vr / rr);
    const double mg = B.m * g, f = mg * (A.pr + B.pr + pi);
    double t[6];
    for (int j = 0; j < 6; ++j)
      t[j] = A.s[j] + B.s[j];
    s.acc[0] += -f * rx + mg * (t[0] * rx + t[3] * ry + t[4] * rz);
    s.acc[1] += -f * ry + mg * (t[3] * rx + t[1] * ry + t[5] * rz);
    s.acc[2] += -f * rz + mg * (t[4] * rx + t[5] * ry + t[2] * rz);
    s.dr += mg * vr;
    const double* a = A.s;
    s.de += mg * (A.pr + 0.5 * pi) * vr -
            mg * (a[0] * vx * rx + a[1] * vy * ry + a[2] * vz * rz + a[3] * (vx * ry + vy * rx) +
                  a[4] * (vx * rz + vz * rx) + a[5] * (vy * rz + vz * ry));
    const double v[3] = {vx, vy, vz}, r[3] = {rx, ry, rz};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s.grad[3 * i + j] -= B.vol * g * v[i] * r[j];
    const double wx = pc.xsph * B.m / (0.5 * (A.rho + B.rho)) * K::W(rr, hb);
    for (int i = 0; i < 3; ++i)
      s.xs[i] -= wx * v[i];
  }
  return s;
}

template <class K> void expectWideEqualsScalar() {
  const std::uint32_t self = 11;
  const Cloud c = makeCloud(400, self, 2024);
  PairScratch w;
  const std::size_t m = supportStreamWide(c.pos.data(), self, c.entries.data(),
                                          static_cast<std::uint32_t>(c.entries.size()), w);
  ASSERT_GE(m, 24u); // a few vectors of pairs
  const PairConstants pc{1.0, 1.5, 0.5, 1.0, 1.0, 0.25, false, {0.0, 0.0, 0.0}};
  const PairSums wide = pairSumsWide<K, true>(c.rec.data(), c.rec[self], m, w, pc);
  const PairSums ref = scalarSums<K>(c, self, w, m, pc);
  // The two differ by rounding only (fused multiply-adds, reciprocals from Newton steps, the
  // order of the lane sums): 1e-11 of the sum's scale, for terms of mixed signs.
  const auto near = [](double a, double b, const char* what) {
    EXPECT_NEAR(a, b, 1e-11 * std::max(std::abs(b), 1e-30)) << what;
  };
  for (int k = 0; k < 3; ++k)
    near(wide.acc[k], ref.acc[k], "acceleration"), near(wide.xs[k], ref.xs[k], "XSPH");
  near(wide.dr, ref.dr, "dρ/dt");
  near(wide.de, ref.de, "du/dt");
  for (int k = 0; k < 9; ++k)
    near(wide.grad[k], ref.grad[k], "velocity gradient");
  near(wide.sig, ref.sig, "signal speed");
  EXPECT_GT(ref.sig, 0.0);
}
} // namespace

TEST(SphPairTerms, WidePairSumsEqualTheTermsSummedPairByPair) {
  if (!wideKernelAvailable())
    GTEST_SKIP() << "no AVX-512 on this processor";
  expectWideEqualsScalar<CubicSpline>();
  expectWideEqualsScalar<WendlandC2>();
}

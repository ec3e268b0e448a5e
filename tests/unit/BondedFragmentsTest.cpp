// The debris-cloud measures of Solvers/bonded/BondedFragments against clouds whose answer is
// known: spheroids (filled and hollow) of given semi-axes with stray particles, where the
// mass-quantile R must be the spheroid's a / b, and a ballistic cloud, where the leading
// edge's axial velocity must be the rate at which the leading edge advances.

#include "bonded/BondedFragments.h"
#include "common/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace craterkit;

namespace {

struct Cloud {
  std::vector<double> x, v, m;
  void add(double px, double py, double pz, double vx = 0.0, double vy = 0.0, double vz = 0.0) {
    x.insert(x.end(), {px, py, pz});
    v.insert(v.end(), {vx, vy, vz});
    m.push_back(1.0);
  }
};

// n points uniform in the spherical shell inner < |u| < 1 (inner = 0: the filled ball).
std::vector<double> ballPoints(std::size_t n, double inner, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> c(-1.0, 1.0);
  std::vector<double> u;
  while (u.size() < 3 * n) {
    const double p[3] = {c(rng), c(rng), c(rng)};
    const double r2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    if (r2 < 1.0 && r2 >= inner * inner)
      u.insert(u.end(), p, p + 3);
  }
  return u;
}

BondedFragmentResult measure(const Cloud& c, double fraction, double v0 = 0.0) {
  DebrisCloudParams p;
  p.cloudStart = 0.0;
  p.impactSpeed = v0;
  p.massFraction = fraction;
  return analyseBondedFragments(c.x, c.v, c.m, {}, {}, p);
}

} // namespace

// A spheroid stretched from a ball (density a function of (s/a)² + (ρ/b)²: filled, and a thin
// shell like the paper's debris bubble) has R = a / b = 1.55 whatever the fraction f (the
// header's argument). Estimated from 20,000 particles: the 2.5 % and 97.5 % mass quantiles
// of the axial coordinate scatter by sqrt(q(1−q)/N) / pdf ≈ 0.5 % of their value (filled:
// pdf 0.26 / a at 0.81 a), the 0.1 % of the mass in stray particles shifts them by as much
// again, so R within 2 %. The max − min envelope (f = 1) is set by the strays instead.
TEST(BondedFragments, SpheroidWithStrayParticlesGivesItsAxisRatio) {
  const double a = 1.55e-2, b = 1.0e-2, centre = 0.05; // m; the cloud past the face at 0
  for (double inner : {0.0, 0.9}) {
    const std::vector<double> u = ballPoints(20000, inner, inner > 0.0 ? 7u : 3u);
    Cloud c;
    for (std::size_t i = 0; i < u.size() / 3; ++i)
      c.add(centre + a * u[3 * i], b * u[3 * i + 1], b * u[3 * i + 2]);
    for (int k = 0; k < 10; ++k) { // stray single particles: far ahead, and far to the side
      c.add(centre + 4.0 * a + 0.001 * k, 0.0, 0.0);
      c.add(centre, 0.0, 3.0 * b + 0.001 * k);
    }
    for (double f : {0.9, 0.95, 0.99}) {
      const BondedFragmentResult r = measure(c, f);
      std::printf("[bonded] spheroid (inner %.1f), f = %.2f: L_a %.4g m, L_r %.4g m, R %.4f\n",
                  inner, f, r.axialLength, r.radialExtent, r.ratio);
      EXPECT_NEAR(r.ratio, a / b, 0.02 * a / b) << "inner " << inner << ", f " << f;
      EXPECT_EQ(r.cloudParticles, c.m.size());
    }
    const BondedFragmentResult all = measure(c, 1.0);
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < c.m.size(); ++i)
      lo = std::min(lo, c.x[3 * i]), hi = std::max(hi, c.x[3 * i]);
    EXPECT_DOUBLE_EQ(all.axialLength, hi - lo); // f = 1: the envelope, max − min
    EXPECT_GT(std::fabs(all.ratio - a / b), 0.1 * a / b);
  }
}

// A ballistic cloud: every particle left one point x0 at t = 0 with its own velocity, so
// x_i = x0 + v_i t. Its leading edge then sits at s0 + v_a t for the measured v_a (the order
// in s is the order in v_x), which is therefore exactly the front's displacement between two
// snapshots over their interval, Section 3.1's measure; a few stray fast particles do not
// change it by more than their share of the mass.
TEST(BondedFragments, BallisticCloudFrontMovesAtTheMeasuredAxialVelocity) {
  const double v0 = 6700.0, x0 = 1e-3;
  const std::vector<double> u = ballPoints(5000, 0.0, 11u);
  auto cloudAt = [&](double t, bool strays) {
    Cloud c;
    for (std::size_t i = 0; i < u.size() / 3; ++i) {
      const double vx = 0.6 * v0 + 0.25 * v0 * u[3 * i], vy = 0.2 * v0 * u[3 * i + 1],
                   vz = 0.2 * v0 * u[3 * i + 2];
      c.add(x0 + vx * t, vy * t, vz * t, vx, vy, vz);
    }
    for (int k = 0; strays && k < 5; ++k) // faster than the impact
      c.add(x0 + 1.3 * v0 * t, 0.0, 0.0, 1.3 * v0, 0.0, 0.0);
    return c;
  };
  const double t1 = 20e-6, t2 = 32e-6;
  const BondedFragmentResult r1 = measure(cloudAt(t1, true), 0.95, v0);
  const BondedFragmentResult r2 = measure(cloudAt(t2, true), 0.95, v0);
  EXPECT_NEAR(r2.axialVelocity, (r2.leadingEdge - x0) / t2, 1e-12 * v0);
  EXPECT_NEAR(r2.axialVelocity, (r2.leadingEdge - r1.leadingEdge) / (t2 - t1), 1e-9 * v0);
  EXPECT_DOUBLE_EQ(r2.axialVelocityRatio, r2.axialVelocity / v0);
  // Without the strays: the 97.5 % quantile moves by at most their 0.1 % of the mass,
  // 0.001 / pdf(0.81) ≈ 0.004 of the 0.25 v0 half-width.
  const BondedFragmentResult clean = measure(cloudAt(t2, false), 0.95, v0);
  EXPECT_NEAR(r2.axialVelocity, clean.axialVelocity, 0.01 * 0.25 * v0);
  EXPECT_LT(r2.axialVelocityRatio, 1.0);
  EXPECT_NEAR(measure(cloudAt(t2, true), 1.0, v0).axialVelocityRatio, 1.3, 1e-12);
}

// A fragment still bonded to material at or before the rear face (a petal of the plate) is
// not debris; the mass fraction must lie in (0, 1].
TEST(BondedFragments, CloudLeavesOutPlateMaterialAndRefusesBadFractions) {
  Cloud c;
  c.add(1.0, 0.0, 0.0);  // 0: debris
  c.add(2.0, 0.0, 0.0);  // 1: debris
  c.add(-1.0, 0.0, 0.0); // 2: the plate
  c.add(0.5, 3.0, 0.0);  // 3: past the face, bonded to the plate
  const std::vector<BondedBond> bonds = {{2, 3, 1.0}, {0, 1, 1.0}};
  DebrisCloudParams p;
  p.massFraction = 1.0;
  const BondedFragmentResult r = analyseBondedFragments(c.x, c.v, c.m, bonds, {}, p);
  EXPECT_EQ(r.cloudParticles, 2u);
  EXPECT_EQ(r.cloudFragments, 1u);
  EXPECT_DOUBLE_EQ(r.largestCloudFragmentMass, 2.0);
  EXPECT_DOUBLE_EQ(r.axialLength, 1.0);
  for (double bad : {0.0, -0.5, 1.5, std::nan("")}) {
    p.massFraction = bad;
    try {
      analyseBondedFragments(c.x, c.v, c.m, bonds, {}, p);
      ADD_FAILURE() << "fraction " << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("CloudMassFraction"), std::string::npos);
    }
  }
}

// The front width w_f = Q_s(0.99) − Q_s(0.90) on clouds whose quantiles are known exactly:
// n equal masses at s = k/n (k = 1..n) along the axis, a uniform slab, has Q_s(q) = ⌈q n⌉ / n,
// so w_f = 0.09 and L_a (f = 0.95) = 0.95 − 0.025 + 1/n. Putting the leading 10 % into a thin
// sheet (a sharp front, all of it within 0.01 of the slab's end) shrinks w_f to that sheet's
// depth; spreading it over a tail twice as long widens it: the measure orders the fronts as a
// photograph would.
TEST(BondedFragments, FrontWidthIsTheLeadingTenthOfTheMassLessItsLastHundredth) {
  const std::size_t n = 10000;
  // The first 90 % uniform on (0, 0.9], the rest uniform on (0.9, 0.9 + depth].
  auto slab = [&](double frontDepth) {
    Cloud c;
    for (std::size_t k = 1; k <= n; ++k) {
      const double q = static_cast<double>(k) / n;
      c.add(q <= 0.9 ? q : 0.9 + (q - 0.9) / 0.1 * frontDepth, 0.0, 0.0);
    }
    return measure(c, 0.95);
  };
  const BondedFragmentResult uniform = slab(0.1), sharp = slab(0.01), diffuse = slab(0.2);
  std::printf("[bonded] front width: uniform %.5f (L_a %.5f), sharp %.5f, diffuse %.5f\n",
              uniform.frontWidth, uniform.axialLength, sharp.frontWidth, diffuse.frontWidth);
  const double step = 2.0 / n; // a quantile is a particle's position: q n may round to the next
  EXPECT_NEAR(uniform.frontWidth, 0.09, step);
  EXPECT_NEAR(uniform.axialLength, 0.975 - 0.025, step);
  EXPECT_NEAR(sharp.frontWidth, 0.009, step);        // 0.9 of the sheet's 0.01
  EXPECT_NEAR(diffuse.frontWidth, 0.18, 2.0 * step); // 0.9 of the tail's 0.2
}

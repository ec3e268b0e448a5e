// CraterProfile on a synthetic crater built from particles: a paraboloid bowl with a raised
// Gaussian rim, whose diameter, rim diameter and depth are known; isolated ejecta above the
// surface must not change the result.
#include "analysis/CraterProfile.h"
#include "common/Error.h"
#include "common/Random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace craterkit;

namespace {
constexpr double kZ0 = 0.0, kRc = 2.0, kDepth = 0.6, kRimR = 2.5, kRimW = 0.5, kRimH = 0.3,
                 kRp = 0.05;

double surface(double r) {
  double z = kZ0 + kRimH * std::exp(-(r - kRimR) * (r - kRimR) / (kRimW * kRimW));
  if (r < kRc)
    z -= kDepth * (1.0 - r * r / (kRc * kRc));
  return z;
}

// The true measures, from the analytic surface sampled finely.
CraterMeasures truth() {
  std::vector<double> r, h;
  for (double x = 0.0005; x < 5.0; x += 0.001)
    r.push_back(x), h.push_back(surface(x));
  return measureProfile(r, h, kZ0);
}

void crater(std::vector<double>& x, std::vector<double>& rad) {
  const double d = 2.0 * kRp;
  for (double px = -5.0 + kRp; px < 5.0; px += d)
    for (double py = -5.0 + kRp; py < 5.0; py += d) {
      const double r = std::hypot(px, py);
      if (r > 5.0)
        continue;
      const double top = surface(r);
      for (double pz = -1.5 + kRp; pz + kRp <= top; pz += d) {
        x.insert(x.end(), {px, py, pz});
        rad.push_back(kRp);
      }
    }
}
} // namespace

TEST(CraterProfile, RecoversTheDimensionsOfASyntheticCrater) {
  std::vector<double> x, rad;
  crater(x, rad);
  CraterProfileParams par;
  par.maxRadius = 4.5;
  const CraterProfileResult a = craterProfile(x, rad, par);
  const CraterMeasures t = truth();
  // Isolated ejecta far above the surface.
  Random rng(7);
  for (int k = 0; k < 200; ++k) {
    const double r = rng.uniform(0.0, 4.0), phi = rng.uniform(0.0, 2.0 * M_PI);
    x.insert(x.end(), {r * std::cos(phi), r * std::sin(phi), rng.uniform(0.8, 3.0)});
    rad.push_back(kRp);
  }
  const CraterProfileResult b = craterProfile(x, rad, par);
  std::printf("synthetic crater, %zu particles: diameter %.3f (true %.3f), rim diameter %.3f "
              "(%.3f), depth %.3f (%.3f), "
              "rim height %.3f (%.3f), volume %.3f (%.3f) m3; with 200 ejecta: %.3f, %.3f, %.3f "
              "(%zu rejected)\n",
              rad.size() - 200, a.all.diameter, t.diameter, a.all.rimDiameter, t.rimDiameter,
              a.all.depth, t.depth, a.all.rimHeight, t.rimHeight, a.all.volume, t.volume,
              b.all.diameter, b.all.rimDiameter, b.all.depth, b.rejectedAsEjecta);
  const double dp = 2.0 * kRp; // one particle diameter
  ASSERT_TRUE(a.all.found);
  EXPECT_NEAR(a.all.diameter, t.diameter, dp);
  EXPECT_NEAR(a.all.rimDiameter, t.rimDiameter, dp);
  EXPECT_NEAR(a.all.depth, t.depth, dp);
  // Volume: the surface of particles is within one diameter of the true one everywhere.
  EXPECT_NEAR(a.all.volume, t.volume, M_PI * 0.25 * t.diameter * t.diameter * dp);
  for (const CraterMeasures* side : {&a.negativeHalf, &a.positiveHalf}) {
    EXPECT_NEAR(side->diameter, t.diameter, dp);
    EXPECT_NEAR(side->depth, t.depth, dp);
  }
  EXPECT_EQ(b.rejectedAsEjecta, 200u);
  EXPECT_DOUBLE_EQ(b.all.diameter, a.all.diameter);
  EXPECT_DOUBLE_EQ(b.all.rimDiameter, a.all.rimDiameter);
  EXPECT_DOUBLE_EQ(b.all.depth, a.all.depth);
  EXPECT_FALSE(a.slab.empty());
}

TEST(CraterProfile, FlatBedHasNoCraterAndBadInputIsNamed) {
  std::vector<double> x, rad;
  for (double px = -2.0; px < 2.0; px += 0.1)
    for (double py = -2.0; py < 2.0; py += 0.1)
      for (double pz = -0.45; pz < 0.0; pz += 0.1)
        x.insert(x.end(), {px, py, pz}), rad.push_back(0.05);
  CraterProfileParams par;
  EXPECT_FALSE(craterProfile(x, rad, par).all.found);
  rad[3] = -1.0;
  EXPECT_THROW(craterProfile(x, rad, par), InputError);
  EXPECT_THROW(craterProfile({}, {}, par), InputError);
  par.azimuthalBins = 0;
  rad[3] = 0.05;
  EXPECT_THROW(craterProfile(x, rad, par), InputError);
}

// The rim is the crest next to the crater, not the highest ground of the whole profile: a
// bowl of radius 2 with a rim 0.1 high at r = 2.4, and a hill 0.5 high at r = 4.5 (terrain,
// or a container's edge); and a cone without a raised rim in bumpy ground, whose rim height
// stays within the bumps.
TEST(CraterProfile, RimIsTheCrestNextToTheCraterNotTheHighestGround) {
  std::vector<double> r, h, cone;
  for (double x = 0.005; x < 6.0; x += 0.01) {
    double z = 0.1 * std::exp(-(x - 2.4) * (x - 2.4) / 0.04) +
               0.5 * std::exp(-(x - 4.5) * (x - 4.5) / 0.09);
    if (x < 2.0)
      z -= 0.6 * (1.0 - x * x / 4.0);
    r.push_back(x), h.push_back(z);
    cone.push_back(x < 2.0 ? -0.577 * (2.0 - x)
                           : 0.01 * std::sin(17.0 * x) + (x > 5.0 ? 0.3 : 0.0));
  }
  const CraterMeasures m = measureProfile(r, h, 0.0, 0.005);
  std::printf("rim at diameter %.3f (crest at 4.8), height %.3f (0.1)\n", m.rimDiameter,
              m.rimHeight);
  ASSERT_TRUE(m.found);
  EXPECT_NEAR(m.rimDiameter, 4.8, 0.05);
  EXPECT_NEAR(m.rimHeight, 0.1, 0.005);
  const CraterMeasures c = measureProfile(r, cone, 0.0, 0.005);
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.diameter, 4.0, 0.02);
  EXPECT_LE(c.rimDiameter, 8.0);
  EXPECT_LT(c.rimHeight, 0.011); // the bumps', not the step at r = 5
}

TEST(CraterProfile, SectionCraterIsTheRunOfBinsBelowTheSurfaceAroundTheImpact) {
  // Bins of 1 m; the impact at x = 3.5 (bin 3); bins more than 0.3 m below z0 = 1 count.
  const std::vector<double> top{1.0, 0.8, 0.5, 0.2, 0.5, 1.0, 0.6};
  const SectionCrater c = measureSection(top, 1.0, 3.5, 1.0, 0.3);
  EXPECT_DOUBLE_EQ(c.depth, 0.8);
  EXPECT_DOUBLE_EQ(c.width, 3.0); // bins 2-4; bin 6 is below too but not connected
  const SectionCrater flat = measureSection(std::vector<double>(5, 1.0), 1.0, 2.5, 1.0, 0.3);
  EXPECT_EQ(flat.depth, 0.0);
  EXPECT_EQ(flat.width, 0.0);
}

// CraterProfile on a synthetic crater built from particles: a paraboloid bowl with a raised
// Gaussian rim, whose diameter, rim diameter and depth are known; isolated ejecta above the
// surface must not change the result.
#include "analysis/CraterProfile.h"
#include "common/Error.h"
#include "common/Random.h"

#include <gtest/gtest.h>

#include <array>
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

// The two depths (below the original surface; rim crest to floor) and the deepest point: a pit
// 0.3 m deep, 1 m wide, cut into the bowl's wall off the axis, fills only a few of the
// azimuthal bins of its rings, so the azimuthal mean barely sees it and the deepest single bin
// does.
TEST(CraterProfile, DepthBelowTheRimAndTheDeepestPoint) {
  std::vector<double> x, rad;
  crater(x, rad);
  const double pitX = 0.8, pitR = 0.5, pitDepth = 0.3;
  std::vector<double> xp, radp;
  for (std::size_t i = 0; i < rad.size(); ++i) {
    const double r = std::hypot(x[3 * i], x[3 * i + 1]);
    if (std::hypot(x[3 * i] - pitX, x[3 * i + 1]) < pitR &&
        x[3 * i + 2] + kRp > surface(r) - pitDepth)
      continue;
    xp.insert(xp.end(), {x[3 * i], x[3 * i + 1], x[3 * i + 2]});
    radp.push_back(kRp);
  }
  CraterProfileParams par;
  par.maxRadius = 4.5;
  const CraterProfileResult a = craterProfile(xp, radp, par);
  const CraterMeasures t = truth();
  const double dp = 2.0 * kRp;
  // The pit's lowest point: its edge nearest the axis, the bowl's depth there plus the pit's.
  const double deepest = -(surface(pitX - pitR) - pitDepth);
  std::printf("depth %.3f below the surface (true %.3f), %.3f below the rim (%.3f); deepest point "
              "%.3f (at most %.3f), %.3f below the rim\n",
              a.all.depth, t.depth, a.all.depthBelowRim, t.depth + t.rimHeight, a.deepestDepth,
              deepest, a.deepestDepthBelowRim);
  ASSERT_TRUE(a.all.found);
  // Each surface is the particles' top, up to one diameter below the true one: the difference
  // of two such heights is within one diameter of the true difference.
  EXPECT_NEAR(a.all.depthBelowRim, t.depth + t.rimHeight, dp);
  EXPECT_DOUBLE_EQ(a.all.depthBelowRim, a.all.depth + a.all.rimHeight);
  EXPECT_NEAR(a.all.depth, t.depth, dp); // the mean profile's lowest point is the axis's
  EXPECT_GT(a.deepestDepth, a.all.depth + pitDepth / 3.0); // the single bins see the pit
  EXPECT_LE(a.deepestDepth, deepest + dp);
  EXPECT_DOUBLE_EQ(a.deepestDepthBelowRim, a.deepestDepth + a.all.rimHeight);
}

// One large body among small grains (radius ratio 10, an impactor in its bed): the ejecta
// filter's verdict equals a brute-force count of each particle's neighbours within its own
// range, wherever the body lies, and a body outside the profile changes none of its measures.
namespace {
std::size_t bruteForceRejected(const std::vector<double>& x, const std::vector<double>& rad,
                               const CraterProfileParams& par) {
  std::size_t rejected = 0;
  for (std::size_t i = 0; i < rad.size(); ++i) {
    if (std::hypot(x[3 * i], x[3 * i + 1]) >= par.maxRadius)
      continue;
    int count = 0;
    const double range = par.neighbourFactor * rad[i];
    for (std::size_t j = 0; j < rad.size(); ++j) {
      const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                   dz = x[3 * i + 2] - x[3 * j + 2];
      count += j != i && dx * dx + dy * dy + dz * dz < range * range;
    }
    rejected += count < par.minNeighbours;
  }
  return rejected;
}
} // namespace

TEST(CraterProfile, OneLargeBodyAmongSmallGrainsChangesNothingButItself) {
  // A small pitted bed (a few thousand grains, so that the brute force stays cheap): a cubic
  // lattice of grains of radius r under a conical pit, and isolated ejecta above it.
  const double r = 0.05, d = 2.0 * r;
  std::vector<double> x, rad;
  for (double px = -1.0 + r; px < 1.0; px += d)
    for (double py = -1.0 + r; py < 1.0; py += d) {
      const double top = -0.3 * std::max(0.0, 1.0 - std::hypot(px, py) / 0.6);
      for (double pz = -0.5 + r; pz + r <= top; pz += d)
        x.insert(x.end(), {px, py, pz}), rad.push_back(r);
    }
  Random rng(11);
  for (int k = 0; k < 30; ++k) {
    const double rr = rng.uniform(0.0, 0.9), phi = rng.uniform(0.0, 2.0 * M_PI);
    x.insert(x.end(), {rr * std::cos(phi), rr * std::sin(phi), rng.uniform(0.5, 2.0)});
    rad.push_back(r);
  }
  CraterProfileParams par;
  par.maxRadius = 0.95;
  par.radialBins = 8;
  par.surfaceHeight = -0.12; // just below the flat grains' tops (at -0.1), so the edge is found
  const CraterProfileResult without = craterProfile(x, rad, par);
  ASSERT_TRUE(without.all.found);
  EXPECT_EQ(without.rejectedAsEjecta, bruteForceRejected(x, rad, par));
  for (const std::array<double, 3> body : {std::array<double, 3>{1.2, 1.2, -0.2},   // outside
                                           std::array<double, 3>{0.0, 0.0, -0.1},   // in the pit
                                           std::array<double, 3>{0.3, 0.0, 1.0}}) { // in flight
    std::vector<double> xb = x, radb = rad;
    xb.insert(xb.end(), body.begin(), body.end());
    radb.push_back(10.0 * r);
    const CraterProfileResult with = craterProfile(xb, radb, par);
    EXPECT_EQ(with.rejectedAsEjecta, bruteForceRejected(xb, radb, par));
    if (body[0] > 1.0) {
      EXPECT_EQ(with.rejectedAsEjecta, without.rejectedAsEjecta);
      EXPECT_DOUBLE_EQ(with.all.diameter, without.all.diameter);
      EXPECT_DOUBLE_EQ(with.all.depth, without.all.depth);
      EXPECT_DOUBLE_EQ(with.deepestDepth, without.deepestDepth);
    }
  }
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

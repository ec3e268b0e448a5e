// GranularBed: geometry, packing and size-distribution checks against oracles.
#include "bed/GranularBed.h"
#include "common/CellList.h"
#include "common/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace craterkit;

namespace {

// Loose random placement unless a test asks for settling (which runs the DEM).
GranularBedParams smallBowl(GranularBedParams::Packing packing) {
  GranularBedParams p;
  p.packing = packing;
  p.settle = false;
  p.container.type = Container::Type::Bowl;
  p.container.bowlRadius = 4.0;
  p.sizes.radius = 0.5;
  return p;
}

GranularBedParams smallBox(GranularBedParams::Packing packing) {
  GranularBedParams p;
  p.packing = packing;
  p.settle = false;
  p.container.type = Container::Type::Box;
  p.container.boxSize = {6.0, 5.0, 4.0};
  p.container.surfaceHeight = 0.5;
  p.sizes.radius = 0.5;
  return p;
}

// O(N^2) oracle: the largest relative overlap over all pairs (<= 0 means none).
double bruteForceWorstOverlap(const ParticleSet& s) {
  double worst = -INFINITY;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
        d2 += std::pow(s.position[3 * i + k] - s.position[3 * j + k], 2);
      const double overlap = s.radius[i] + s.radius[j] - std::sqrt(d2);
      worst = std::max(worst, overlap / std::min(s.radius[i], s.radius[j]));
    }
  return worst;
}

void expectInsideContainer(const ParticleSet& s, const Container& c) {
  for (std::size_t i = 0; i < s.size(); ++i)
    ASSERT_TRUE(c.inside(&s.position[3 * i], s.radius[i] * (1 - 1e-9)))
        << "particle " << i << " at (" << s.position[3 * i] << ", " << s.position[3 * i + 1] << ", "
        << s.position[3 * i + 2] << ") r = " << s.radius[i];
}

} // namespace

TEST(GranularBed, RandomBedsHaveNoOverlapsBruteForce) {
  for (auto p :
       {smallBowl(GranularBedParams::Packing::RCP), smallBox(GranularBedParams::Packing::RCP)}) {
    p.sizes.type = SizeDistribution::Type::Uniform;
    p.sizes.minRadius = 0.3;
    p.sizes.maxRadius = 0.6;
    const ParticleSet bed = generateGranularBed(p);
    ASSERT_GT(bed.size(), 100u);
    EXPECT_LE(bruteForceWorstOverlap(bed), 0.0);
    expectInsideContainer(bed, p.container);
  }
}

TEST(GranularBed, HcpBedsHaveNoOverlapsAndTouchNeighbours) {
  for (auto p :
       {smallBowl(GranularBedParams::Packing::HCP), smallBox(GranularBedParams::Packing::HCP)}) {
    const ParticleSet bed = generateGranularBed(p);
    ASSERT_GT(bed.size(), 50u);
    // Lattice neighbours touch: the worst "overlap" is zero to round-off, never positive.
    const double worst = bruteForceWorstOverlap(bed);
    EXPECT_LE(worst, 1e-12);
    EXPECT_GT(worst, -1e-9);
    expectInsideContainer(bed, p.container);
  }
}

TEST(GranularBed, CellListGapAgreesWithBruteForce) {
  auto p = smallBox(GranularBedParams::Packing::RCP);
  p.sizes.type = SizeDistribution::Type::PowerLaw;
  p.sizes.minRadius = 0.25;
  p.sizes.maxRadius = 0.6;
  const ParticleSet bed = generateGranularBed(p);
  double brute = INFINITY;
  for (std::size_t i = 0; i < bed.size(); ++i)
    for (std::size_t j = i + 1; j < bed.size(); ++j) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
        d2 += std::pow(bed.position[3 * i + k] - bed.position[3 * j + k], 2);
      brute = std::min(brute, std::sqrt(d2) - bed.radius[i] - bed.radius[j]);
    }
  EXPECT_DOUBLE_EQ(smallestGap(bed), brute);
}

TEST(GranularBed, HcpBulkPackingFraction) {
  GranularBedParams p;
  p.packing = GranularBedParams::Packing::HCP;
  p.container.type = Container::Type::Box;
  p.container.boxSize = {14.0, 14.0, 14.0};
  p.sizes.radius = 0.5;
  const ParticleSet bed = generateGranularBed(p);
  const double phi = measurePackingFraction(bed, p.container, 2.0, 2000000);
  EXPECT_NEAR(phi, M_PI / (3.0 * std::sqrt(2.0)), 0.01);
}

TEST(GranularBed, HcpIsHexagonalNotCubic) {
  // Every interior sphere of an HCP lattice has exactly 12 touching neighbours, six in its
  // own layer and three above and below; FCC would also give 12, so check the stacking:
  // the layer two spacings up sits directly above (ABAB), not offset (ABC).
  GranularBedParams p = smallBox(GranularBedParams::Packing::HCP);
  p.container.boxSize = {8.0, 8.0, 6.0};
  const ParticleSet bed = generateGranularBed(p);
  const double dz = 2 * 0.5 * std::sqrt(2.0 / 3.0);
  int interior = 0;
  for (std::size_t i = 0; i < bed.size(); ++i) {
    if (!p.container.inside(&bed.position[3 * i], 1.6))
      continue;
    ++interior;
    int touching = 0;
    bool above2 = false;
    for (std::size_t j = 0; j < bed.size(); ++j) {
      double e[3], d2 = 0;
      for (int k = 0; k < 3; ++k) {
        e[k] = bed.position[3 * j + k] - bed.position[3 * i + k];
        d2 += e[k] * e[k];
      }
      if (j != i && std::abs(std::sqrt(d2) - 1.0) < 1e-9)
        ++touching;
      if (std::hypot(e[0], e[1]) < 1e-9 && std::abs(e[2] - 2 * dz) < 1e-9)
        above2 = true;
    }
    EXPECT_EQ(touching, 12) << "particle " << i;
    if (bed.position[3 * i + 2] + 2 * dz < p.container.surfaceHeight - 0.5)
      EXPECT_TRUE(above2) << "particle " << i;
  }
  EXPECT_GT(interior, 10);
}

TEST(GranularBed, RandomBulkPackingIsLooseButAboveHalf) {
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  p.container.bowlRadius = 8.0;
  GranularBedReport report;
  const ParticleSet bed = generateGranularBed(p, &report);
  EXPECT_GE(report.bulkPackingFraction, 0.50);
  EXPECT_LE(report.bulkPackingFraction, 0.64);
  EXPECT_EQ(report.particles, bed.size());
}

TEST(GranularBed, SettledRandomBedIsDenseAndRestsOnItsContacts) {
  // Monodisperse RCP settled under gravity with the DEM: bulk 0.58-0.64, inside the container,
  // top layer reaching the surface; at rest in the DEM stage's law, its grains touch with the
  // small overlaps that carry its weight (below the stage's MaxOverlap, which its stiffness is
  // chosen for).
  for (auto p :
       {smallBowl(GranularBedParams::Packing::RCP), smallBox(GranularBedParams::Packing::RCP)}) {
    p.settle = true;
    GranularBedReport report;
    const ParticleSet bed = generateGranularBed(p, &report);
    EXPECT_TRUE(report.settled);
    EXPECT_GT(report.settlingSteps, 100);
    EXPECT_GT(report.restSteps, 100);
    const double worst = bruteForceWorstOverlap(bed);
    EXPECT_GT(worst, 0.0);
    EXPECT_LT(worst, p.stageMaxOverlap);
    for (std::size_t i = 0; i < bed.size(); ++i)
      ASSERT_TRUE(
          p.container.inside(&bed.position[3 * i], bed.radius[i] * (1 - p.stageMaxOverlap)));
    const double phi = measurePackingFraction(bed, p.container, 2.0 * p.sizes.radius, 400000);
    EXPECT_GE(phi, 0.58) << Container::typeName(p.container.type);
    EXPECT_LE(phi, 0.645) << Container::typeName(p.container.type);
    // Trimmed before its contacts stiffen to the stage's law, the bed rises a little.
    EXPECT_GT(report.topHeight, p.container.surfaceHeight - 1.0 * p.sizes.radius);
    EXPECT_LE(report.topHeight, p.container.surfaceHeight + p.stageMaxOverlap * p.sizes.radius);
    for (double v : bed.velocity)
      ASSERT_EQ(v, 0.0);
  }
}

TEST(GranularBed, SettlingFrictionLoosensThePacking) {
  auto p = smallBox(GranularBedParams::Packing::RCP);
  p.settle = true;
  p.settlingFriction = 0.0;
  const ParticleSet smooth = generateGranularBed(p);
  p.settlingFriction = 0.8;
  const ParticleSet rough = generateGranularBed(p);
  EXPECT_GT(measurePackingFraction(smooth, p.container, 1.0, 400000),
            measurePackingFraction(rough, p.container, 1.0, 400000) + 0.01);
}

TEST(GranularBed, SizeDistributionMatchesItsParameters) {
  for (auto type : {SizeDistribution::Type::Uniform, SizeDistribution::Type::PowerLaw}) {
    GranularBedParams p = smallBox(GranularBedParams::Packing::RCP);
    p.container.boxSize = {9.0, 9.0, 4.0};
    p.sizes.type = type;
    p.sizes.minRadius = 0.2;
    p.sizes.maxRadius = 0.5;
    p.sizes.exponent = 2.5;
    const ParticleSet bed = generateGranularBed(p);
    const double n = static_cast<double>(bed.size());
    double mean = 0, mean2 = 0, lo = INFINITY, hi = 0;
    for (double r : bed.radius) {
      mean += r / n;
      mean2 += r * r / n;
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
    const double sd = std::sqrt(p.sizes.moment(2) - std::pow(p.sizes.moment(1), 2));
    EXPECT_NEAR(mean, p.sizes.moment(1), 4.0 * sd / std::sqrt(n))
        << SizeDistribution::typeName(type);
    EXPECT_NEAR(mean2, p.sizes.moment(2), 0.03 * p.sizes.moment(2));
    EXPECT_GE(lo, 0.2);
    EXPECT_LE(hi, 0.5);
    EXPECT_LT(lo, 0.2 + 0.02); // the extremes are reached
    EXPECT_GT(hi, type == SizeDistribution::Type::Uniform ? 0.48 : 0.45);
  }
}

TEST(GranularBed, PowerLawCumulativeSlope) {
  // N(>r) ∝ r^-q: compare the sampled counts above two radii with the analytic ratio.
  SizeDistribution d;
  d.type = SizeDistribution::Type::PowerLaw;
  d.minRadius = 0.1;
  d.maxRadius = 10.0;
  d.exponent = 2.5;
  Random rng(7);
  const int n = 400000;
  int above1 = 0, above2 = 0;
  for (int i = 0; i < n; ++i) {
    const double r = d.sample(rng);
    above1 += r > 0.2;
    above2 += r > 0.4;
  }
  auto tail = [&](double r) {
    return (std::pow(r, -2.5) - std::pow(10.0, -2.5)) /
           (std::pow(0.1, -2.5) - std::pow(10.0, -2.5));
  };
  EXPECT_NEAR(above1 / double(n), tail(0.2), 4 * std::sqrt(tail(0.2) / n));
  EXPECT_NEAR(above2 / double(n), tail(0.4), 4 * std::sqrt(tail(0.4) / n));
}

TEST(GranularBed, SeedMakesBedsReproducible) {
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  p.sizes.type = SizeDistribution::Type::Uniform;
  const ParticleSet a = generateGranularBed(p);
  const ParticleSet b = generateGranularBed(p);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.radius, b.radius);
  p.seed = 2;
  const ParticleSet c = generateGranularBed(p);
  EXPECT_NE(a.position, c.position);
}

TEST(GranularBed, ArraysAreConsistent) {
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  p.particleDensity = 1500;
  const ParticleSet bed = generateGranularBed(p);
  std::set<std::int64_t> ids(bed.id.begin(), bed.id.end());
  EXPECT_EQ(ids.size(), bed.size());
  for (std::size_t i = 0; i < bed.size(); ++i) {
    EXPECT_NEAR(bed.mass[i], 1500 * 4.0 / 3.0 * M_PI * std::pow(bed.radius[i], 3), 1e-9);
    EXPECT_EQ(bed.velocity[3 * i], 0.0);
  }
}

TEST(GranularBed, FlatSurface) {
  // No particle pokes through the free surface, and the top layer reaches it.
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  p.container.bowlRadius = 6.0;
  p.container.surfaceHeight = -1.0;
  GranularBedReport report;
  generateGranularBed(p, &report);
  EXPECT_LE(report.topHeight, -1.0 + 1e-9);
  EXPECT_GT(report.topHeight, -1.0 - 0.05);
}

TEST(GranularBed, BadInputGivesNamedErrors) {
  auto expectError = [](GranularBedParams p, const std::string& word) {
    try {
      generateGranularBed(p);
      ADD_FAILURE() << "no error for " << word;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  auto q = p;
  q.sizes.radius = -1;
  expectError(q, "ParticleRadius");
  q = p;
  q.sizes.radius = std::nan("");
  expectError(q, "ParticleRadius");
  q = p;
  q.sizes.type = SizeDistribution::Type::Uniform;
  q.sizes.minRadius = 0.6;
  q.sizes.maxRadius = 0.3;
  expectError(q, "MaxRadius");
  q = p;
  q.container.bowlRadius = 0.4;
  expectError(q, "bowl");
  q = smallBox(GranularBedParams::Packing::RCP);
  q.container.boxSize[0] = 0.5;
  expectError(q, "box");
  q = p;
  q.maxParticles = 100;
  expectError(q, "MaxParticles");
  q = p;
  q.packingFraction = 0.7;
  expectError(q, "PackingFraction");
  q = p;
  q.packing = GranularBedParams::Packing::HCP;
  q.sizes.type = SizeDistribution::Type::PowerLaw;
  expectError(q, "Monodisperse");
  q = p;
  q.container.surfaceHeight = 1.0;
  expectError(q, "rim");
  q = p;
  q.particleDensity = 0;
  expectError(q, "ParticleDensity");
  q = p;
  q.packing = GranularBedParams::Packing::Loose;
  q.packingFraction = 0.7;
  expectError(q, "PackingFraction");
  q = p;
  q.settle = true;
  q.stageMaxOverlap = 0.0;
  expectError(q, "DEMMaxOverlap");
  q = p;
  q.packing = GranularBedParams::Packing::Loose;
  q.stageMaxExpectedSpeed = -1.0;
  expectError(q, "DEMMaxExpectedSpeed");
  q = p;
  q.settle = true;
  q.stageNormalStiffness = std::nan("");
  expectError(q, "DEMNormalStiffness");
}

TEST(GranularBed, ProgressCanAbort) {
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  int calls = 0;
  EXPECT_THROW(generateGranularBed(p, nullptr, [&](double) { return ++calls < 2; }), Aborted);
  EXPECT_EQ(calls, 2);
}

// The progress a bed reports rises with every report until it is done (ParaView's bar and
// the scripts' progress lines read it). The plateau this guards against (the last overlaps of
// a random placement reported as the growth's end, 20 % of a bed's bar, for thousands of
// sweeps) needs a fill above the bowl's rim, which only settling beds have; this small bed
// checks the order and the end.
TEST(GranularBed, ProgressRisesUntilDone) {
  auto p = smallBowl(GranularBedParams::Packing::RCP);
  std::vector<double> f;
  generateGranularBed(p, nullptr, [&](double x) {
    f.push_back(x);
    return true;
  });
  ASSERT_GE(f.size(), 10u);
  EXPECT_DOUBLE_EQ(f.back(), 1.0);
  std::size_t flat = 0;
  for (std::size_t k = 1; k < f.size(); ++k) {
    EXPECT_GE(f[k], f[k - 1]);
    flat += f[k] == f[k - 1] && f[k] < 1.0;
  }
  EXPECT_EQ(flat, 0u) << f.size() << " reports";
}

TEST(Container, ProjectionIsNearestFeasiblePoint) {
  // Compare the bowl projection with a brute-force search over feasible points, for a
  // surface below the rim and one above it (the wall continues as a cylinder).
  for (double surface : {-0.5, 1.0}) {
    Container c;
    c.type = Container::Type::Bowl;
    c.bowlRadius = 3.0;
    c.surfaceHeight = surface;
    const double r = 0.4;
    Random rng(3);
    for (int trial = 0; trial < 300; ++trial) {
      double x[3] = {rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-4, 2)};
      double p[3] = {x[0], x[1], x[2]};
      c.project(p, r);
      ASSERT_TRUE(c.inside(p, r * (1 - 1e-12)));
      const double dp =
          std::sqrt(std::pow(p[0] - x[0], 2) + std::pow(p[1] - x[1], 2) + std::pow(p[2] - x[2], 2));
      for (int s = 0; s < 3000; ++s) {
        double y[3] = {rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 1)};
        if (!c.inside(y, r))
          continue;
        const double dy = std::sqrt(std::pow(y[0] - x[0], 2) + std::pow(y[1] - x[1], 2) +
                                    std::pow(y[2] - x[2], 2));
        ASSERT_GE(dy, dp - 1e-9) << "surface " << surface;
      }
    }
  }
}

TEST(Container, FillVolumeMatchesMonteCarlo) {
  for (auto type : {Container::Type::Box, Container::Type::Bowl, Container::Type::Bowl}) {
    static int round = 0;
    Container c;
    c.type = type;
    c.bowlRadius = 2.0;
    c.surfaceHeight = round++ == 2 ? 0.7 : -0.3; // last: a bowl filled above its rim
    c.boxSize = {2.0, 3.0, 1.0};
    double lo[3], hi[3];
    c.bounds(0.0, lo, hi);
    Random rng(5);
    const int n = 400000;
    int in = 0;
    for (int i = 0; i < n; ++i) {
      double x[3] = {rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]),
                     rng.uniform(lo[2], hi[2])};
      in += c.inside(x, 0.0);
    }
    const double box = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    EXPECT_NEAR(box * in / n, c.fillVolume(), 0.01 * c.fillVolume());
  }
}

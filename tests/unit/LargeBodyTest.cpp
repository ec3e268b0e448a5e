// One large body among small grains (radius 10 r among grains of radius r): every neighbour
// search that sizes its cells by the ordinary particles (common/CellList.h, sizeClasses) and
// searches the large ones with their own reach must give what a brute-force search over all
// pairs gives: the fragments (ids included), the DEM's pair list (in its order), the hand-off's
// candidates, and the hand-off's velocity map and carving bit for bit as on cells sized by the
// largest support radius, the search they had before.
#include "analysis/Fragments.h"
#include "common/CellList.h"
#include "common/Random.h"
#include "common/SparseGrid.h"
#include "dem/PairList.h"
#include "handoff/AlphaShapeCarve.h"
#include "handoff/Split.h"
#include "handoff/VelocityMap.h"

#include "ComponentsOracle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

using namespace craterkit;

namespace {

// Grains of radius 1 on a cubic lattice of spacing 2 (side m), each moved by up to `jitter`
// on every axis, and a body of radius `big` at the lattice's centre (the grains closer than
// big + 0.95 to its centre left out, so that some touch it).
void grainsAndBody(int m, double jitter, double big, std::vector<double>& x, std::vector<double>& r,
                   unsigned seed) {
  Random rng(seed);
  const double c = m;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const double p[3] = {2.0 * i + 1 + rng.uniform(-jitter, jitter),
                             2.0 * j + 1 + rng.uniform(-jitter, jitter),
                             2.0 * k + 1 + rng.uniform(-jitter, jitter)};
        const double d =
            std::sqrt((p[0] - c) * (p[0] - c) + (p[1] - c) * (p[1] - c) + (p[2] - c) * (p[2] - c));
        if (d < big + 0.95)
          continue;
        x.insert(x.end(), p, p + 3);
        r.push_back(1.0);
      }
  x.insert(x.end(), {c, c, c});
  r.push_back(big);
}

double dist2(const std::vector<double>& x, std::size_t a, std::size_t b) {
  return (x[3 * a] - x[3 * b]) * (x[3 * a] - x[3 * b]) +
         (x[3 * a + 1] - x[3 * b + 1]) * (x[3 * a + 1] - x[3 * b + 1]) +
         (x[3 * a + 2] - x[3 * b + 2]) * (x[3 * a + 2] - x[3 * b + 2]);
}

// FragmentAnalysis's numbering from brute force: components by breadth-first search over all
// pairs, numbered by decreasing mass (summed in index order), ties by smallest member.
std::vector<long long> oracleFragments(const std::vector<double>& x, const std::vector<double>& r,
                                       const std::vector<double>& m, double tolerance) {
  const std::size_t n = r.size();
  const std::vector<int> comp = componentsOracle(n, [&](std::size_t a, std::size_t b) {
    const double cut = (r[a] + r[b]) * (1.0 + tolerance);
    return dist2(x, a, b) <= cut * cut;
  });
  const long long next = comp.empty() ? 0 : 1 + *std::max_element(comp.begin(), comp.end());
  std::vector<double> mass(static_cast<std::size_t>(next), 0.0);
  for (std::size_t i = 0; i < n; ++i)
    mass[static_cast<std::size_t>(comp[i])] += m[i];
  std::vector<long long> order(mass.size()), rank(mass.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](long long a, long long b) {
    return mass[a] != mass[b] ? mass[a] > mass[b] : a < b; // components numbered by first member
  });
  for (std::size_t k = 0; k < order.size(); ++k)
    rank[static_cast<std::size_t>(order[k])] = static_cast<long long>(k);
  std::vector<long long> ids(n);
  for (std::size_t i = 0; i < n; ++i)
    ids[i] = rank[static_cast<std::size_t>(comp[i])];
  return ids;
}

} // namespace

TEST(LargeBody, SizeClassesSetTheFewLargeOnesApart) {
  std::vector<double> r(1000, 1.0);
  SizeClasses c = sizeClasses(r.data(), r.size());
  EXPECT_EQ(c.large, 0u);
  EXPECT_EQ(c.ordinaryMax, 1.0);
  r.push_back(10.0);
  c = sizeClasses(r.data(), r.size());
  EXPECT_EQ(c.large, 1u);
  EXPECT_EQ(c.ordinaryMax, 1.0);
  EXPECT_EQ(c.largest, 10.0);
  EXPECT_TRUE(c.isLarge(10.0));
  EXPECT_FALSE(c.isLarge(1.0));
}

// Every contact is found once, by the larger particle's search: the grains touching the body
// must join its fragment although their own searches never reach its centre.
TEST(LargeBody, FragmentsMatchTheBruteForceOracle) {
  for (const double jitter : {0.08, 0.2}) {
    std::vector<double> x, r;
    grainsAndBody(14, jitter, 10.0, x, r, 41);
    if (jitter > 0.1) { // polydisperse grains: radii from 0.8 to 1.2, the body kept
      Random rng(42);
      for (std::size_t i = 0; i + 1 < r.size(); ++i)
        r[i] = rng.uniform(0.8, 1.2);
    }
    const std::size_t n = r.size();
    std::vector<double> m(n), v(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      m[i] = r[i] * r[i] * r[i];
    FragmentParams par;
    par.tolerance = 0.01;
    const FragmentResult res = analyseFragments(x, r, m, v, par);
    EXPECT_EQ(res.fragmentId, oracleFragments(x, r, m, par.tolerance)) << "jitter " << jitter;
    EXPECT_GT(res.fragments.size(), 2u);
    EXPECT_GT(res.fragments[static_cast<std::size_t>(res.fragmentId.back())].count, 1u)
        << "no grain found the body";
  }
}

// The DEM's half list: every pair i < j within r_i + r_j + skin, sorted by (i, j), with its
// per-particle indices; one body among equal grains (each grain tests it itself), and more
// than 64 large bodies among polydisperse grains (found on cells of their own).
TEST(LargeBody, DemPairListMatchesTheBruteForceOracle) {
  for (int variant = 0; variant < 2; ++variant) {
    std::vector<double> x, r;
    grainsAndBody(14, 0.1, 10.0, x, r, 43);
    if (variant == 1) {
      Random rng(44);
      for (std::size_t i = 0; i + 1 < r.size(); ++i)
        r[i] = i % 20 == 0 ? rng.uniform(3.0, 9.0) : rng.uniform(0.8, 1.3);
    }
    const std::size_t n = r.size();
    const double skin = 0.2, rmax = *std::max_element(r.begin(), r.end());
    std::vector<std::uint32_t> first, second;
    std::vector<std::size_t> firstStart(n + 1, 0), secondStart(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const double reach = r[i] + r[j] + skin;
        const double d0 = x[3 * j] - x[3 * i], d1 = x[3 * j + 1] - x[3 * i + 1],
                     d2 = x[3 * j + 2] - x[3 * i + 2];
        if (d0 * d0 + d1 * d1 + d2 * d2 < reach * reach) {
          first.push_back(static_cast<std::uint32_t>(i));
          second.push_back(static_cast<std::uint32_t>(j));
          ++firstStart[i + 1], ++secondStart[j + 1];
        }
      }
    std::partial_sum(firstStart.begin(), firstStart.end(), firstStart.begin());
    std::partial_sum(secondStart.begin(), secondStart.end(), secondStart.begin());
    PairList list;
    list.build(x.data(), r.data(), n, rmax, skin);
    EXPECT_EQ(list.first, first) << "variant " << variant;
    EXPECT_EQ(list.second, second) << "variant " << variant;
    EXPECT_EQ(list.firstStart, firstStart);
    EXPECT_EQ(list.secondStart, secondStart);
    const std::size_t body = n - 1;
    EXPECT_GT(std::count(second.begin(), second.end(), body), 10) << "variant " << variant;
    if (variant == 1) // more large ones than the grains test themselves
      EXPECT_GT(sizeClasses(r.data(), n).large, 64u);
  }
}

// The hand-off's ejecta placement searches spheres on two grids (SphereGrid): every listed
// sphere a query overlaps must be visited, for small and large queries, and after removals.
TEST(LargeBody, SphereGridVisitsEveryOverlappingSphere) {
  Random rng(45);
  std::vector<double> x, r;
  for (int i = 0; i < 3000; ++i) {
    for (int k = 0; k < 3; ++k)
      x.push_back(rng.uniform(0.0, 40.0));
    r.push_back(i % 500 == 7 ? 10.0 : rng.uniform(0.5, 1.0));
  }
  const SizeClasses sizes = sizeClasses(r.data(), r.size());
  ASSERT_EQ(sizes.large, 6u);
  SphereGrid grid(sizes.ordinaryMax, sizes.largest);
  for (std::size_t i = 0; i < r.size(); ++i)
    grid.insert(&x[3 * i], r[i], i);
  std::vector<char> removed(r.size(), 0);
  for (int q = 0; q < 400; ++q) {
    const double at[3] = {rng.uniform(-5.0, 45.0), rng.uniform(-5.0, 45.0),
                          rng.uniform(-5.0, 45.0)};
    const double rq = q % 4 == 0 ? 10.0 : q % 4 == 1 ? 3.0 : rng.uniform(0.1, 1.0);
    std::set<std::size_t> seen;
    grid.forEachOverlapCandidate(at, rq, [&](std::size_t j) {
      EXPECT_FALSE(removed[j]) << "removed sphere " << j << " visited";
      seen.insert(j);
      const bool take = q % 7 == 0 && j % 2 == 0; // some queries take spheres off the grid
      removed[j] = removed[j] || take;
      return take;
    });
    for (std::size_t j = 0; j < r.size(); ++j) {
      const double d = std::sqrt((x[3 * j] - at[0]) * (x[3 * j] - at[0]) +
                                 (x[3 * j + 1] - at[1]) * (x[3 * j + 1] - at[1]) +
                                 (x[3 * j + 2] - at[2]) * (x[3 * j + 2] - at[2]));
      if (!removed[j] && d < rq + r[j])
        ASSERT_TRUE(seen.count(j)) << "query " << q << " missed sphere " << j;
    }
  }
}

namespace {

// SPH particles on a cubic lattice (spacing dx) in the hemisphere of radius 1 below z = 0, in a
// smooth non-linear flow, support 2.5 dx; the one nearest (0.3, 0.2, -0.3) has 10 times that.
SphSnapshot sphWithOneWideParticle(double dx) {
  SphSnapshot s;
  const int n = static_cast<int>(1.0 / dx);
  std::size_t wide = 0;
  double bestD = INFINITY;
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, -(k + 0.5) * dx};
        if (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] > 1.0)
          continue;
        const double v[3] = {std::sin(3.0 * x[1]) + 0.1 * x[2], x[0] * x[0] - 0.3 * x[2],
                             x[0] * x[2] + 0.2 * std::cos(2.0 * x[0])};
        const double d = std::hypot(x[0] - 0.3, x[1] - 0.2, x[2] + 0.3);
        if (d < bestD)
          bestD = d, wide = s.size();
        s.x.insert(s.x.end(), x, x + 3);
        s.v.insert(s.v.end(), v, v + 3);
        s.mass.push_back(1000.0 * dx * dx * dx * (1.0 + 0.1 * std::sin(7.0 * x[0])));
        s.h.push_back(2.5 * dx);
      }
  s.h[wide] *= 10.0;
  return s;
}

// The same cloud on cells as wide as its largest support radius, without the wide ones' own
// cells: the search the hand-off made before.
CompactCloud onCellsOfTheLargest(CompactCloud cloud) {
  cloud.wide.clear();
  cloud.isWide.clear();
  cloud.orderKey.clear();
  cloud.hOrdinary = cloud.hmax;
  cloud.cells.build(cloud.x.data(), cloud.h.size(), cloud.hmax);
  return cloud;
}

} // namespace

TEST(LargeBody, HandoffSearchesMatchBruteForceAndTheirFormerBits) {
  const double dx = 1.0 / 15.0;
  const SphSnapshot sph = sphWithOneWideParticle(dx);
  std::vector<std::size_t> compact(sph.size());
  std::iota(compact.begin(), compact.end(), 0);
  const double alpha = 1.75 * dx;
  const CompactCloud cloud(sph, compact, alpha);
  ASSERT_EQ(cloud.wide.size(), 1u);
  EXPECT_DOUBLE_EQ(cloud.hOrdinary, 2.5 * dx);
  const CompactCloud before = onCellsOfTheLargest(cloud);

  // Bed grains on a lattice wider than the cloud (some with no SPH particle in reach).
  ParticleSet bed;
  Random rng(46);
  std::int64_t id = 0;
  for (int i = -10; i < 10; ++i)
    for (int j = -10; j < 10; ++j)
      for (int k = -2; k < 10; ++k) {
        const double x[3] = {(i + 0.5) * 0.12 + rng.uniform(-0.01, 0.01),
                             (j + 0.5) * 0.12 + rng.uniform(-0.01, 0.01), -(k + 0.5) * 0.12};
        bed.add(x, 0.05, 2000.0, 0, id++);
      }
  // and a few grains farther than hmax from every SPH particle: their nearest one is searched
  // among the former cells around them, or (the last two) among all
  for (const auto& at : {std::array<double, 3>{2.6, 0.0, -0.5},
                         {2.7, 2.7, -0.2},
                         {-2.65, 0.3, -0.1},
                         {0.0, 0.0, 2.7},
                         {10.0, 10.0, 10.0}})
    bed.add(at.data(), 0.05, 2000.0, 0, id++);
  // The candidates hold every SPH particle whose support reaches the grain (brute force). The
  // map sums them in the order of the former cells (by cell, then by index), which for some
  // grains is not the order the new cells visit them in: the bits below depend on it.
  std::size_t reordered = 0;
  for (std::size_t g = 0; g < bed.size(); g += 2) {
    const double* at = &bed.position[3 * g];
    std::set<std::size_t> seen;
    std::vector<std::size_t> inReach;
    cloud.forEachCandidateSupport(at, [&](std::size_t k) {
      seen.insert(k);
      if (std::hypot(cloud.x[3 * k] - at[0], cloud.x[3 * k + 1] - at[1],
                     cloud.x[3 * k + 2] - at[2]) < cloud.h[k])
        inReach.push_back(k);
    });
    for (std::size_t k = 0; k < cloud.h.size(); ++k) {
      const double d = std::hypot(cloud.x[3 * k] - at[0], cloud.x[3 * k + 1] - at[1],
                                  cloud.x[3 * k + 2] - at[2]);
      if (d < cloud.h[k])
        ASSERT_TRUE(seen.count(k)) << "grain " << g << " missed SPH particle " << k;
    }
    std::vector<std::size_t> byFormerCells = inReach;
    std::sort(byFormerCells.begin(), byFormerCells.end(), [&](std::size_t a, std::size_t b) {
      return cloud.orderKey[a] != cloud.orderKey[b] ? cloud.orderKey[a] < cloud.orderKey[b] : a < b;
    });
    reordered += byFormerCells != inReach;
  }
  EXPECT_GT(reordered, 0u);
  // The velocity map, with the fit (1 neighbour) and with the nearest particle's velocity
  // (more neighbours than any grain has): the same bits as on the former cells.
  std::vector<std::size_t> mapped(bed.size());
  std::iota(mapped.begin(), mapped.end(), 0);
  for (const int minNeighbours : {1, 1000}) {
    ParticleSet now = bed, then = bed;
    mapVelocities(sph, compact, cloud, minNeighbours, mapped, now);
    mapVelocities(sph, compact, before, minNeighbours, mapped, then);
    EXPECT_EQ(0, std::memcmp(now.velocity.data(), then.velocity.data(),
                             now.velocity.size() * sizeof(double)))
        << "minNeighbours " << minNeighbours;
    EXPECT_EQ(0, std::memcmp(now.angularVelocity.data(), then.angularVelocity.data(),
                             now.angularVelocity.size() * sizeof(double)))
        << "minNeighbours " << minNeighbours;
  }
  // The carving (a grain within half a spacing of a compact particle is kept).
  AlphaShapeCarve shape(sph, compact, alpha);
  double volume = 0.0;
  std::vector<double> points;
  std::vector<long long> triangles;
  shape.buildShape(volume, points, triangles);
  TargetRegion region;
  region.shape = TargetRegion::Shape::Hemisphere;
  region.radius = 1.0;
  const Carving a = shape.carve(bed, region, cloud), b = shape.carve(bed, region, before);
  EXPECT_EQ(a.keep, b.keep);
  EXPECT_EQ(a.mapped, b.mapped);
  EXPECT_EQ(a.removed, b.removed);
}

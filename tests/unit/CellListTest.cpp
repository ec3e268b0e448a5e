// CellList: neighbour candidates must include every point within reach (brute-force oracle),
// in the dense and the sparse layout; the sparse layout's cells keep their size on a wide cloud.
#include "common/CellList.h"
#include "common/Random.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cstdio>
#include <set>
#include <utility>

using namespace craterkit;

TEST(CellList, CandidatesContainAllNeighboursWithinReach) {
  Random rng(11);
  const std::size_t n = 3000;
  std::vector<double> x(3 * n);
  for (auto& v : x)
    v = rng.uniform(-5.0, 5.0);
  x[0] = 1e3; // one far outlier stretches the domain
  CellList cells;
  for (double cell : {0.3, 1.0, 2.5}) {
    cells.build(x.data(), n, cell);
    for (std::size_t i = 0; i < n; i += 7) {
      const double reach = cell;
      std::set<std::size_t> found;
      cells.forEachCandidate(&x[3 * i], reach, [&](std::size_t j) { found.insert(j); });
      for (std::size_t j = 0; j < n; ++j) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k)
          d2 += (x[3 * i + k] - x[3 * j + k]) * (x[3 * i + k] - x[3 * j + k]);
        if (d2 <= reach * reach)
          ASSERT_TRUE(found.count(j)) << "missed neighbour " << j << " of " << i;
      }
    }
  }
}

// The ranges of sorted() are the points forEachCandidate visits, in the same order.
TEST(CellList, CandidateRangesHoldTheCandidates) {
  Random rng(12);
  const std::size_t n = 2000;
  std::vector<double> x(3 * n);
  for (auto& v : x)
    v = rng.uniform(-3.0, 3.0);
  CellList cells;
  cells.build(x.data(), n, 0.7);
  for (std::size_t i = 0; i < n; i += 5) {
    std::vector<std::size_t> visited, ranged;
    cells.forEachCandidate(&x[3 * i], 0.7, [&](std::size_t j) { visited.push_back(j); });
    cells.forEachCandidateRange(&x[3 * i], 0.7, [&](std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s)
        ranged.push_back(cells.sorted()[s]);
    });
    ASSERT_EQ(ranged, visited) << "point " << i;
    ASSERT_FALSE(visited.empty()); // the point itself at least
  }
}

namespace {

// A debris-cloud-like set: dense clumps (random and lattice) a few reaches wide, scattered
// single points and one far outlier, in a box thousands of reaches wide and mostly empty.
std::vector<double> spreadOutCloud(double reach) {
  Random rng(13);
  std::vector<double> x;
  for (int clump = 0; clump < 6; ++clump) {
    double centre[3];
    for (double& c : centre)
      c = rng.uniform(-1000.0, 1000.0) * reach;
    for (int p = 0; p < 400; ++p)
      for (int k = 0; k < 3; ++k)
        x.push_back(centre[k] + rng.uniform(-2.0, 2.0) * reach);
  }
  // A lattice of spacing reach / 2 puts many points on cell faces and pairs at exactly reach.
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int c = 0; c < 8; ++c)
        for (double v : {a * 0.5 * reach, b * 0.5 * reach, c * 0.5 * reach})
          x.push_back(v + 3.0 * reach);
  for (int p = 0; p < 300; ++p)
    for (int k = 0; k < 3; ++k)
      x.push_back(rng.uniform(-1500.0, 1500.0) * reach);
  for (double v : {4e4 * reach, -2e3 * reach, 7e3 * reach})
    x.push_back(v);
  return x;
}

double distance2(const std::vector<double>& x, std::size_t i, std::size_t j) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k)
    d2 += (x[3 * i + k] - x[3 * j + k]) * (x[3 * i + k] - x[3 * j + k]);
  return d2;
}

} // namespace

// The neighbours closer than the reach found from each point's 27 cells (forEachNeighbourRange)
// are, point by point, those of a brute-force search over all pairs, with 1 and 2 threads building
// the cells, which give the same order and ranges; the cells stay the reach where the dense grid's
// grow.
TEST(CellList, SparseCellsKeepTheirSizeAndFindTheBruteForcePairs) {
  const double reach = 0.37;
  const std::vector<double> x = spreadOutCloud(reach);
  const std::size_t n = x.size() / 3;
  std::set<std::pair<std::size_t, std::size_t>> brute;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (distance2(x, i, j) < reach * reach)
        brute.emplace(i, j), brute.emplace(j, i); // each point's own list: both orders
  CellList dense;
  dense.build(x.data(), n, reach);
  std::printf("[cells] %zu points, %zu ordered pairs within the reach; dense cells %.1f reach\n", n,
              brute.size(), dense.cellSize() / reach);
  EXPECT_GT(dense.cellSize(), 10.0 * reach); // the case the sparse layout is for
  const int threadsBefore = omp_get_max_threads();
  std::vector<std::vector<std::size_t>> visits;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    CellList cells;
    cells.buildSparse(x.data(), n, reach);
    EXPECT_LT(cells.cellSize(), reach * (1.0 + 1e-7));
    std::set<std::pair<std::size_t, std::size_t>> found;
    std::vector<std::size_t> visit(cells.sorted());
    for (std::size_t i = 0; i < n; ++i)
      cells.forEachNeighbourRange(i, [&](std::size_t begin, std::size_t end) {
        visit.push_back(begin), visit.push_back(end);
        for (std::size_t s = begin; s < end; ++s) {
          const std::size_t j = cells.sorted()[s];
          if (j != i && distance2(x, i, j) < reach * reach)
            found.emplace(i, j);
        }
      });
    EXPECT_EQ(found, brute) << threads << " threads";
    visits.push_back(std::move(visit));
  }
  omp_set_num_threads(threadsBefore);
  EXPECT_EQ(visits[0], visits[1]);
}

// Queries anywhere (outside the box too) and of any reach find every point within reach in
// the sparse layout, as forEachCandidateRange's ranges.
TEST(CellList, SparseCandidatesContainAllNeighboursWithinReach) {
  const double cell = 0.5;
  const std::vector<double> x = spreadOutCloud(cell);
  const std::size_t n = x.size() / 3;
  CellList cells;
  cells.buildSparse(x.data(), n, cell);
  Random rng(14);
  for (double reach : {0.3, 0.5, 1.7}) {
    for (std::size_t q = 0; q < n + 200; q += 3) {
      double at[3];
      for (int k = 0; k < 3; ++k) // the points, then queries near and beyond the box's faces
        at[k] = q < n ? x[3 * q + k] : rng.uniform(-1.1, 1.1) * 1000.0 * cell;
      std::set<std::size_t> found;
      cells.forEachCandidateRange(at, reach, [&](std::size_t begin, std::size_t end) {
        for (std::size_t s = begin; s < end; ++s)
          found.insert(cells.sorted()[s]);
      });
      for (std::size_t j = 0; j < n; ++j) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k)
          d2 += (at[k] - x[3 * j + k]) * (at[k] - x[3 * j + k]);
        if (d2 <= reach * reach)
          ASSERT_TRUE(found.count(j)) << "missed point " << j << " of query " << q;
      }
    }
  }
}

TEST(CellList, RejectsNonFinitePoints) {
  std::vector<double> x = {0, 0, 0, std::nan(""), 0, 0};
  CellList cells;
  EXPECT_ANY_THROW(cells.build(x.data(), 2, 1.0));
  EXPECT_ANY_THROW(cells.buildSparse(x.data(), 2, 1.0));
  EXPECT_ANY_THROW(cells.buildSparse(x.data(), 1, 0.0));
}

// CellList: neighbour candidates must include every point within reach (brute-force oracle).
#include "common/CellList.h"
#include "common/Random.h"

#include <gtest/gtest.h>

#include <set>

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

TEST(CellList, RejectsNonFinitePoints) {
  std::vector<double> x = {0, 0, 0, std::nan(""), 0, 0};
  CellList cells;
  EXPECT_ANY_THROW(cells.build(x.data(), 2, 1.0));
}

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

TEST(CellList, RejectsNonFinitePoints) {
  std::vector<double> x = {0, 0, 0, std::nan(""), 0, 0};
  CellList cells;
  EXPECT_ANY_THROW(cells.build(x.data(), 2, 1.0));
}

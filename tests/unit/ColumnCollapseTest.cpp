// The column collapse's deposit edge (Solvers/analysis/ColumnCollapse.h) against geometry.
#include "analysis/ColumnCollapse.h"
#include "common/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace craterkit;

namespace {
// A monolayer of touching grains (radius 1) on a square lattice, centres within `within` of
// the axis.
void disk(double within, std::vector<double>& x, std::vector<double>& r) {
  const int n = static_cast<int>(within / 2.0) + 1;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      if (std::hypot(2.0 * i, 2.0 * j) <= within) {
        x.insert(x.end(), {2.0 * i, 2.0 * j, 1.0});
        r.push_back(1.0);
      }
}
} // namespace

// A disk of touching grains whose centres lie within 19 radii covers the floor out to about
// 20 radii (its grains' edges); the cover falls through half a monolayer's in the last ring of
// grains, between 19 and 20 radii.
TEST(ColumnCollapse, DepositEdgeOfADiskOfTouchingGrains) {
  std::vector<double> x, r;
  disk(19.0, x, r);
  const double edge = depositEdgeRadius(x, r);
  EXPECT_LE(edge, 20.0);
  EXPECT_GE(edge, 19.0);
}

// Grains that rolled away one by one do not move the edge, though more than 1 % of the grains
// (the radius holding 99 % of them would follow them).
TEST(ColumnCollapse, DepositEdgeIgnoresDetachedGrains) {
  std::vector<double> x, r;
  disk(19.0, x, r);
  const double edge = depositEdgeRadius(x, r);
  const std::size_t pile = r.size();
  for (int k = 0; k < 24; ++k) { // one stray grain per sector, 40 radii out
    const double a = (k + 0.5) * 2.0 * M_PI / 24.0 - M_PI;
    x.insert(x.end(), {40.0 * std::cos(a), 40.0 * std::sin(a), 1.0});
    r.push_back(1.0);
  }
  EXPECT_GT(r.size() - pile, pile / 100); // more than 1 % of the grains
  EXPECT_DOUBLE_EQ(depositEdgeRadius(x, r), edge);
}

TEST(ColumnCollapse, DepositEdgeRefusesEmptyInput) {
  EXPECT_THROW(depositEdgeRadius({}, {}), InputError);
  EXPECT_THROW(depositEdgeRadius({0.0, 0.0}, {1.0}), InputError);
}

// The support list (sph/SupportList.h) against a brute-force oracle: while particles wander and
// their h grows, every pair inside the support ½(h_a + h_b) is in the list, the list is the
// Verlet list's entries in their order, and it is drawn again only now and then.
#include "sph/NeighbourList.h"
#include "sph/SupportList.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace craterkit;

namespace {
double gap2(const PairPosition& a, const PairPosition& b, std::uint32_t code, const double L[3]) {
  const std::uint32_t c = code & 31u;
  const double rx = a.x[0] - b.x[0] - (static_cast<int>(c % 3) - 1) * L[0];
  const double ry = a.x[1] - b.x[1] - (static_cast<int>(c / 3 % 3) - 1) * L[1];
  const double rz = a.x[2] - b.x[2] - (static_cast<int>(c / 9) - 1) * L[2];
  return rx * rx + ry * ry + rz * rz;
}

// Whether `sub` is a subsequence of `all` (the same entries in the same order, some left out).
bool inOrder(const std::uint32_t* sub, std::uint32_t m, const std::vector<std::uint32_t>& all) {
  std::size_t k = 0;
  for (std::uint32_t j = 0; j < m; ++j) {
    while (k < all.size() && all[k] != sub[j])
      ++k;
    if (k++ == all.size())
      return false;
  }
  return true;
}
} // namespace

TEST(SphSupportList, HoldsEveryPairInsideTheSupportWhileParticlesMove) {
  const std::size_t n = 400;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PairPosition> X(n);
  for (PairPosition& p : X)
    p.x[0] = u(rng), p.x[1] = u(rng), p.x[2] = u(rng), p.h = 0.1 + 0.1 * u(rng);
  // The Verlet list: every other particle, in a shuffled order (always valid).
  std::vector<std::vector<std::uint32_t>> verlet(n);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::uint32_t b = 0; b < n; ++b)
      if (b != a)
        verlet[a].push_back(b * 32 + kNoShift);
    std::shuffle(verlet[a].begin(), verlet[a].end(), rng);
  }
  const SupportList::Source source = [&](std::size_t a, const std::uint32_t*& e, std::uint32_t& m) {
    e = verlet[a].data(), m = static_cast<std::uint32_t>(verlet[a].size());
  };
  const double none[3] = {0.0, 0.0, 0.0};
  SupportList list;
  std::size_t inside = 0, listed = 0, used = 0;
  const int calls = 300;
  for (int call = 0; call < calls; ++call) {
    const bool use = list.follow(X.data(), n, 1, none, source);
    for (std::size_t a = 0; a < n && use; ++a) {
      ASSERT_TRUE(inOrder(list.entries(a), list.count(a), verlet[a])) << "particle " << a;
      listed += list.count(a);
      for (std::uint32_t code : verlet[a]) {
        const PairPosition& b = X[code >> 5];
        const double hb = 0.5 * (X[a].h + b.h);
        if (gap2(X[a], b, code, none) >= hb * hb)
          continue;
        ++inside;
        bool found = false;
        for (std::uint32_t j = 0; j < list.count(a) && !found; ++j)
          found = list.entries(a)[j] == code;
        ASSERT_TRUE(found) << "call " << call << ": pair " << a << "-" << (code >> 5)
                           << " inside the support is not listed";
      }
    }
    used += use;
    // A random walk of about a sixtieth of the skin per call, and h growing by 0.1 % per call.
    for (PairPosition& p : X) {
      for (double& x : p.x)
        x += 0.03 * kSupportSkin * p.h * (u(rng) - 0.5);
      p.h *= 1.001;
    }
  }
  // Drawn again as the walk went on, each draw used for several calls, never resting (each
  // list lived long enough); and thin: a list of all pairs within (1 + s) of the support holds
  // about (1 + s)³ times the pairs inside it.
  EXPECT_GT(list.draws(), 2u);
  EXPECT_LT(list.draws(), static_cast<std::size_t>(calls) / kSupportLife);
  EXPECT_EQ(used, static_cast<std::size_t>(calls));
  EXPECT_LT(static_cast<double>(listed), 1.5 * static_cast<double>(inside));
}

TEST(SphSupportList, RestsWhenItMustBeDrawnAgainTooSoon) {
  // Two particles closing fast: the list must be drawn again after a few calls, so it rests.
  std::vector<PairPosition> X(2);
  X[0].x[0] = 0.0, X[1].x[0] = 1.0;
  for (PairPosition& p : X)
    p.x[1] = p.x[2] = 0.0, p.h = 0.5;
  std::vector<std::vector<std::uint32_t>> verlet = {{1 * 32 + kNoShift}, {0 * 32 + kNoShift}};
  const SupportList::Source source = [&](std::size_t a, const std::uint32_t*& e, std::uint32_t& m) {
    e = verlet[a].data(), m = static_cast<std::uint32_t>(verlet[a].size());
  };
  const double none[3] = {0.0, 0.0, 0.0};
  SupportList list;
  int calls = 0;
  while (list.follow(X.data(), 2, 1, none, source)) { // 0.01 a call against 0.45 s h = 0.0225
    ++calls;
    X[1].x[0] -= 0.01;
  }
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(list.draws(), 1u);
  for (std::size_t k = 0; k < kSupportRest; ++k)
    EXPECT_FALSE(list.follow(X.data(), 2, 1, none, source));
  EXPECT_TRUE(list.follow(X.data(), 2, 1, none, source)); // drawn again after the rest
  EXPECT_EQ(list.draws(), 2u);
}

TEST(SphSupportList, KeepsPeriodicImagesAndDrawsAgainForANewVerletList) {
  // Two particles near opposite faces of a periodic unit box: near through the x face only.
  std::vector<PairPosition> X(2);
  X[0].x[0] = 0.02, X[1].x[0] = 0.97;
  for (PairPosition& p : X)
    p.x[1] = p.x[2] = 0.5, p.h = 0.1;
  const double L[3] = {1.0, 0.0, 0.0};
  // 0 sees 1 shifted by −L (code 12: sx = −1); 1 sees 0 shifted by +L (code 14), and unshifted.
  std::vector<std::vector<std::uint32_t>> verlet = {{1 * 32 + 12},
                                                    {0 * 32 + 14, 0 * 32 + kNoShift}};
  const SupportList::Source source = [&](std::size_t a, const std::uint32_t*& e, std::uint32_t& m) {
    e = verlet[a].data(), m = static_cast<std::uint32_t>(verlet[a].size());
  };
  SupportList list;
  EXPECT_TRUE(list.follow(X.data(), 2, 1, L, source));
  ASSERT_EQ(list.count(0), 1u);
  EXPECT_EQ(list.entries(0)[0], 1u * 32 + 12);
  ASSERT_EQ(list.count(1), 1u); // the unshifted image is 0.95 away
  EXPECT_EQ(list.entries(1)[0], 0u * 32 + 14);
  EXPECT_TRUE(list.follow(X.data(), 2, 1, L, source)); // nothing moved: not drawn again
  EXPECT_EQ(list.draws(), 1u);
  verlet[1] = {0 * 32 + kNoShift};
  for (std::size_t k = 0; k < kSupportLife; ++k) // long enough not to rest
    EXPECT_TRUE(list.follow(X.data(), 2, 1, L, source));
  EXPECT_TRUE(list.follow(X.data(), 2, 2, L, source)); // a new Verlet list
  EXPECT_EQ(list.draws(), 2u);
  EXPECT_EQ(list.count(1), 0u);
}

// The bonded model's force pass in its two versions (bonded/BondedForces.h): where the processor
// has AVX-512, the intrinsics pass must give the bits of the generic pass's AVX-512 clone, so
// that a run does not depend on which of the two ran (the solver picks one at run time).
#include "bonded/BondedForces.h"
#include "bonded/WatsonSteinhauser2017.h"
#include "common/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

using namespace craterkit;

namespace {

// A pass over n particles in a box of 2σ (partners 1.3σ apart on average), each lane with `depth`
// listed partners: a third without a bond, the rest bonded with rest lengths around r_eq, so that
// some bonds sit beyond r_cut (they break) and some partners are closer than r_eq (repulsion). The
// last block is part full (n not a multiple of eight), as in the solver. The rest lengths are held
// both ways: as doubles (the wide lists) and as float offsets from r_eq (the compact lists), each
// double the sum r_eq + offset the compact pass forms, so that both describe the same lists.
struct PassData {
  std::vector<double> x, rest, force, v, m;
  std::vector<float> offset;
  double restRef = 0.0;
  std::vector<std::size_t> blockStart;
  std::vector<std::uint32_t> partner, breaks;
};

// Pair lists over n particles, depth entries a lane, a third of them unbonded. The bonded ones
// rest at 0.8–1.3 r_eq: with exactDoubles the wide lists hold these doubles (which no float offset
// holds) and the compact lists are unused; else both hold restRef + the float offset, restRef
// away from r_eq so that a pass decoding from r_eq would fail.
PassData makePass(std::size_t n, std::size_t depth, double sigma, unsigned seed,
                  bool exactDoubles = false) {
  using bondedpass::kLanes;
  PassData d;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> box(0.0, 2.0 * sigma), rel(0.8, 1.3), kick(-1.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(n - 1));
  for (std::size_t i = 0; i < 3 * n; ++i)
    d.x.push_back(box(rng)), d.v.push_back(kick(rng));
  d.m.assign(n, 1e-9);
  const std::size_t blocks = (n + kLanes - 1) / kLanes;
  for (std::size_t b = 0; b <= blocks; ++b)
    d.blockStart.push_back(b * depth * kLanes);
  const double rEq = ws2017::kTwoToOneSixth * sigma;
  d.restRef = 1.0625 * rEq;
  for (std::size_t e = 0; e < blocks * depth * kLanes; ++e) {
    d.partner.push_back(pick(rng));
    const bool bonded = e % 3 != 0;
    const double r0 = bonded ? rel(rng) * rEq : bondedpass::kNoBond;
    const float offset = bonded ? static_cast<float>(r0 - d.restRef) : bondedpass::kNoBondOffset;
    d.offset.push_back(offset);
    d.rest.push_back(exactDoubles ? r0 : d.restRef + static_cast<double>(offset)); // +∞: none
  }
  d.breaks.assign(blocks, 0);
  d.force.assign(3 * n, 0.0);
  return d;
}

bondedpass::BlockPass passOf(PassData& d, double sigma, bool kick, bool compact) {
  bondedpass::BlockPass p;
  p.x = d.x.data();
  p.n = d.x.size() / 3;
  p.blockStart = d.blockStart.data();
  p.partner = d.partner.data();
  p.rest = compact ? nullptr : d.rest.data();
  p.offset = compact ? d.offset.data() : nullptr;
  p.restRef = d.restRef;
  p.breaks = d.breaks.data();
  p.force = d.force.data();
  p.v = kick ? d.v.data() : nullptr;
  p.m = d.m.data();
  p.halfStep = 0.5e-10;
  const double rEq = ws2017::kTwoToOneSixth * sigma;
  p.terms = {sigma * sigma, ws2017::kHeadlineEpsilon, ws2017::kHeadlineKappa, rEq * rEq};
  p.rCut2 = 1.5 * sigma * 1.5 * sigma;
  return p;
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Two passes' outputs, bit for bit: forces, bond marks in either list, break counts, velocities.
void expectSameOutputs(const PassData& a, const PassData& b) {
  EXPECT_TRUE(sameBits(a.force, b.force)) << "forces differ";
  EXPECT_TRUE(sameBits(a.rest, b.rest)) << "bond marks differ";
  EXPECT_TRUE(sameBits(a.offset, b.offset)) << "bond marks differ (compact)";
  EXPECT_TRUE(sameBits(a.breaks, b.breaks)) << "per-block break counts differ";
  EXPECT_TRUE(sameBits(a.v, b.v)) << "velocities differ";
}

} // namespace

TEST(BondedForces, Avx512PassEqualsTheGenericPassBitForBit) {
  if (!bondedpass::avx512Available())
    GTEST_SKIP() << "this processor has no AVX-512: only the generic pass runs here";
  const double sigma = ws2017::headlineSigma();
  for (bool compact : {false, true})
    for (bool kick : {false, true}) {
      // The wide lists with rest lengths no float offset holds.
      PassData generic = makePass(1003, 12, sigma, 7, !compact), wide = generic;
      const std::size_t blocks = generic.breaks.size();
      const long brokeGeneric =
          bondedpass::blockForces(passOf(generic, sigma, kick, compact), 0, blocks);
      const long brokeWide =
          bondedpass::blockForcesAvx512(passOf(wide, sigma, kick, compact), 0, blocks);
      std::printf("compact %d, kick %d: %ld bonds beyond r_cut of %zu entries\n", compact, kick,
                  brokeGeneric, generic.rest.size());
      // The case must hold breaks and intact bonds, or it tests less than it claims.
      const long bonded = static_cast<long>(2 * generic.rest.size() / 3);
      ASSERT_GT(brokeGeneric, 0);
      ASSERT_LT(brokeGeneric, bonded);
      EXPECT_EQ(brokeWide, brokeGeneric);
      expectSameOutputs(wide, generic);
    }
}

// The compact lists (rest lengths as float offsets from r_eq) give the bits of the wide lists
// holding the same rest lengths as doubles, and mark the same bonds, in both passes.
TEST(BondedForces, CompactListsEqualTheWideListsBitForBit) {
  const double sigma = ws2017::headlineSigma();
  for (bool avx512 : {false, true}) {
    if (avx512 && !bondedpass::avx512Available())
      continue;
    const auto pass = avx512 ? bondedpass::blockForcesAvx512 : bondedpass::blockForces;
    PassData wide = makePass(1003, 12, sigma, 5), compact = wide;
    const std::vector<float> offsetBefore = compact.offset;
    const std::size_t blocks = wide.breaks.size();
    const long brokeWide = pass(passOf(wide, sigma, true, false), 0, blocks);
    const long brokeCompact = pass(passOf(compact, sigma, true, true), 0, blocks);
    ASSERT_GT(brokeWide, 0); // the case holds breaks
    EXPECT_EQ(brokeCompact, brokeWide);
    EXPECT_TRUE(sameBits(compact.force, wide.force)) << "forces differ";
    EXPECT_TRUE(sameBits(compact.v, wide.v)) << "half kicks differ";
    EXPECT_TRUE(sameBits(compact.breaks, wide.breaks)) << "per-block break counts differ";
    // Every entry as before but for the marks, and marked where the wide list is.
    for (std::size_t e = 0; e < wide.rest.size(); ++e)
      ASSERT_EQ(compact.offset[e], wide.rest[e] == bondedpass::kBreaking
                                       ? bondedpass::kBreakingOffset
                                       : offsetBefore[e])
          << "entry " << e;
  }
}

// The force pass with the kick-drift block by block (the solver's fused step) gives the bits of
// the pass followed by the kick-drift over the same particles: forces, bond marks, velocities,
// drifted positions and the velocities' spread, with and without the pending half kick, over
// chunks that end inside the blocks' range and a part-full last block (1,003 particles).
TEST(BondedForces, KickDriftBlockByBlockEqualsThePassThenTheKickDrift) {
  if (!bondedpass::avx512Available())
    GTEST_SKIP() << "this processor has no AVX-512: the fused pass does not run here";
  const double sigma = ws2017::headlineSigma();
  for (bool compact : {false, true})
    for (bool pending : {false, true}) {
      PassData split = makePass(1003, 12, sigma, 11);
      std::mt19937_64 rng(3);
      std::uniform_real_distribution<double> mass(0.5e-9, 2e-9); // particles of unequal masses
      for (double& m : split.m)
        m = mass(rng);
      PassData fused = split;
      const std::size_t n = split.m.size(), blocks = split.breaks.size();
      std::vector<double> xSplit(3 * n), xFused(3 * n);
      auto driftOf = [&](PassData& d, std::vector<double>& out) {
        return bondedpass::DriftPass{d.x.data(), out.data(), d.v.data(), d.force.data(),
                                     d.m.data(), 1e-10,      0.5e-10,    pending};
      };
      bondedpass::VelocitySpread spreadSplit, spreadFused;
      long brokeSplit = 0, brokeFused = 0;
      for (std::size_t b0 = 0; b0 < blocks; b0 += 40) { // chunks as the solver calls them
        const std::size_t b1 = std::min(blocks, b0 + 40);
        brokeSplit += bondedpass::blockForcesAvx512(passOf(split, sigma, false, compact), b0, b1);
        bondedpass::driftAvx512(driftOf(split, xSplit), 8 * b0, std::min(n, 8 * b1), spreadSplit);
        brokeFused += bondedpass::blockForcesDriftAvx512(
            passOf(fused, sigma, false, compact), driftOf(fused, xFused), b0, b1, spreadFused);
      }
      ASSERT_GT(brokeSplit, 0); // the case holds breaks
      EXPECT_EQ(brokeFused, brokeSplit);
      expectSameOutputs(fused, split);
      EXPECT_TRUE(sameBits(xFused, xSplit)) << "drifted positions differ";
      EXPECT_TRUE(sameBits(fused.x, split.x)) << "the current positions were written";
      EXPECT_NE(xFused, fused.x); // the particles moved
      const std::vector<double> a = {spreadFused.speed2, spreadFused.lo[0], spreadFused.lo[1],
                                     spreadFused.lo[2],  spreadFused.hi[0], spreadFused.hi[1],
                                     spreadFused.hi[2]},
                                b = {spreadSplit.speed2, spreadSplit.lo[0], spreadSplit.lo[1],
                                     spreadSplit.lo[2],  spreadSplit.hi[0], spreadSplit.hi[1],
                                     spreadSplit.hi[2]};
      EXPECT_TRUE(sameBits(a, b)) << "the velocities' spread differs";
    }
}

// The rebuild's candidate test: the AVX-512 version lists the same particles as the generic one
// and as a brute-force count, over ranges of every length modulo eight (the masked tails).
TEST(BondedForces, Avx512CandidateTestListsTheBruteForceNeighbours) {
  if (!bondedpass::avx512Available())
    GTEST_SKIP() << "this processor has no AVX-512: only the generic test runs here";
  Random rng(5);
  const std::size_t n = 613;
  std::vector<double> x(n), y(n), z(n);
  std::vector<std::uint32_t> id(n);
  for (std::size_t k = 0; k < n; ++k)
    x[k] = rng.uniform(-1.0, 1.0), y[k] = rng.uniform(-1.0, 1.0), z[k] = rng.uniform(-1.0, 1.0),
    id[k] = static_cast<std::uint32_t>(3 * k + 1);
  const bondedpass::NearScan scan{x.data(), y.data(), z.data(), id.data(), 0.8 * 0.8};
  std::size_t total = 0;
  for (std::size_t begin = 0; begin + 20 < n; begin += 19) {
    const std::size_t end = std::min(n, begin + 1 + begin % 41);
    const double at[3] = {x[begin], y[begin], z[begin]};
    std::vector<std::uint32_t> generic(end - begin + bondedpass::kLanes), wide = generic, brute;
    generic.resize(bondedpass::nearCandidates(scan, begin, end, at, id[begin], generic.data()));
    wide.resize(bondedpass::nearCandidatesAvx512(scan, begin, end, at, id[begin], wide.data()));
    for (std::size_t k = begin; k < end; ++k) {
      const double dx = x[k] - at[0], dy = y[k] - at[1], dz = z[k] - at[2];
      if (k != begin && dx * dx + dy * dy + dz * dz < 0.64)
        brute.push_back(id[k]);
    }
    EXPECT_EQ(generic, brute) << "range " << begin;
    EXPECT_EQ(wide, brute) << "range " << begin;
    total += brute.size();
  }
  EXPECT_GT(total, 50u); // the case must list neighbours, or it tests nothing
}

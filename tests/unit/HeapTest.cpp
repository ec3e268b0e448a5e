// Angle of repose of the SSDEM contact model (fixed-base heap, Solvers/analysis/HeapTest.h).
#include "analysis/HeapTest.h"

#include <gtest/gtest.h>

using namespace craterkit;

// The defaults are calibrated to a 30° friction angle (the SCI study's regolith). A base of
// 20 particle radii (5000 spheres) is the smallest heap whose two angle measures agree
// within a few degrees; the calibration itself used 30 radii (benchmarks/README.md).
TEST(HeapAngle, DefaultRegolithGivesThirtyDegrees) {
  const HeapTestResult h = runFixedBaseHeap(ContactParams{}, 20.0);
  EXPECT_NEAR(h.flankDegrees, 30.0, 4.0);
  EXPECT_NEAR(h.coneDegrees, 30.0, 4.0);
  EXPECT_GT(h.particlesHeap, 500u);
}

// Less sliding or rolling friction, a lower heap (12 radii: quick, same column every time).
TEST(HeapAngle, AngleGrowsWithSlidingAndRollingFriction) {
  const double base = 12.0;
  const HeapTestResult reference = runFixedBaseHeap(ContactParams{}, base);
  ContactParams lowSliding;
  lowSliding.muS = 0.3;
  ContactParams lowRolling;
  lowRolling.muR = 0.15;
  lowRolling.muT = 0.1875;
  ContactParams littleRolling; // (none at all: the column flows off a base this small)
  littleRolling.muR = 0.05;
  littleRolling.muT = 0.05;
  const double sliding = runFixedBaseHeap(lowSliding, base).coneDegrees;
  const double rolling = runFixedBaseHeap(lowRolling, base).coneDegrees;
  const double little = runFixedBaseHeap(littleRolling, base).coneDegrees;
  EXPECT_GT(reference.coneDegrees, sliding + 3.0);
  EXPECT_GT(reference.coneDegrees, rolling + 3.0);
  EXPECT_GT(rolling, little + 3.0);
}

// BondedRun (Watson & Steinhauser 2017 on the shared time-driven protocol): an earlier time
// gives the state it gave before, a run resumed from its checkpoint continues bit for bit, a
// checkpoint of another set-up or another Dissipation is refused, and a progress callback
// aborts the run.
#include "bonded/BondedRun.h"
#include "bonded/BondedBody.h"
#include "common/Error.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <string>

using namespace craterkit;

namespace {

BondedSystem smallImpact(double particles) {
  BondedImpactParams p;
  p.particleCount = particles;
  p.plateWidthRatio = 2.5;
  p.seed = 11;
  return buildBondedImpact(p);
}

bool sameState(const BondedSolver& a, const BondedSolver& b) {
  const auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
  };
  return a.stepCount() == b.stepCount() && a.brokenBonds() == b.brokenBonds() &&
         same(a.system().positions, b.system().positions) &&
         same(a.system().velocities, b.system().velocities) && a.bondBroken() == b.bondBroken();
}

} // namespace

TEST(BondedRun, EarlierTimeGivesTheSameStateAsBefore) {
  const BondedSystem start = smallImpact(800);
  BondedRun run(start, {}, 2);
  const BondedSolver first = run.advanceTo(4e-7);
  const BondedSolver second = run.advanceTo(9e-7);
  EXPECT_GT(second.brokenBonds(), 0u);
  EXPECT_TRUE(sameState(run.advanceTo(4e-7), first)); // from the kept snapshot
  EXPECT_TRUE(sameState(run.advanceTo(9e-7), second));
  BondedRun noneKept(start, {}, 0);
  noneKept.advanceTo(9e-7);
  EXPECT_TRUE(sameState(noneKept.advanceTo(4e-7), first)); // from the initial state
  EXPECT_TRUE(sameState(run.advanceTo(-1.0), BondedRun(start).solver()));
  std::printf("steps %llu and %llu, broken bonds %zu and %zu\n",
              static_cast<unsigned long long>(first.stepCount()),
              static_cast<unsigned long long>(second.stepCount()), first.brokenBonds(),
              second.brokenBonds());
}

TEST(BondedRun, ResumedFromCheckpointContinuesBitForBit) {
  const BondedSystem start = smallImpact(800);
  const std::string path = ::testing::TempDir() + "bonded_run_checkpoint.bin";
  std::remove(path.c_str());
  BondedRun whole(start);
  whole.advanceTo(1.2e-6);

  BondedRun interrupted(start);
  interrupted.advanceTo(5e-7, {}, path, 97);
  const double written = interrupted.checkpointTime();
  EXPECT_NEAR(written, 5e-7, interrupted.solver().timeStep());
  interrupted.advanceTo(2e-7, {}, path, 97); // going back never overwrites the file
  EXPECT_EQ(interrupted.checkpointTime(), written);

  BondedRun resumed(start);
  resumed.resumeFrom(path);
  EXPECT_EQ(resumed.time(), written);
  EXPECT_TRUE(sameState(resumed.advanceTo(1.2e-6), whole.solver()));

  BondedRun other(smallImpact(1500));
  EXPECT_THROW(other.resumeFrom(path), InputError);
  // The same particles and bonds with another step or another impact speed: refused too (an
  // earlier time would otherwise be replayed with this run's settings, not the file's).
  BondedSolverParams finer;
  finer.timeStepFraction = 0.5 * BondedSolverParams{}.timeStepFraction;
  BondedRun otherStep(start, finer);
  EXPECT_THROW(otherStep.resumeFrom(path), InputError);
  BondedSystem faster = start;
  faster.impactSpeed *= 1.5;
  BondedRun otherSpeed(faster);
  EXPECT_THROW(otherSpeed.resumeFrom(path), InputError);
  // The same set-up with shock heating: the file holds the paper's model, so it is refused
  // (by name) rather than continued with the model the file holds.
  BondedSolverParams heating;
  heating.dissipation = BondedDissipation::ShockViscosity;
  BondedRun otherModel(start, heating);
  try {
    otherModel.resumeFrom(path);
    ADD_FAILURE() << "a checkpoint of the paper's model resumed a ShockViscosity run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Dissipation None"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

TEST(BondedRun, ProgressCallbackAborts) {
  BondedRun run(smallImpact(800));
  double last = -1.0;
  EXPECT_THROW(run.advanceTo(1e-6,
                             [&](double f) {
                               last = f;
                               return f < 0.3;
                             }),
               Aborted);
  EXPECT_GE(last, 0.3);
  EXPECT_LT(last, 0.5);
}

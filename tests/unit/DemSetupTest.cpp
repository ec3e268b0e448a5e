// DemSetup: the container's walls (one wall per region) and the one choice of stiffness and
// time step, which follows the Hertz law when the contact law is Hertz.
#include "dem/DemSetup.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace craterkit;

namespace {
constexpr double kR = 0.05, kRho = 2000.0;
double sphereMass() { return kRho * 4.0 / 3.0 * M_PI * kR * kR * kR; }

ParticleSet one(double x, double y, double z, double vz = 0.0) {
  ParticleSet s;
  const double p[3] = {x, y, z};
  s.add(p, kR, kRho, 0, 0);
  s.velocity = {0, 0, vz};
  return s;
}
} // namespace

TEST(DemSetup, BowlContainerPushesAGrainAtItsRimOnce) {
  // A grain against the container just below the rim plane overlaps both the bowl and the
  // cylinder above it geometrically; each region has one wall, so it is pushed once, by the
  // bowl: one wall contact and the radial acceleration of one overlap k x / m.
  Container c;
  c.type = Container::Type::Bowl;
  c.bowlRadius = 1.0;
  DemParams p;
  p.walls = containerWalls(c);
  p.gravity.type = Gravity::Type::None;
  p.contact.kN = 1e5;
  p.contact.muS = p.contact.muR = p.contact.muT = 0.0;
  p.dt = pairCollisionTime(sphereMass(), p.contact.kN) / 200.0;
  const double overlap = 1e-4, z = -0.2 * kR;
  const double rho = std::sqrt(std::pow(c.bowlRadius - kR + overlap, 2) - z * z);
  DemSolver s(one(rho, 0.0, z), p);
  EXPECT_EQ(s.diagnostics().wallContacts, 1u);
  s.step();
  // After one kick-drift-kick step from rest the radial speed is dt k x / m (to O(dt²)).
  const double expected = p.dt * p.contact.kN * overlap / sphereMass();
  EXPECT_NEAR(-s.particles().velocity[0], expected, 0.02 * expected);
  // Above the rim plane the cylinder alone holds it.
  DemSolver above(one(c.bowlRadius - kR + overlap, 0.0, 0.2 * kR), p);
  EXPECT_EQ(above.diagnostics().wallContacts, 1u);
}

TEST(DemSetup, HertzStepFollowsTheHertzContactDuration) {
  // With the Hertz law the step is the Hertz wall contact's duration at the expected speed
  // over the steps per collision; a sphere dropped on a plane at that speed then stays in
  // contact for that many steps (20 m/s, where the Hertz contact is shorter than the
  // solver's stability time) (elastic: 2.868 (m² / (r E*² v))^(1/5), Johnson 1985 §11.4).
  StiffnessInput in{kR, kRho, 20.0, 0.01, 0.0, kR, 30.0};
  in.hertz = true;
  in.youngsModulus = 1e8;
  in.poissonRatio = 0.3;
  const StiffnessChoice k = chooseStiffnessAndStep(in);
  const double E = in.youngsModulus / (1.0 - in.poissonRatio * in.poissonRatio);
  const double duration = hertzCollisionTime(sphereMass(), kR, E, 20.0);
  EXPECT_NEAR(k.dt * 30.0, duration, 1e-12 * duration);

  DemParams p;
  p.contact.normalModel = "Hertz";
  p.contact.youngsModulus = in.youngsModulus;
  p.contact.poissonRatio = in.poissonRatio;
  p.contact.restitutionN = 1.0;
  p.contact.muS = p.contact.muR = p.contact.muT = 0.0;
  p.gravity.type = Gravity::Type::None;
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  p.dt = k.dt;
  // The contact is resolved by the chosen number of steps: 30 ± 2 (the step's own error in
  // placing the start and end).
  int inContact = 0;
  DemSolver again(one(0, 0, kR + 1e-9, -20.0), p);
  for (int i = 0; i < 1000; ++i) {
    again.step();
    if (again.particles().position[2] < kR)
      ++inContact;
    else if (inContact > 0)
      break;
  }
  EXPECT_NEAR(inContact, 30, 2);
  EXPECT_NEAR(again.particles().velocity[2], 20.0, 0.01 * 20.0); // elastic
}

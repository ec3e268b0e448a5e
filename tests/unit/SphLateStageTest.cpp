// The late-stage sound speed that falls with the crater's flow (sph/LateStageSchedule.h): its
// power law, the stage a restored solver takes up, the artificial viscosity it keeps, bad
// schedules; the late-stage Poisson ratio. The staged layer at rest is in SphOverburdenTest.cpp.
#include "SphColumns.h"
#include "sph/LateStageSchedule.h"
#include "sph/SphSolver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace craterkit;

// The staged c against its power law c0 (t/t_s)^(−q): c0 at the switch, never below the law nor
// more than one stage (2^(1/4)) above it, down to the floor, where it stays; a floor at or above
// c0 is one switch.
TEST(SphLateStage, SoundSpeedFollowsThePowerLawInQuarterOctaves) {
  SphParams par;
  par.lateStageTime = 1e-3, par.lateStageSoundSpeed = 0.5;
  par.lateStageInitialSoundSpeed = 90.0, par.lateStageSoundSpeedExponent = 0.6;
  EXPECT_EQ(lateStageSoundSpeedAt(par, 1e-3), 90.0);
  double last = 90.0;
  for (double t = 1e-3; t < 100.0; t *= 1.01) {
    const double c = lateStageSoundSpeedAt(par, t), law = 90.0 * std::pow(t / 1e-3, -0.6);
    ASSERT_LE(c, last) << "t = " << t;
    ASSERT_GE(c, std::max(0.5, law) * (1.0 - 1e-12)) << "t = " << t;
    ASSERT_LE(c, std::max(0.5, law * std::exp2(0.25)) * (1.0 + 1e-12)) << "t = " << t;
    last = c;
  }
  EXPECT_EQ(last, 0.5);
  par.lateStageInitialSoundSpeed = 0.0;
  EXPECT_EQ(lateStageSoundSpeedAt(par, 5.0), 0.5);
  par.lateStageInitialSoundSpeed = 0.4;
  EXPECT_EQ(lateStageSoundSpeedAt(par, 5.0), 0.5);
}

namespace {

// A granular soil (G = 0.35 K) on a rigid floor under 9.81 m/s², switched at 0.1 ms to the late
// law of c = 8 m/s, and its lithostatic column of 4 x 4 x 10 particles.
SphParams soilOnFloor() {
  SphParams par;
  const Material soil = sphtest::granularSoil(1500.0, 4e6, 7.0);
  Material floor = soil;
  floor.name = "floor", floor.rigid = true;
  par.materials = {soil, floor};
  par.gravity[2] = -9.81;
  par.lateStageTime = 1e-4, par.lateStageSoundSpeed = 8.0;
  return par;
}
SphState soilColumn(SphParams& par) {
  return sphtest::lithostaticColumn(par, 4, 10, 0.02, 1500.0, 9.81, 4e6, 7.0, 1.0);
}

} // namespace

// A solver restored at a time in the schedule (a resumed checkpoint) takes the stage it was
// written in: its law is the running solver's, then and after both have gone on.
TEST(SphLateStage, RestoredSolverTakesUpTheStageOfItsTime) {
  SphParams par = soilOnFloor();
  par.lateStageInitialSoundSpeed = 32.0, par.lateStageSoundSpeedExponent = 0.25;
  const SphState s = soilColumn(par);
  SphSolver running(s, par);
  running.advanceTo(2e-3);
  const double mid = running.lateStageSoundSpeed();
  EXPECT_LT(mid, 32.0);
  EXPECT_GT(mid, 8.0);
  SphSolver restored(running.state(), par, {running.time(), running.steps(), 0.0});
  EXPECT_EQ(restored.lateStageSoundSpeed(), mid);
  EXPECT_EQ(restored.params().materials[0].eos.murnaghanK0,
            running.params().materials[0].eos.murnaghanK0);
  running.advanceTo(0.03), restored.advanceTo(0.03);
  EXPECT_EQ(restored.lateStageSoundSpeed(), 8.0);
  EXPECT_EQ(running.lateStageSoundSpeed(), 8.0);
}

namespace {

// The kinetic energy left, as a fraction, of a shear wave v_x = V sin(2π z / L) in a periodic
// cube of fluid (8³ particles, L = 0.16 m, Murnaghan K = 4 MPa, n = 7, no strength, no gravity)
// switched at 0.1 ms to the late law of c = 2 m/s, or with c0 > 0 to a c falling from c0 as
// (t / 0.1 ms)^(−0.1) (still above 8 m/s at the end), after 50 ms.
double shearWaveEnergyLeft(double c0) {
  const int n = 8;
  const double dx = 0.02, L = n * dx, rho0 = 1000.0, V = 0.01;
  Material fluid;
  fluid.name = "fluid";
  fluid.eos.model = EquationOfState::Model::Murnaghan;
  fluid.eos.murnaghanRho0 = rho0, fluid.eos.murnaghanK0 = 4e6, fluid.eos.murnaghanN = 7.0;
  fluid.bulkModulus = 4e6;
  SphParams par;
  par.materials = {fluid};
  for (int a = 0; a < 3; ++a)
    par.periodic[a] = true, par.boxLo[a] = 0.0, par.boxHi[a] = L;
  par.lateStageTime = 1e-4, par.lateStageSoundSpeed = 2.0;
  par.lateStageInitialSoundSpeed = c0, par.lateStageSoundSpeedExponent = 0.1;
  SphState s;
  const double pi = std::acos(-1.0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        const double v[3] = {V * std::sin(2.0 * pi * x[2] / L), 0.0, 0.0};
        s.add(x, v, rho0 * dx * dx * dx, rho0, 0.0, 0);
      }
  SphSolver solver(s, par);
  const double e0 = solver.kineticEnergy();
  solver.advanceTo(0.05);
  const double left = solver.kineticEnergy() / e0;
  std::printf("shear wave, late-stage c %s: kinetic energy left %.4f (c at the end %.3g m/s)\n",
              c0 > 0.0 ? "falling" : "2 m/s throughout", left, solver.lateStageSoundSpeed());
  return left;
}

} // namespace

// The artificial viscosity's linear term, α c h, is the flow's numerical viscosity in the late
// stage. With c falling from a higher c0 it keeps the final c's α c (α scaled by c_final / c):
// a shear wave, which neither compresses nor needs the sound speed, then decays as it does under
// the final law throughout. The bound, 10 %, is what the two runs' other differences allow (step
// sizes, density noise); with α unscaled the wave decays as (c0 / c)-fold larger viscosity
// would make it, to a small fraction of the final law's.
TEST(SphLateStage, FallingSoundSpeedKeepsTheFinalLawsViscosity) {
  const double constant = shearWaveEnergyLeft(0.0), falling = shearWaveEnergyLeft(16.0);
  EXPECT_LT(constant, 0.9); // the viscosity acts: the test can tell it
  EXPECT_NEAR(falling / constant, 1.0, 0.1);
}

// Bad input: a negative initial sound speed, an exponent outside (0, 2] or a falling c with the
// switch at t = 0 is refused, naming the property.
TEST(SphLateStage, BadScheduleIsRefused) {
  auto message = [](double c0, double q, double t) {
    SphParams par;
    par.lateStageTime = t, par.lateStageSoundSpeed = 1.0;
    par.lateStageInitialSoundSpeed = c0, par.lateStageSoundSpeedExponent = q;
    return sphtest::refusal(par);
  };
  EXPECT_NE(message(-1.0, 0.6, 1e-3).find("initial sound speed"), std::string::npos);
  EXPECT_NE(message(NAN, 0.6, 1e-3).find("initial sound speed"), std::string::npos);
  EXPECT_NE(message(10.0, 0.0, 1e-3).find("exponent"), std::string::npos);
  EXPECT_NE(message(10.0, 3.0, 1e-3).find("exponent"), std::string::npos);
  EXPECT_NE(message(10.0, 0.6, 0.0).find("time after 0"), std::string::npos);
  EXPECT_EQ(message(10.0, 0.6, 1e-3), "");
  EXPECT_EQ(message(0.0, 0.0, 1e-3), ""); // one switch: the exponent is not read
}

// The shear modulus at the switch. The SCI regolith (data/materials/regolith.cfg: a basalt
// matrix's K = A = 26.7 GPa with the porous bulk's G = 20 MPa, so nu = 0.49963) keeping its
// Poisson ratio at c = 0.46637 m/s keeps G = 0.44 Pa of K' = 2700 c^2 = 587 Pa: shear waves at
// 2 cm/s, and a Drucker-Prager yield stress of 0.4 Pa (4 m deep at Ryugu's gravity, 30 deg)
// needs a shear strain of about 0.5 to reach. LateStagePoissonRatio 0.25 gives it G = 0.6 K' =
// 352 Pa. In a solver, the switch applies the ratio.
TEST(SphLateStage, PoissonRatioSetsTheLateShearModulus) {
  Material regolith;
  regolith.eos.model = EquationOfState::Model::Tillotson;
  regolith.eos.tillotson.rho0 = 2700.0;
  regolith.bulkModulus = 26.7e9, regolith.shearModulus = 2e7;
  regolith.strength = Material::Strength::DruckerPrager;
  Material kept = regolith, set = regolith;
  const double c = 0.46637, K = 2700.0 * c * c;
  const double keptScale = kept.switchToLateStage(c);
  EXPECT_NEAR(kept.shearModulus, 0.44, 0.005);
  EXPECT_NEAR(keptScale, kept.shearModulus / 2e7, 1e-15);
  const double setScale = set.switchToLateStage(c, 0.25);
  EXPECT_NEAR(set.bulkModulus, K, 1e-9 * K);
  EXPECT_NEAR(set.shearModulus, 0.6 * K, 1e-9 * K);
  EXPECT_NEAR(setScale, 0.6 * K / 2e7, 1e-15);

  // In a solver: the soil column (G = 0.35 K, so nu = 0.3433) of soilOnFloor, with nu 0.25 and
  // with its own: G' = 3 K' (1 - 2 nu) / (2 (1 + nu)), K' = rho0 c^2.
  for (const double nu : {0.25, -1.0}) {
    SphParams par = soilOnFloor();
    par.lateStagePoissonRatio = nu;
    SphSolver solver(soilColumn(par), par);
    solver.advanceTo(2e-4);
    const double Kl = 1500.0 * 8.0 * 8.0, nuUsed = nu >= 0.0 ? nu : (3.0 - 0.7) / (2.0 * 3.35);
    const double expected = 3.0 * Kl * (1.0 - 2.0 * nuUsed) / (2.0 * (1.0 + nuUsed));
    EXPECT_NEAR(solver.params().materials[0].shearModulus, expected, 1e-9 * expected)
        << "nu " << nu;
  }

  // Bad input: a ratio of 0.5 or more, or not a number, is refused, naming the property.
  auto message = [](double nu) {
    SphParams par;
    par.lateStageTime = 1e-3, par.lateStageSoundSpeed = 1.0, par.lateStagePoissonRatio = nu;
    return sphtest::refusal(par);
  };
  EXPECT_NE(message(0.5).find("Poisson ratio"), std::string::npos);
  EXPECT_NE(message(NAN).find("Poisson ratio"), std::string::npos);
  EXPECT_EQ(message(0.25), "");
  EXPECT_EQ(message(-1.0), "");
}

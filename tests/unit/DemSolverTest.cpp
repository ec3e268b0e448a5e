// SSDEM solver: analytic collisions, friction laws, conservation, neighbour oracle, restart.
#include "dem/DemSolver.h"
#include "bed/GranularBed.h"
#include "common/Error.h"
#include "common/Random.h"
#include "dem/DemRun.h"
#include "dem/ParticleContacts.h"
#include "dem/WorkShares.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>

using namespace craterkit;

namespace {

constexpr double kR = 0.05, kRho = 2000.0;
double sphereMass(double r = kR) { return kRho * 4.0 / 3.0 * M_PI * r * r * r; }

ParticleSet one(double x, double y, double z, double vx, double vy, double vz, double r = kR) {
  ParticleSet s;
  const double p[3] = {x, y, z};
  s.add(p, r, kRho, 0, 0);
  s.velocity = {vx, vy, vz};
  return s;
}

// The scheme's restitution error comes from where in a step a contact starts: measured
// 0.4-2.3 % at 30-50 steps per contact and below 0.4 % at 200 (pair, e = 0.3-0.9), so the
// 1 % checks run at 200 steps per contact.
DemParams frictionless(double restitution, double vmax = 1.0, double steps = 200.0) {
  DemParams p;
  p.contact.restitutionN = restitution;
  p.contact.restitutionT = 1.0;
  p.contact.muS = p.contact.muR = p.contact.muT = 0.0;
  const StiffnessProposal k = proposeStiffness(kR, kRho, vmax, 0.01, 0.0, 0.0, steps);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.gravity.type = Gravity::Type::None;
  return p;
}

Eigen::Vector3d velocityOf(const DemSolver& s, std::size_t i) {
  const auto& v = s.particles().velocity;
  return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

// The solver orders particles spatially: find one by its Id.
std::size_t indexOf(const DemSolver& s, std::int64_t id) {
  const auto& ids = s.particles().id;
  return static_cast<std::size_t>(std::find(ids.begin(), ids.end(), id) - ids.begin());
}

} // namespace

// A free sphere's velocity is the impulse of gravity per unit mass, ∫ g dt; changing gravity
// mid-run (the bed settling lowers it) changes the acceleration from the next step on. The
// leapfrog's half kicks straddle the change, so the velocity may differ from the two stages'
// sum by half a step of the difference, no more.
TEST(DemGravity, SetGravityChangesTheAccelerationFromTheNextStep) {
  DemParams p = frictionless(0.5);
  const double g1 = 9.81, g2 = 1.5;
  p.gravity = Gravity::downward(g1);
  DemSolver solver(one(0, 0, 0, 0, 0, 0), p);
  const int n1 = 40, n2 = 60;
  for (int i = 0; i < n1; ++i)
    solver.step();
  solver.setGravity(Gravity::downward(g2));
  for (int i = 0; i < n2; ++i)
    solver.step();
  const double expected = -(g1 * n1 + g2 * n2) * p.dt;
  EXPECT_NEAR(velocityOf(solver, 0)[2], expected, 0.5 * (g1 - g2) * p.dt + 1e-12);
  // Without the change the sphere would be much faster.
  EXPECT_GT(velocityOf(solver, 0)[2], -g1 * (n1 + n2) * p.dt + 0.5 * (g1 - g2) * n2 * p.dt);
  Gravity bad = Gravity::downward(g1);
  bad.vector[2] = std::nan("");
  EXPECT_THROW(solver.setGravity(bad), InputError);
}

TEST(DemContact, DampingCoefficientFormula) {
  // Schwartz 2012 Eq. 15 at e = 0.55 and 0.8 (docs/physics.md §1.2: 0.374 and 0.142 sqrt(k mu)).
  EXPECT_NEAR(dashpotCoefficient(1.0, 0.55, 1.0), 0.374, 5e-4);
  EXPECT_NEAR(dashpotCoefficient(1.0, 0.8, 1.0), 0.142, 5e-4);
  EXPECT_EQ(dashpotCoefficient(1.0, 1.0, 1.0), 0.0);
}

TEST(DemContact, ProposedStiffnessMatchesWorkedExample) {
  const StiffnessProposal p = proposeStiffness(0.05, 2000.0, 10.0, 0.01, 0.0, 0.0, 30.0);
  EXPECT_NEAR(p.kN, 4.19e8, 0.01e8);
  EXPECT_NEAR(p.collisionTime, 1.11e-4, 0.01e-4);
  EXPECT_NEAR(p.dt, p.collisionTime / 30.0, 1e-12);
}

class DropTest : public ::testing::TestWithParam<double> {};

TEST_P(DropTest, SphereOnPlaneReboundsWithRestitution) {
  const double e = GetParam();
  DemParams p = frictionless(e);
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  DemSolver s(one(0, 0, kR + 1e-4, 0, 0, -1.0), p);
  double contactStart = -1, contactEnd = -1;
  for (int k = 0; k < 100000 && contactEnd < 0; ++k) {
    s.step();
    const bool touching = s.particles().position[2] < kR;
    if (touching && contactStart < 0)
      contactStart = s.time();
    if (!touching && contactStart >= 0)
      contactEnd = s.time();
  }
  ASSERT_GT(contactEnd, 0.0) << "no rebound";
  EXPECT_NEAR(velocityOf(s, 0)[2] / 1.0, e, 0.01 * e);
  // The clipped law's force vanishes at ω1 t = θ = atan2(2γω1, 2γ² - 1) in units of
  // sqrt(m/k), with γ = f/2 and ω1 = sqrt(1 - γ²) (Schwäger & Pöschel 2007), while the
  // overlap x = e^{-γt} sin(ω1 t)/ω1 (units v0 sqrt(m/k)) has not closed yet: the sphere
  // leaves it at the rebound speed e v0.
  const double m = sphereMass();
  const double g = 0.5 * clippedDampingFactor(NormalLawKind::LinearSpringDashpot, e);
  const double w1 = std::sqrt(1.0 - g * g), theta = std::atan2(2 * g * w1, 2 * g * g - 1);
  const double left = std::exp(-g * theta / w1) * std::sin(theta) / w1;
  const double duration = (theta / w1 + left / e) * std::sqrt(m / p.contact.kN);
  EXPECT_NEAR(contactEnd - contactStart, duration, 0.03 * duration);
}

INSTANTIATE_TEST_SUITE_P(Restitution, DropTest, ::testing::Values(0.2, 0.55, 0.8, 1.0));

TEST(DemContact, HeadOnPairReboundsWithRestitution) {
  for (double e : {0.3, 0.55, 0.9}) {
    DemParams p = frictionless(e, 2.0);
    ParticleSet s = one(-kR - 1e-4, 0, 0, 1.0, 0, 0);
    const double x2[3] = {kR + 1e-4, 0, 0};
    s.add(x2, kR, kRho, 0, 1);
    s.velocity[3] = -1.0;
    DemSolver solver(s, p);
    solver.advanceTo(0.01);
    const std::size_t a = indexOf(solver, 0), b = indexOf(solver, 1);
    const double relative = velocityOf(solver, b)[0] - velocityOf(solver, a)[0];
    EXPECT_NEAR(relative / 2.0, e, 0.01 * e);
    EXPECT_NEAR(velocityOf(solver, a)[0] + velocityOf(solver, b)[0], 0.0, 1e-12);
  }
}

TEST(DemContact, HertzDropReboundsWithRestitution) {
  for (double e : {0.5, 0.8}) {
    DemParams p = frictionless(e);
    p.contact.normalModel = "Hertz";
    p.contact.youngsModulus = 1e7;
    p.contact.poissonRatio = 0.3;
    p.dt = 2e-6; // the contact lasts about 8.6 ms (Hertz: 2.87 (m^2 / (r E*^2 v))^(1/5))
    p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
    DemSolver s(one(0, 0, kR + 1e-5, 0, 0, -1.0), p);
    s.advanceTo(0.02);
    ASSERT_GT(s.particles().position[2], kR);
    EXPECT_NEAR(velocityOf(s, 0)[2], e, 0.02 * e);
  }
}

namespace {
// A sphere resting on the floor z = 0 under gravity g: the parameters and its rest height.
DemParams onFloor(double g, double& restHeight) {
  DemParams p;
  const StiffnessProposal k = proposeStiffness(kR, kRho, 1.0, 0.01, g, 0.1, 50.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.gravity.vector = {0, 0, -g};
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  restHeight = kR - sphereMass() * g / p.contact.kN;
  return p;
}
} // namespace

TEST(DemFriction, SlidingSphereDeceleratesAtMuGThenRolls) {
  const double g = 9.81, mu = 0.3, v0 = 2.0;
  double rest;
  DemParams p = onFloor(g, rest);
  p.contact.muS = mu;
  p.contact.muR = p.contact.muT = 0.0;
  p.contact.restitutionN = 0.3;
  DemSolver s(one(0, 0, rest, v0, 0, 0), p);
  // Slip lasts 2 v0 / (7 mu g): measure the deceleration over its middle half.
  const double slip = 2.0 * v0 / (7.0 * mu * g);
  s.advanceTo(0.25 * slip);
  const double v1 = velocityOf(s, 0)[0], t1 = s.time();
  s.advanceTo(0.75 * slip);
  const double v2 = velocityOf(s, 0)[0], t2 = s.time();
  EXPECT_NEAR((v1 - v2) / (t2 - t1), mu * g, 0.02 * mu * g);
  s.advanceTo(1.5 * slip);
  EXPECT_NEAR(velocityOf(s, 0)[0], 5.0 / 7.0 * v0, 0.01 * v0);
  const double spin = s.particles().angularVelocity[1];
  EXPECT_NEAR(spin * kR, velocityOf(s, 0)[0], 0.01 * v0); // rolling without slip
}

TEST(DemFriction, RollingSphereStopsAsRollingFrictionPredicts) {
  // At the slider limit M = mu_r beta r m g opposes rolling: dv/dt = -(5/7) mu_r beta g.
  const double g = 9.81, muR = 0.1, beta = 0.5, v0 = 0.5;
  double rest;
  DemParams p = onFloor(g, rest);
  p.contact.muS = 0.8;
  p.contact.muR = muR;
  p.contact.beta = beta;
  p.contact.muT = 0.0;
  ParticleSet ball = one(0, 0, rest, v0, 0, 0);
  ball.angularVelocity = {0, v0 / rest, 0};
  DemSolver s(ball, p);
  const double decel = 5.0 / 7.0 * muR * beta * g;
  const double stop = v0 / decel;
  s.advanceTo(0.2 * stop);
  const double va = velocityOf(s, 0)[0], ta = s.time();
  s.advanceTo(0.7 * stop);
  const double vb = velocityOf(s, 0)[0], tb = s.time();
  EXPECT_NEAR((va - vb) / (tb - ta), decel, 0.03 * decel);
  s.advanceTo(1.2 * stop);
  EXPECT_LT(std::abs(velocityOf(s, 0)[0]), 0.02 * v0);
  EXPECT_NEAR(s.particles().position[0], v0 * v0 / (2 * decel), 0.03 * v0 * v0 / (2 * decel));
}

namespace {
// A dense HCP box of equal spheres with random velocities, as DEM input; squeeze < 1
// pulls the lattice together so that every neighbour pair starts in contact.
ParticleSet jostledBlock(double speed, std::uint64_t seed, double squeeze = 1.0, double r = kR,
                         double cells = 12.0) {
  GranularBedParams bp;
  bp.packing = GranularBedParams::Packing::HCP;
  bp.container.type = Container::Type::Box;
  bp.container.boxSize = {cells * r, cells * r, cells * r};
  bp.sizes.radius = r;
  bp.particleDensity = kRho;
  ParticleSet s = generateGranularBed(bp);
  for (std::size_t i = 0; i < s.size(); ++i) {
    s.position[3 * i] *= squeeze;
    s.position[3 * i + 1] *= squeeze;
    s.position[3 * i + 2] = -0.5 * cells * r + (s.position[3 * i + 2] + 0.5 * cells * r) * squeeze;
  }
  Random rng(seed);
  for (double& v : s.velocity)
    v = rng.uniform(-speed, speed);
  return s;
}
} // namespace

TEST(DemConservation, ElasticFrictionlessBoxConservesEnergy) {
  ParticleSet s = jostledBlock(0.5, 3, 0.996);
  // (squeeze 0.996 below matches the walls)
  ASSERT_GT(s.size(), 150u);
  DemParams p = frictionless(1.0, 1.0, 100.0);
  // Walls at the squeezed block's faces, so that it stays dense.
  const double q = 0.996;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0}, nlo{0, 0, 0}, nhi{0, 0, 0};
    lo[k] = k == 2 ? -6 * kR - 6 * kR * q : -6 * kR * q;
    hi[k] = k == 2 ? -6 * kR + 6 * kR * q : 6 * kR * q;
    nlo[k] = 1.0;
    nhi[k] = -1.0;
    p.walls.push_back(Wall::plane(lo, nlo));
    p.walls.push_back(Wall::plane(hi, nhi));
  }
  DemSolver solver(s, p);
  const double e0 = solver.diagnostics().totalEnergy();
  double worst = 0.0;
  for (int k = 0; k < 10; ++k) {
    for (int j = 0; j < 1000; ++j)
      solver.step();
    worst = std::max(worst, std::abs(solver.diagnostics().totalEnergy() - e0) / e0);
  }
  EXPECT_GT(solver.diagnostics().contacts, 50u); // still colliding at the end
  EXPECT_LT(worst, 1e-4);
}

TEST(DemConservation, IsolatedFrictionalClusterConservesMomenta) {
  ParticleSet s = jostledBlock(0.3, 5, 0.995);
  Random rng(9);
  for (double& w : s.angularVelocity)
    w = rng.uniform(-5.0, 5.0);
  DemParams p;
  p.gravity.type = Gravity::Type::None;
  const StiffnessProposal k = proposeStiffness(kR, kRho, 1.0, 0.01, 0.0, 0.0, 30.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.contact.cohesion = 10.0;
  DemSolver solver(s, p);
  const DemDiagnostics a = solver.diagnostics();
  EXPECT_GT(a.contacts, 300u);
  for (int j = 0; j < 2000; ++j)
    solver.step();
  const DemDiagnostics b = solver.diagnostics();
  double scaleP = 0.0, scaleL = 0.0;
  const auto& st = solver.particles();
  for (std::size_t i = 0; i < st.size(); ++i) {
    const Eigen::Vector3d x(st.position[3 * i], st.position[3 * i + 1], st.position[3 * i + 2]);
    scaleP += st.mass[i] * velocityOf(solver, i).norm();
    scaleL +=
        st.mass[i] * x.norm() * velocityOf(solver, i).norm() + 0.4 * st.mass[i] * kR * kR * 5.0;
  }
  EXPECT_LT((b.momentum - a.momentum).norm(), 1e-12 * scaleP);
  EXPECT_LT((b.angularMomentum - a.angularMomentum).norm(), 1e-12 * scaleL);
}

TEST(DemNeighbours, ContactsMatchBruteForceOracle) {
  Random rng(21);
  ParticleSet s;
  const std::size_t n = 600;
  for (std::size_t i = 0; i < n; ++i) {
    const double x[3] = {rng.uniform(0, 1.0), rng.uniform(0, 1.0), rng.uniform(0, 1.0)};
    s.add(x, rng.uniform(0.02, 0.05), kRho, 0, static_cast<std::int64_t>(i));
  }
  for (double& v : s.velocity)
    v = rng.uniform(-1, 1);
  DemParams p;
  p.gravity.type = Gravity::Type::None;
  p.contact.kN = 1e5;
  p.dt = 1e-5;
  p.initialOverlapLimit = 10.0; // random placement overlaps; the oracle does not care
  p.overlapAbort = 10.0;
  DemSolver solver(s, p);
  auto oracle = [&](const ParticleSet& st) {
    std::set<std::pair<std::size_t, std::size_t>> out;
    for (std::size_t i = 0; i < st.size(); ++i)
      for (std::size_t j = i + 1; j < st.size(); ++j) {
        double d2 = 0;
        for (int k = 0; k < 3; ++k)
          d2 += std::pow(st.position[3 * i + k] - st.position[3 * j + k], 2);
        if (std::sqrt(d2) < st.radius[i] + st.radius[j])
          out.emplace(i, j);
      }
    return out;
  };
  for (int round = 0; round < 4; ++round) {
    const auto pairs = solver.contactPairs();
    const std::set<std::pair<std::size_t, std::size_t>> got(pairs.begin(), pairs.end());
    EXPECT_EQ(got, oracle(solver.particles())) << "round " << round;
    EXPECT_EQ(solver.diagnostics().contacts, got.size());
    for (int j = 0; j < 400; ++j)
      solver.step();
  }
  EXPECT_GT(solver.neighbourBuilds(), 1u);
}

// The force gather sums each particle's contacts in the order of the pair list (first-member
// rows by second member, then second-member rows by first member), which keeps the sums
// bit-identical for any thread count: the per-particle index must list every row of the table
// once, in that order, however many threads build it and however unevenly the particles are
// split among them (the splits follow the threads' measured times, dem/WorkShares.h), and
// whichever particles are handled as shared (indexed after the earlier threads' rows).
TEST(DemNeighbours, ParticleContactsListEveryRowInListOrder) {
  Random rng(5);
  const std::size_t n = 300;
  // A sorted half list of random pairs, a third of them in contact (the table's rows).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> listed;
  for (std::size_t e = 0; e < 2000; ++e) {
    const auto a = static_cast<std::uint32_t>(rng.uniform(0, n - 1));
    const auto b = static_cast<std::uint32_t>(rng.uniform(a + 1, n));
    listed.emplace_back(a, std::min<std::uint32_t>(b, n - 1));
  }
  listed.erase(std::remove_if(listed.begin(), listed.end(),
                              [](const auto& q) { return q.first >= q.second; }),
               listed.end());
  std::sort(listed.begin(), listed.end());
  listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
  std::vector<std::size_t> secondStart(n + 1, 0);
  for (const auto& q : listed)
    ++secondStart[q.second + 1];
  for (std::size_t i = 0; i < n; ++i)
    secondStart[i + 1] += secondStart[i];
  ContactTable table;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> rows;
  for (const auto& q : listed)
    if (rng.uniform() < 1.0 / 3.0)
      rows.push_back(q);
  table.resize(rows.size());
  for (std::size_t c = 0; c < rows.size(); ++c) {
    table.first[c] = rows[c].first;
    table.second[c] = rows[c].second;
  }
  for (std::size_t threads : {1u, 2u, 3u, 7u}) {
    // Random ranges, some of them empty, covering the particles.
    std::vector<std::size_t> cut{0, n};
    for (std::size_t t = 1; t < threads; ++t)
      cut.push_back(static_cast<std::size_t>(rng.uniform(0, n)));
    std::sort(cut.begin(), cut.end());
    // Each thread's rows are those of its first members; a particle that is the second member
    // of an earlier thread's row is shared, and so are some others at random (a superset of
    // the shared ones must do as well).
    const std::uint64_t stamp = 7;
    std::vector<std::uint64_t> shared(n, 0);
    std::vector<std::size_t> rowCut(threads + 1, 0);
    for (std::size_t t = 0; t <= threads; ++t)
      while (rowCut[t] < rows.size() && rows[rowCut[t]].first < cut[t])
        ++rowCut[t];
    for (std::size_t t = 0; t < threads; ++t)
      for (std::size_t c = rowCut[t]; c < rowCut[t + 1]; ++c)
        if (rows[c].second >= cut[t + 1] || rng.uniform() < 0.05)
          shared[rows[c].second] = stamp;
    ParticleContacts pc;
    pc.resize(n, listed.size());
    for (std::size_t t = 0; t < threads; ++t) // the first thread as the solver calls it: no marks
      pc.indexOwnRows(table, secondStart, cut[t], cut[t + 1], rowCut[t], rowCut[t + 1],
                      t == 0 ? nullptr : shared.data(), stamp);
    for (std::size_t t = 1; t < threads; ++t)
      pc.indexSharedRows(table, secondStart, cut[t], cut[t + 1], rowCut[t + 1], shared.data(),
                         stamp);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::size_t> firstWant, secondWant, firstGot, secondGot;
      for (std::size_t c = 0; c < rows.size(); ++c) {
        if (rows[c].first == i)
          firstWant.push_back(c);
        if (rows[c].second == i)
          secondWant.push_back(c);
      }
      for (std::size_t q = 0; q < pc.firstCount[i]; ++q)
        firstGot.push_back(pc.firstBegin[i] + q);
      for (std::size_t q = 0; q < pc.secondCount[i]; ++q)
        secondGot.push_back(pc.secondRow[secondStart[i] + q]);
      EXPECT_EQ(firstGot, firstWant) << "particle " << i << ", " << threads << " threads";
      EXPECT_EQ(secondGot, secondWant) << "particle " << i << ", " << threads << " threads";
    }
  }
}

namespace {
DemParams frictionalBox() {
  DemParams p;
  const StiffnessProposal k = proposeStiffness(kR, kRho, 1.0, 0.01, 9.81, 0.6, 30.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.walls.push_back(Wall::plane({0, 0, -12 * kR}, {0, 0, 1}));
  p.walls.push_back(Wall::cylinder({0, 0, 0}, {0, 0, 1}, 9 * kR));
  p.walls.push_back(Wall::bowl({0, 0, 0}, 16 * kR));
  return p;
}
} // namespace

TEST(DemRestart, ResumedRunIsBitIdentical) {
  const ParticleSet s = jostledBlock(0.5, 7);
  const DemParams p = frictionalBox();
  DemSolver straight(s, p);
  for (int j = 0; j < 300; ++j)
    straight.step();
  std::stringstream checkpoint;
  straight.writeCheckpoint(checkpoint);
  const std::string snapshot = straight.checkpointBytes();
  for (int j = 0; j < 500; ++j)
    straight.step();

  const std::string bytes = checkpoint.str();
  std::istringstream in(bytes);
  // From the file's bytes, and from the in-memory snapshot (DemRun's kept states), which must
  // be the same bytes.
  for (DemSolver resumed :
       {DemSolver::readCheckpoint(in, bytes.size()), DemSolver::fromCheckpointBytes(snapshot)}) {
    EXPECT_EQ(resumed.stepCount(), 300);
    for (int j = 0; j < 500; ++j)
      resumed.step();
    EXPECT_EQ(resumed.particles().position, straight.particles().position);
    EXPECT_EQ(resumed.particles().velocity, straight.particles().velocity);
    EXPECT_EQ(resumed.particles().angularVelocity, straight.particles().angularVelocity);
  }
  EXPECT_TRUE(snapshot == bytes);
  EXPECT_GT(straight.diagnostics().contacts, 50u);
}

// The wall histories are stored for the (particle, wall) pairs within reach only: a wall no
// particle reaches adds its own record (type, point, normal, radius: 60 bytes) and nothing per
// particle (one history per particle and wall, the CKDEMCP1 layout, added 81 bytes a particle
// for it: 405 a particle in a five-walled box).
TEST(DemRestart, CheckpointKeepsOnlyTheWallsWithinReach) {
  const ParticleSet s = jostledBlock(0.5, 7);
  const DemParams p = frictionalBox();
  DemParams far = p;
  far.walls.push_back(Wall::plane({0, 0, -1000 * kR}, {0, 0, 1}));
  DemSolver a(s, p), b(s, far);
  for (int j = 0; j < 50; ++j) {
    a.step();
    b.step();
  }
  ASSERT_EQ(a.particles().position, b.particles().position);
  EXPECT_EQ(b.checkpointBytes().size() - a.checkpointBytes().size(), 60u);
}

// A requested state is kept when the run leaves it, not when it reaches it (the solver holds
// it until then): a run asked for one time keeps nothing; asked for a later one, it keeps the
// first; asked for the first again, it restores it bit for bit from that snapshot.
TEST(DemRestart, RequestedStateIsKeptOnlyWhenTheRunLeavesIt) {
  const ParticleSet s = jostledBlock(0.5, 7);
  const DemParams p = frictionalBox();
  DemRun run(s, p, 0.0, 16);
  run.advanceTo(100 * p.dt);
  const std::vector<double> first = run.solver().particles().position;
  EXPECT_EQ(run.keptCount(), 0u);
  run.advanceTo(100 * p.dt); // the same time again: the run does not move
  EXPECT_EQ(run.keptCount(), 0u);
  run.advanceTo(200 * p.dt);
  EXPECT_EQ(run.keptCount(), 1u);
  run.advanceTo(100 * p.dt);
  EXPECT_EQ(run.solver().stepCount(), 100);
  EXPECT_EQ(run.solver().particles().position, first);
  EXPECT_EQ(run.keptCount(), 2u); // the state at step 200 was kept as the run went back
}

// A run given the initial state as a function (the DEMIntegrator's, which rebuilds it from its
// input instead of holding a copy) asks for it only when it goes back before every kept state.
TEST(DemRestart, GoingBackToTheStartAsksForTheInitialStateAgain) {
  const ParticleSet s = jostledBlock(0.5, 7);
  const DemParams p = frictionalBox();
  int asked = 0;
  DemRun run(
      s,
      [&] {
        ++asked;
        return s;
      },
      p, 0.0, 0);
  run.advanceTo(100 * p.dt);
  const std::vector<double> first = run.solver().particles().position;
  run.advanceTo(200 * p.dt);
  EXPECT_EQ(asked, 0);
  run.advanceTo(100 * p.dt);
  EXPECT_EQ(asked, 1);
  EXPECT_EQ(run.solver().particles().position, first);
}

// A run resumed from its checkpoint file and then asked for an earlier time (a script that
// walks its output times from the start again) recomputes that time from the initial state
// and must not overwrite the file with the earlier state; every requested state is written.
TEST(DemRestart, EarlierRequestsNeverOverwriteALaterCheckpoint) {
  const ParticleSet s = jostledBlock(0.5, 7);
  const DemParams p = frictionalBox();
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("ck_demrun_" + std::to_string(::getpid()) + ".ckdem"))
                               .string();
  const auto stepInFile = [&] { return DemSolver::readCheckpoint(path).stepCount(); };
  DemSolver straight(s, p);
  std::vector<std::vector<double>> at(401);
  for (int j = 0; j <= 400; ++j) {
    at[j] = straight.particles().position;
    straight.step();
  }
  {
    DemRun first(s, p, 0.0, 0);
    first.advanceTo(333 * p.dt, {}, path, 50);
    EXPECT_EQ(stepInFile(), 333); // the requested state, not only the last multiple of 50
    EXPECT_EQ(first.solver().particles().position, at[333]);
  }
  DemRun resumed(s, p, 0.0, 0);
  resumed.resumeFrom(path);
  EXPECT_NEAR(resumed.checkpointTime(), 333 * p.dt, 1e-12);
  double reported = 0.0;
  resumed.advanceTo(
      120 * p.dt,
      [&](double f) {
        reported = std::max(reported, f);
        return true;
      },
      path, 50);
  EXPECT_EQ(resumed.solver().stepCount(), 120);
  EXPECT_EQ(resumed.solver().particles().position, at[120]);
  EXPECT_EQ(stepInFile(), 333) << "an earlier state overwrote the checkpoint";
  EXPECT_DOUBLE_EQ(reported, 1.0);
  resumed.advanceTo(360 * p.dt, {}, path, 50); // passes the file's step: 350 and 360 are written
  EXPECT_EQ(resumed.solver().particles().position, at[360]);
  EXPECT_EQ(stepInFile(), 360);
  resumed.advanceTo(400 * p.dt, {}, path, 50);
  EXPECT_EQ(resumed.solver().particles().position, at[400]);
  EXPECT_EQ(stepInFile(), 400);
  std::remove(path.c_str());
}

TEST(DemRestart, ThreadCountDoesNotChangeResults) {
  // Large enough (> 512 particles) for the solver to run its loops in parallel.
  // Same physical block as the other tests (12 kR wide), in smaller particles.
  const ParticleSet s = jostledBlock(0.5, 8, 1.0, 0.6 * kR, 20.0);
  ASSERT_GT(s.size(), 600u);
  const DemParams p = frictionalBox();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  DemSolver one(s, p);
  for (int j = 0; j < 300; ++j)
    one.step();
  omp_set_num_threads(std::max(2, threads));
  DemSolver many(s, p);
  for (int j = 0; j < 300; ++j)
    many.step();
  omp_set_num_threads(threads);
  EXPECT_EQ(one.particles().position, many.particles().position);
}

// The threads' ranges follow their measured times: a thread that took three times as long for
// an equal share gets less work, the ranges stay contiguous, cover every item and move back
// when the times become equal; a team of another size splits evenly.
TEST(DemThreads, WorkSharesFollowTheMeasuredTimes) {
  WorkShares shares;
  shares.resize(2);
  const std::size_t total = 100000;
  EXPECT_EQ(shares.begin(total, 1, 2), total / 2);
  for (int step = 0; step < 50; ++step) {
    // Thread 1 is three times slower per item: time = share / speed.
    const double s0 = static_cast<double>(shares.begin(total, 1, 2)) / total;
    shares.record(0, 2, s0 / 3.0);
    shares.record(1, 2, (1.0 - s0) / 1.0);
    shares.update();
  }
  // Equal times need thread 0 (three times faster) to take 3/4 of the items; the share moves
  // 30 % of the way each step, so after 50 steps it is there to 1e-7.
  EXPECT_NEAR(static_cast<double>(shares.begin(total, 1, 2)) / total, 0.75, 1e-4);
  EXPECT_EQ(shares.begin(total, 0, 2), 0u);
  EXPECT_EQ(shares.begin(total, 2, 2), total);
  EXPECT_EQ(shares.begin(total, 1, 3), total / 3) << "a team of another size splits evenly";
  shares.record(0, 2, 0.0); // no time: the shares stay
  shares.update();
  EXPECT_NEAR(static_cast<double>(shares.begin(total, 1, 2)) / total, 0.75, 1e-4);
  for (int step = 0; step < 80; ++step) { // equal speeds: back to halves
    const double s0 = static_cast<double>(shares.begin(total, 1, 2)) / total;
    shares.record(0, 2, s0);
    shares.record(1, 2, 1.0 - s0);
    shares.update();
  }
  EXPECT_NEAR(static_cast<double>(shares.begin(total, 1, 2)) / total, 0.5, 1e-4);
}

// The fused steps split the pairs and the particles among the threads by their measured times,
// which differ from run to run: the results must not. One, two and three threads (more than the
// machine may have, so that a thread waits for a processor and the splits move) give the same
// bits, through neighbour-list rebuilds.
TEST(DemThreads, FusedStepsGiveTheSameBitsOnAnyThreadCount) {
  const ParticleSet s = jostledBlock(0.5, 8, 1.0, 0.6 * kR, 20.0);
  ASSERT_GT(s.size(), 600u);
  const DemParams p = frictionalBox();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  DemSolver one(s, p);
  one.advanceSteps(600);
  EXPECT_GT(one.neighbourBuilds(), 2u);
  EXPECT_GT(one.diagnostics().contacts, 50u);
  for (int t : {2, 3}) {
    omp_set_num_threads(t);
    DemSolver many(s, p);
    many.advanceSteps(600);
    EXPECT_EQ(many.particles().position, one.particles().position) << t << " threads";
    EXPECT_EQ(many.particles().velocity, one.particles().velocity) << t << " threads";
    EXPECT_EQ(many.particles().angularVelocity, one.particles().angularVelocity) << t;
    EXPECT_EQ(many.diagnostics().contacts, one.diagnostics().contacts) << t << " threads";
  }
  omp_set_num_threads(threads);
}

// advanceSteps (and advanceTo between its progress reports and checkpoints) starts each step
// inside the previous one: the next step's half-kick and drift run in the force gather. Same
// arithmetic, so the same bits as single steps, through neighbour-list rebuilds, on as many
// threads as the machine gives (> 512 particles: the parallel loops), and the state between
// two calls is the real one (the next call continues it bit for bit).
TEST(DemIntegrator, FusedStepsGiveTheBitsOfSingleSteps) {
  const ParticleSet s = jostledBlock(0.5, 8, 1.0, 0.6 * kR, 20.0);
  ASSERT_GT(s.size(), 600u);
  const DemParams p = frictionalBox();
  DemSolver single(s, p), fused(s, p), timed(s, p);
  for (int j = 0; j < 800; ++j)
    single.step();
  fused.advanceSteps(300);
  fused.advanceSteps(1);
  fused.advanceSteps(499);
  int reports = 0;
  timed.advanceTo(800 * p.dt, [&](double) { return ++reports > 0; });
  EXPECT_GT(reports, 200); // a report every fourth step: the fusion stops at each
  EXPECT_GT(single.neighbourBuilds(), 2u) << "no rebuild inside the fused steps";
  for (const DemSolver* other : {&fused, &timed}) {
    EXPECT_EQ(other->stepCount(), 800);
    EXPECT_EQ(other->neighbourBuilds(), single.neighbourBuilds());
    EXPECT_EQ(other->particles().position, single.particles().position);
    EXPECT_EQ(other->particles().velocity, single.particles().velocity);
    EXPECT_EQ(other->particles().angularVelocity, single.particles().angularVelocity);
    EXPECT_EQ(other->diagnostics().contacts, single.diagnostics().contacts);
  }
  EXPECT_GT(single.diagnostics().contacts, 50u);
}

// A neighbour-list rebuild never resets a spring: a run whose list is rebuilt at an arbitrary
// step (removing a grain forces one) goes on bit for bit as the run without the rebuild. The
// removed grain falls freely high above the block and touches nothing, so the others cannot
// tell it was there; were a history lost or misplaced in the rebuild, the frictional contacts
// of the block (tangential, rolling and twisting springs) would change the trajectories.
TEST(DemNeighbours, RebuildKeepsEveryContactHistory) {
  ParticleSet s = jostledBlock(0.5, 7);
  const double above[3] = {0.0, 0.0, 40 * kR};
  const std::int64_t loneId = 1000000;
  s.add(above, kR, kRho, 0, loneId);
  const DemParams p = frictionalBox();
  DemSolver straight(s, p), rebuilt(s, p);
  for (int j = 0; j < 300; ++j) {
    straight.step();
    rebuilt.step();
  }
  ASSERT_GT(rebuilt.diagnostics().contacts, 20u);
  std::vector<char> remove(s.size(), 0);
  const std::size_t lone = indexOf(rebuilt, loneId);
  remove[lone] = 1;
  const std::size_t builds = rebuilt.neighbourBuilds();
  ASSERT_EQ(rebuilt.removeParticles(remove), 1u);
  ASSERT_EQ(rebuilt.neighbourBuilds(), builds + 1);
  for (int j = 0; j < 500; ++j) {
    straight.step();
    rebuilt.step();
  }
  auto withoutLone = [&](std::vector<double> a) {
    a.erase(a.begin() + 3 * lone, a.begin() + 3 * lone + 3);
    return a;
  };
  EXPECT_EQ(withoutLone(straight.particles().position), rebuilt.particles().position);
  EXPECT_EQ(withoutLone(straight.particles().velocity), rebuilt.particles().velocity);
  EXPECT_EQ(withoutLone(straight.particles().angularVelocity), rebuilt.particles().angularVelocity);
}

TEST(DemRestart, MalformedCheckpointsAreRejected) {
  const ParticleSet s = jostledBlock(0.1, 1);
  DemSolver solver(s, frictionalBox());
  std::stringstream out;
  solver.writeCheckpoint(out);
  const std::string good = out.str();
  auto load = [](const std::string& bytes) {
    std::istringstream in(bytes);
    return DemSolver::readCheckpoint(in, bytes.size());
  };
  EXPECT_NO_THROW(load(good));
  for (std::size_t cut : {std::size_t(0), std::size_t(5), good.size() / 3, good.size() - 1})
    EXPECT_THROW(load(good.substr(0, cut)), InputError) << "cut at " << cut;
  std::string wrong = good;
  wrong[0] = 'X';
  EXPECT_THROW(load(wrong), InputError);
  // A corrupted particle count must not trigger a huge allocation.
  std::string huge = good;
  const std::size_t at = huge.find("LinearSpringDashpot");
  ASSERT_NE(at, std::string::npos);
  EXPECT_THROW(load(huge.substr(0, at) + std::string(8, '\xff') + huge.substr(at)), InputError);
}

TEST(DemInput, BadInputGivesNamedErrors) {
  DemParams p = frictionless(0.5);
  auto expectError = [&](const ParticleSet& s, const DemParams& q, const std::string& word) {
    try {
      DemSolver solver(s, q);
      ADD_FAILURE() << "no error for " << word;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  ParticleSet s = one(0, 0, 0, 0, 0, 0);
  s.position[1] = std::nan("");
  expectError(s, p, "NaN");
  s = one(0, 0, 0, 0, 0, 0);
  s.velocity[2] = INFINITY;
  expectError(s, p, "infinite velocities");
  s = one(0, 0, 0, 0, 0, 0);
  s.radius[0] = -1;
  expectError(s, p, "non-positive radii");
  expectError(ParticleSet{}, p, "no particles");
  DemParams q = p;
  q.dt = 1.0;
  expectError(one(0, 0, 0, 0, 0, 0), q, "stability");
  q = p;
  q.contact.restitutionN = 1.5;
  expectError(one(0, 0, 0, 0, 0, 0), q, "NormalRestitution");
  q = p;
  q.contact.normalModel = "Hooke";
  expectError(one(0, 0, 0, 0, 0, 0), q, "Hooke");
  ParticleSet pair = one(0, 0, 0, 0, 0, 0);
  const double x2[3] = {kR, 0, 0};
  pair.add(x2, kR, kRho, 0, 1);
  expectError(pair, p, "overlap");
}

TEST(DemInput, BlowUpStopsWithStepAndParticle) {
  DemParams p = frictionless(0.5, 0.01); // stiffness for 1 cm/s
  ParticleSet s = one(-kR - 1e-3, 0, 0, 2.0, 0, 0);
  const double x2[3] = {kR + 1e-3, 0, 0};
  s.add(x2, kR, kRho, 0, 42);
  DemSolver solver(s, p);
  try {
    solver.advanceTo(1.0);
    FAIL() << "no blow-up reported";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("blew up at step"), std::string::npos) << what;
    EXPECT_NE(what.find("Id"), std::string::npos) << what;
  }
}

TEST(DemInput, OverlapWarningIsCounted) {
  DemParams p = frictionless(0.9, 0.05); // stiffness for 5 cm/s, hit at 0.5 m/s
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  DemSolver s(one(0, 0, kR + 1e-4, 0, 0, -0.5), p);
  s.advanceTo(0.05);
  EXPECT_GT(s.overlapWarnings(), 0u);
  ASSERT_FALSE(s.warnings().empty());
  EXPECT_NE(s.warnings().back().find("overlap"), std::string::npos);
}

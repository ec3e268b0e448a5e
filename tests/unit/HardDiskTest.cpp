// Event-driven hard disks: conservation, a brute-force event oracle, the hard-disk equation of
// state, inelastic bounces, compression and the crater scenario's input checks.
#include "common/Error.h"
#include "common/Random.h"
#include "edmd/EventQueue.h"
#include "edmd/HardDiskCrater.h"
#include "edmd/HardDiskSystem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <utility>
#include <vector>

using namespace craterkit;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Random non-overlapping disks of radius r in a box (random sequential addition, brute force).
HardDisks randomGas(std::size_t n, double r, double w, double h, std::uint64_t seed,
                    bool zeroMomentum) {
  Random rng(seed);
  HardDisks d;
  while (d.size() < n) {
    const double x = rng.uniform(r, w - r), y = rng.uniform(r, h - r);
    bool ok = true;
    for (std::size_t j = 0; j < d.size() && ok; ++j)
      ok = std::hypot(d.x[j] - x, d.y[j] - y) >= 2.0 * r * (1 + 1e-9) &&
           std::hypot(std::abs(d.x[j] - x) - w, d.y[j] - y) >= 2.0 * r * (1 + 1e-9) &&
           std::hypot(d.x[j] - x, std::abs(d.y[j] - y) - h) >= 2.0 * r * (1 + 1e-9) &&
           std::hypot(std::abs(d.x[j] - x) - w, std::abs(d.y[j] - y) - h) >= 2.0 * r * (1 + 1e-9);
    if (!ok)
      continue;
    const double a = 2.0 * kPi * rng.uniform(), s = rng.uniform(0.5, 1.5);
    d.add(x, y, s * std::cos(a), s * std::sin(a), r, 1.0 + rng.uniform(), 0,
          static_cast<std::int64_t>(d.size()));
  }
  if (zeroMomentum) {
    double px = 0, py = 0, m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      px += d.mass[i] * d.vx[i];
      py += d.mass[i] * d.vy[i];
      m += d.mass[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
      d.vx[i] -= px / m;
      d.vy[i] -= py / m;
    }
  }
  return d;
}

// The reference: every disk advanced together, every pair and wall tested at every event.
struct BruteForce {
  HardDisks d;
  HardDiskParams p;
  double t = 0.0;

  double pairTime(std::size_t i, std::size_t j) const {
    const double rx = d.x[j] - d.x[i], ry = d.y[j] - d.y[i], ux = d.vx[j] - d.vx[i],
                 uy = d.vy[j] - d.vy[i];
    const double s = d.radius[i] + d.radius[j];
    const double c = rx * rx + ry * ry - s * s, b = rx * ux + ry * uy, a = ux * ux + uy * uy;
    if (b >= 0.0)
      return kInf;
    if (c <= 0.0)
      return 0.0;
    const double disc = b * b - a * c;
    return disc < 0.0 ? kInf : c / (-b + std::sqrt(disc));
  }
  // Time to the wall (0 -x, 1 +x, 2 floor, 3 ceiling) and which.
  double wallTime(std::size_t i, std::uint32_t& wall) const {
    const double r = d.radius[i];
    double best = kInf;
    if (d.vx[i] < 0.0 && (d.x[i] - r) / -d.vx[i] < best)
      best = (d.x[i] - r) / -d.vx[i], wall = 0;
    if (d.vx[i] > 0.0 && (p.width - r - d.x[i]) / d.vx[i] < best)
      best = (p.width - r - d.x[i]) / d.vx[i], wall = 1;
    const double g = p.gravity, y = d.y[i], v = d.vy[i];
    if (g == 0.0) {
      if (v < 0.0 && (y - r) / -v < best)
        best = (y - r) / -v, wall = 2;
      if (v > 0.0 && (p.height - r - y) / v < best)
        best = (p.height - r - y) / v, wall = 3;
    } else {
      // ceiling: y + v τ - g τ²/2 = H - r (smaller root) if reachable, else floor (larger root)
      const double up = p.height - r - y;
      if (v > 0.0 && v * v >= 2.0 * g * up) {
        const double tc = (v - std::sqrt(v * v - 2.0 * g * up)) / g;
        if (tc < best)
          best = tc, wall = 3;
      } else {
        const double tf = (v + std::sqrt(v * v + 2.0 * g * std::max(0.0, y - r))) / g;
        if (tf < best)
          best = tf, wall = 2;
      }
    }
    return std::max(0.0, best);
  }
  // The next event from the current state (not executed).
  EventRecord next() const {
    const std::size_t n = d.size();
    double best = kInf;
    EventRecord e{kInf, EventType::None, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t w = 0;
      const double tw = wallTime(i, w);
      if (tw < best)
        best = tw, e = EventRecord{0.0, EventType::Wall, static_cast<std::uint32_t>(i), w};
      for (std::size_t j = i + 1; j < n; ++j) {
        const double tp = pairTime(i, j);
        if (tp < best)
          best = tp, e = EventRecord{0.0, EventType::Pair, static_cast<std::uint32_t>(i),
                                     static_cast<std::uint32_t>(j)};
      }
    }
    e.time = t + best;
    return e;
  }
};

// Hard-disk dynamics is chaotic: two correct codes drift apart by round-off within a few
// hundred events. So before every event the oracle takes the engine's state (every disk
// brought to the current time) and finds the next event by testing every pair and wall;
// the engine's next physical event must be the same one at the same time.
void compareWithBruteForce(const HardDisks& disks, const HardDiskParams& p, std::size_t events) {
  std::vector<EventRecord> log;
  HardDiskSystem sys(disks, p);
  sys.recordEvents(&log);
  sys.checkOverlaps(true);
  for (std::size_t k = 0; k < events; ++k) {
    sys.advanceTo(sys.time());
    const BruteForce ref{sys.disks(), p, sys.time()};
    const EventRecord b = ref.next();
    log.clear();
    while (log.empty() || log.back().type == EventType::Cell)
      sys.processEvents(1);
    const EventRecord& a = log.back();
    ASSERT_EQ(a.type, b.type) << "event " << k;
    if (a.type == EventType::Pair) {
      ASSERT_EQ(std::min(a.i, a.partner), b.i) << "event " << k;
      ASSERT_EQ(std::max(a.i, a.partner), b.partner) << "event " << k;
    } else {
      ASSERT_EQ(a.i, b.i) << "event " << k;
      ASSERT_EQ(a.partner, b.partner) << "event " << k;
    }
    ASSERT_NEAR(a.time, b.time, 1e-12 * b.time + 1e-15) << "event " << k;
  }
}
} // namespace

TEST(HardDiskSystem, EventSequenceMatchesBruteForceOracle) {
  HardDiskParams p;
  p.width = 1.0;
  p.height = 0.8;
  compareWithBruteForce(randomGas(40, 0.03, p.width, p.height, 7, false), p, 5000);
}

TEST(HardDiskSystem, EventSequenceWithGravityMatchesBruteForceOracle) {
  HardDiskParams p;
  p.width = 1.0;
  p.height = 0.8;
  p.gravity = 9.81;
  compareWithBruteForce(randomGas(30, 0.03, p.width, p.height, 11, false), p, 5000);
}

TEST(HardDiskSystem, EventSequenceWithABigDiskMatchesBruteForceOracle) {
  HardDiskParams p;
  p.width = 1.0;
  p.height = 1.0;
  HardDisks d = randomGas(40, 0.02, p.width, 0.5, 5, false);
  d.add(0.5, 0.75, 0.3, -2.0, 0.15, 20.0, 1, 40);
  compareWithBruteForce(d, p, 5000);
}

TEST(HardDiskSystem, ElasticRunConservesEnergyAndMomentumOverAMillionEvents) {
  HardDiskParams p;
  p.width = p.height = 1.0;
  p.periodicX = p.periodicY = true;
  // About 0.35 area fraction: 1100 disks of radius 0.01.
  Random rng(3);
  HardDisks d;
  const double r = 0.01;
  const int side = 34;
  for (int a = 0; a < side; ++a)
    for (int b = 0; b < side; ++b) {
      const double ang = 2.0 * kPi * rng.uniform();
      d.add((a + 0.5) / side, (b + 0.5) / side, std::cos(ang), std::sin(ang), r,
            1.0 + rng.uniform(), 0, static_cast<std::int64_t>(d.size()));
    }
  double px = 0, py = 0, m = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    px += d.mass[i] * d.vx[i], py += d.mass[i] * d.vy[i], m += d.mass[i];
  for (std::size_t i = 0; i < d.size(); ++i)
    d.vx[i] -= px / m, d.vy[i] -= py / m;
  HardDiskSystem sys(d, p);
  sys.checkOverlaps(true);
  const double e0 = sys.kineticEnergy();
  double scale = 0.0; // Σ m |v|: the scale of momentum round-off
  for (std::size_t i = 0; i < d.size(); ++i)
    scale += d.mass[i] * std::hypot(d.vx[i], d.vy[i]);
  sys.processEvents(1000000);
  EXPECT_GT(sys.pairCollisions(), 400000u);
  EXPECT_NEAR(sys.kineticEnergy(), e0, 1e-10 * e0);
  double qx, qy;
  sys.momentum(qx, qy);
  EXPECT_LT(std::hypot(qx, qy), 1e-12 * scale);
  sys.advanceTo(sys.time());
  EXPECT_GE(sys.smallestGap(), -1e-9 * r);
}

// Henderson (1975): Z = P A / (N k T) = (1 + η²/8) / (1 - η)².
class HardDiskPressure : public ::testing::TestWithParam<double> {};

TEST_P(HardDiskPressure, CollisionVirialMatchesHendersonEquationOfState) {
  const double eta = GetParam();
  const std::size_t n = 2000;
  const double r = 0.01, area = n * kPi * r * r / eta, side = std::sqrt(area);
  HardDiskParams p;
  p.width = p.height = side;
  p.periodicX = p.periodicY = true;
  HardDisks d;
  {
    // Start from a square lattice with random velocities (equal masses).
    Random rng(21);
    const int k = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    for (std::size_t i = 0; i < n; ++i) {
      const double ang = 2.0 * kPi * rng.uniform();
      d.add((i % k + 0.5) * side / k, (i / k + 0.5) * side / k, std::cos(ang), std::sin(ang), r,
            1.0, 0, static_cast<std::int64_t>(i));
    }
  }
  HardDiskSystem sys(d, p);
  sys.processEvents(400000); // equilibrate
  sys.advanceTo(sys.time());
  const double t0 = sys.time(), v0 = sys.virialSum();
  const std::uint64_t c0 = sys.pairCollisions();
  while (sys.pairCollisions() - c0 < 1500000)
    sys.processEvents(100000);
  sys.advanceTo(sys.time());
  const double kT = sys.kineticEnergy() / n; // 2D: E = N k T
  const double z = 1.0 + (sys.virialSum() - v0) / (2.0 * (sys.time() - t0) * n * kT);
  const double henderson = (1.0 + eta * eta / 8.0) / ((1.0 - eta) * (1.0 - eta));
  EXPECT_NEAR(z, henderson, 0.02 * henderson) << "area fraction " << eta;
}
INSTANTIATE_TEST_SUITE_P(AreaFractions, HardDiskPressure, ::testing::Values(0.2, 0.4));

TEST(HardDiskSystem, InelasticBounceLosesEnergyAsRestitutionSquared) {
  for (double e : {0.9, 0.7, 0.5}) {
    HardDiskParams p;
    p.width = 1.0;
    p.height = 2.0;
    p.gravity = 9.81;
    p.wallRestitution = e;
    HardDisks d;
    d.add(0.5, 1.0, 0.0, 0.0, 0.05, 1.0, 0, 0);
    HardDiskSystem sys(d, p);
    double previous = -1.0;
    int bounces = 0;
    while (bounces < 5) {
      const std::uint64_t before = sys.wallCollisions();
      sys.processEvents(1);
      if (sys.wallCollisions() == before)
        continue;
      const double energy = sys.kineticEnergy(); // at the floor: all kinetic
      if (previous > 0.0)
        EXPECT_NEAR(energy / previous, e * e, 1e-9) << "restitution " << e;
      previous = energy;
      ++bounces;
    }
  }
}

TEST(HardDiskCrater, CompressionReachesTheAreaFractionWithoutOverlaps) {
  HardDiskCraterParams p;
  p.width = 0.3;
  p.groundDepth = 0.15;
  p.areaFraction = 0.78;
  p.maxDiskRadius = 0.006;
  const HardDisks g = generateHardDiskGround(p);
  double area = 0.0;
  for (double r : g.radius)
    area += kPi * r * r;
  EXPECT_NEAR(area / (p.width * p.groundDepth), p.areaFraction, 0.01);
  HardDiskParams hp;
  hp.width = p.width;
  hp.height = p.groundDepth;
  HardDiskSystem sys(g, hp); // throws if anything overlaps
  EXPECT_GE(sys.smallestGap(), -1e-9 * p.diskRadius);
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_GE(g.y[i], g.radius[i] * (1 - 1e-9));
    EXPECT_LE(g.y[i], p.groundDepth - g.radius[i] * (1 - 1e-9));
  }
}

TEST(HardDiskCrater, ElasticCraterRunConservesEnergyAndRecordsEjecta) {
  HardDiskCraterParams p;
  p.width = 0.6;
  p.groundDepth = 0.25;
  p.headroom = 0.3;
  p.diskRadius = 0.005;
  p.areaFraction = 0.7;
  p.impactorRadius = 0.025;
  p.frameInterval = 2e-3;
  p.endTime = 0.02;
  HardDiskCraterRun run(p);
  const double e0 = run.system().kineticEnergy();
  run.advanceToFrame(run.frameCount() - 1);
  EXPECT_NEAR(run.system().kineticEnergy(), e0, 1e-9 * e0);
  EXPECT_GE(run.system().smallestGap(), -1e-9 * p.diskRadius);
  EXPECT_EQ(run.shockFront().size(), run.frameCount());
  // The disturbance runs ahead of the impactor and grows monotonically.
  for (std::size_t k = 1; k < run.shockFront().size(); ++k)
    EXPECT_GE(run.shockFront()[k], run.shockFront()[k - 1]);
  EXPECT_GT(run.shockFront().back(), 0.05);
  EXPECT_FALSE(run.ejections().empty());
  for (const auto& ej : run.ejections()) {
    EXPECT_GT(ej.angleDeg, 0.0);
    EXPECT_LE(ej.angleDeg, 90.0);
  }
  // Tracer paths hold one point per frame.
  for (const auto& path : run.tracerPaths())
    EXPECT_EQ(path.size(), 2 * run.frameCount());
}

TEST(HardDiskCrater, BadInputGivesClearErrors) {
  auto message = [](HardDiskCraterParams p) {
    try {
      p.validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  HardDiskCraterParams p;
  p.areaFraction = 0.9;
  EXPECT_NE(message(p).find("jamming"), std::string::npos);
  p = {};
  p.diskRadius = 0.6;
  EXPECT_NE(message(p).find("larger than the box"), std::string::npos);
  p = {};
  p.impactSpeed = -1.0;
  EXPECT_NE(message(p).find("ImpactSpeed"), std::string::npos);
  p = {};
  p.groundDensity = -5.0;
  EXPECT_NE(message(p).find("GroundDensity"), std::string::npos);
  p = {};
  p.frameInterval = 0.0;
  EXPECT_NE(message(p).find("FrameInterval"), std::string::npos);
  p = {};
  p.impactAngle = 90.0;
  EXPECT_NE(message(p).find("ImpactAngle"), std::string::npos);
  EXPECT_THROW(HardDiskCraterParams::preset("Moon dust"), InputError);
  HardDisks overlapping;
  overlapping.add(0.5, 0.5, 0, 0, 0.1, 1, 0, 0);
  overlapping.add(0.55, 0.5, 0, 0, 0.1, 1, 0, 1);
  HardDiskParams hp;
  EXPECT_THROW(HardDiskSystem(overlapping, hp), InputError);
}

// The future-event queue against an ordered set of the pending (time, disk) pairs, in phases
// that make every part of it run: events soon after the present (the ring turns many times),
// ties, events that disappear or lie far ahead (the overflow list and its refills); a phase
// in which every new event lies far ahead (the ring empties and the queue jumps, then widens);
// a new tune() in mid-run; bursts of events closer than a bucket's width (the ring narrows).
// Every few thousand steps the queue's own bookkeeping is checked and its count of valid
// events compared with the set's. 500 disks with as many buckets, 2,000 with seven times
// fewer (several chunks to a bucket), and 40,000, for which the queue chooses the latter itself
// (too many for the ring to turn often in a test).
namespace {
void checkQueueAgainstOrderedSet(std::size_t n, int steps, std::size_t perBucket, bool adapts) {
  Random rng(17);
  std::vector<double> times(n);
  std::set<std::pair<double, std::size_t>> pending;
  for (std::size_t i = 0; i < n; ++i) {
    times[i] = rng.uniform(0.0, 1.0);
    pending.insert({times[i], i});
  }
  struct Timed {
    double t;
  };
  EventQueue<Timed> q;
  q.reset(n, 0.0, perBucket);
  for (std::size_t i = 0; i < n; ++i)
    q.update(i, Timed{times[i]});
  q.tune(0.0);
  auto set = [&](std::size_t i, double t) {
    if (times[i] < kInf)
      pending.erase({times[i], i});
    times[i] = t;
    if (t < kInf)
      pending.insert({t, i});
    q.update(i, Timed{t});
  };
  const double dt =
      50.0 / static_cast<double>(n); // a disk's next event, on average, in phases 0 and 2
  double now = 0.0;
  int checked = 0;
  for (int step = 0; step < steps; ++step) {
    const int phase = step < 4 * steps / 10   ? 0
                      : step < 5 * steps / 10 ? 1
                      : step < 6 * steps / 10 ? 2
                                              : 3;
    if (step == 5 * steps / 10)
      q.tune(now);
    const std::size_t expected = pending.empty() ? n : pending.begin()->second;
    const auto* top = q.top();
    const std::size_t got = top ? top->disk : n;
    ASSERT_EQ(got, expected) << "step " << step;
    if (got == n)
      break;
    ASSERT_EQ(top->event.t, times[got]);
    q.pop();
    now = times[got];
    pending.erase({now, got});
    times[got] = kInf;
    // The disk's next event: usually soon, sometimes a tie, sometimes far away or none.
    const double u = rng.uniform();
    double next = now + rng.uniform(0.0, 2.0 * dt);
    if (u < 0.05)
      next = now; // a tie with the current time
    else if (u < 0.07)
      next = kInf;
    else if (u < 0.08)
      next = now + rng.uniform(0.0, 1000.0);
    else if (phase == 1)
      next = now + rng.uniform(50.0, 60.0); // all new events far ahead: the ring empties
    else if (phase == 3)
      next = now + rng.uniform(0.0, 1e-4 * dt); // a burst: the ring must narrow
    set(got, next);
    // Another disk's event changes too (and disks without one get one back).
    const std::size_t other = static_cast<std::size_t>(rng.uniform() * n);
    const std::size_t third = static_cast<std::size_t>(rng.uniform() * n);
    double t = phase == 1 ? now + rng.uniform(50.0, 60.0) : now + rng.uniform(0.0, 4.0 * dt);
    if (rng.uniform() < 0.2 && times[third] < kInf)
      t = times[third]; // an exact tie between two disks
    set(other, t);
    if (step % 4999 == 0)
      ASSERT_EQ(q.checkedPending(), static_cast<long long>(pending.size())) << "step " << step;
    ++checked;
  }
  EXPECT_EQ(checked, steps);
  std::printf("%zu disks: %llu turns of the ring, %llu width changes, now at t = %.4g\n", n,
              static_cast<unsigned long long>(q.turns()),
              static_cast<unsigned long long>(q.rebuilds()), now);
  if (adapts) {
    EXPECT_GT(q.turns(), 10u);
    EXPECT_GT(q.rebuilds(), 3u); // the two tune() calls, and the ring widening and narrowing
  }
}
} // namespace

TEST(EventQueue, AlwaysYieldsTheEarliestEventLowestIndexFirst) {
  checkQueueAgainstOrderedSet(500, 400000, 0, true);    // a bucket per disk
  checkQueueAgainstOrderedSet(2000, 400000, 7, true);   // seven disks a bucket: chunk chains
  checkQueueAgainstOrderedSet(40000, 200000, 0, false); // the same, chosen for a large system
}

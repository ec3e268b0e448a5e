// Partial rebuilds of the SPH neighbour lists (sph/PartialRebuild.cpp), used by the late
// stage's individual time steps: against a brute-force search over all pairs, after every one
// of hundreds of events in which some particles move fast through slow ones, fragments fly in
// from far away and smoothing lengths grow, the lists must hold every pair within the kernel's
// reach (r < max(h_a, h_b), the support of the larger kernel), in both partners' lists, once.
#include "common/Random.h"
#include "sph/NeighbourList.h"
#include "sph/SphParams.h"
#include "sph/SphState.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

using namespace craterkit;

namespace {

// Pairs within reach at s missing from a's or b's list, and entries listed twice or
// listed on one side only (the lists are symmetric).
struct Audit {
  std::size_t inReach = 0, missing = 0, duplicates = 0, oneSided = 0;
};

Audit audit(const SphState& s, const NeighbourList& nb) {
  const std::size_t n = s.size();
  Audit r;
  std::vector<std::vector<std::uint32_t>> lists(n);
  for (std::size_t a = 0; a < n; ++a) {
    lists[a] = nb.sortedOf(a);
    r.duplicates +=
        static_cast<std::size_t>(lists[a].end() - std::unique(lists[a].begin(), lists[a].end()));
  }
  auto listed = [&](std::size_t a, std::size_t b) {
    return std::binary_search(lists[a].begin(), lists[a].end(),
                              static_cast<std::uint32_t>(b * 32 + kNoShift));
  };
  for (std::size_t a = 0; a < n; ++a) {
    for (std::uint32_t e : lists[a])
      r.oneSided += !listed(e / 32, a);
    for (std::size_t b = a + 1; b < n; ++b) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k)
        d2 += (s.x[3 * a + k] - s.x[3 * b + k]) * (s.x[3 * a + k] - s.x[3 * b + k]);
      const double reach = std::max(s.h[a], s.h[b]);
      if (d2 < reach * reach) {
        ++r.inReach;
        r.missing += !listed(a, b) || !listed(b, a);
      }
    }
  }
  return r;
}

// Events of 1 ms, as block steps ask: a list is kept while valid(), else partly rebuilt if that
// makes it valid, else built anew; after each event's motion (particles in `bounce` turned back
// at the faces of the cube [0, L]³, and every seventh particle's h grows) the lists are audited.
struct EventRun {
  std::size_t refreshes = 0, builds = 1, counted = 0, failures = 0;
  Audit worst;
};

EventRun runEvents(SphState& s, const std::vector<double>& acc, const std::vector<char>& bounce,
                   double L, std::size_t events) {
  SphParams par;
  const std::size_t n = s.size();
  NeighbourList nb;
  const double dt = 1e-3;
  const std::vector<double> noXsph;
  nb.build(s, par, noXsph, dt);
  EventRun run;
  for (std::size_t event = 0; event < events; ++event) {
    if (!nb.valid(s, par, noXsph, acc, dt)) {
      bool kept = false; // as sph/BlockSteps.cpp asks
      for (int pass = 0; pass < 3 && !kept && nb.refresh(s, par, noXsph, acc, dt); ++pass) {
        ++run.refreshes;
        kept = nb.valid(s, par, noXsph, acc, dt);
      }
      if (!kept) {
        nb.build(s, par, noXsph, dt);
        ++run.builds;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) {
        s.x[3 * i + k] += dt * (s.v[3 * i + k] + 0.5 * dt * acc[3 * i + k]);
        s.v[3 * i + k] += dt * acc[3 * i + k];
        const double xk = s.x[3 * i + k];
        if (bounce[i] && (xk < 0.0 || xk > L) && (xk < 0.0) == (s.v[3 * i + k] < 0.0))
          s.v[3 * i + k] = -s.v[3 * i + k]; // a velocity jump: the lists' check sees only v now
      }
      if (i % 7 == 0)
        s.h[i] *= 1.002;
    }
    const Audit a = audit(s, nb);
    run.failures += a.missing + a.duplicates + a.oneSided;
    if (a.missing + a.duplicates + a.oneSided >
        run.worst.missing + run.worst.duplicates + run.worst.oneSided)
      run.worst = a;
    EXPECT_GT(a.inReach, 2 * n);
  }
  run.counted = nb.refreshes();
  std::printf("%zu events: %zu partial rebuilds (%zu counted by the list), %zu full builds; "
              "worst event: %zu missing, %zu listed twice, %zu one-sided\n",
              events, run.refreshes, run.counted, run.builds, run.worst.missing,
              run.worst.duplicates, run.worst.oneSided);
  return run;
}

} // namespace

// A graded body (h from 3 to 7 cm, so that the neighbour grid has three levels) of slow
// particles (up to 5 cm/s), a tenth of them fast (up to 3 m/s, with their own accelerations,
// turned back at the body's faces), and a clump and lone fragments flying into it from 30 cm away
// at 4 m/s (their clearance keeps them out of the pairs' check until the body's particles come
// near). Events of 1 ms, as block steps ask: a list is kept while valid(), else partly rebuilt if
// that makes it valid, else built anew. A missed pair would let a fast particle pass through its
// neighbours unseen.
TEST(SphNeighbourList, PartialRebuildsKeepEveryPairInReachOverManyEvents) {
  SphState s;
  Random rng(5);
  const double L = 0.25;
  std::vector<double> acc;
  for (int i = 0; i < 1400; ++i) {
    const double x[3] = {rng.uniform(0.0, L), rng.uniform(0.0, L), rng.uniform(0.0, L)};
    const bool fast = i % 10 == 0;
    const double speed = fast ? 3.0 : 0.05;
    const double v[3] = {speed * rng.uniform(-1.0, 1.0), speed * rng.uniform(-1.0, 1.0),
                         speed * rng.uniform(-1.0, 1.0)};
    s.add(x, v, 1.0, 1000.0, 0.0, 0);
    s.h.back() = 0.03 + 0.04 * x[0] / L; // graded along x (spacing 2.2 cm)
    for (int k = 0; k < 3; ++k)
      acc.push_back(fast ? rng.uniform(-5.0, 5.0) : 0.0);
  }
  const double incoming[4][3] = {
      {L + 0.3, 0.12, 0.12}, {L + 0.305, 0.12, 0.12}, {0.1, -0.3, 0.1}, {0.2, 0.2, L + 0.3}};
  const double towards[4][3] = {{-4, 0, 0}, {-4, 0, 0}, {0, 4, 0}, {0, 0, -4}};
  for (int f = 0; f < 4; ++f) {
    s.add(incoming[f], towards[f], 1.0, 1000.0, 0.0, 0);
    s.h.back() = 0.04;
    acc.insert(acc.end(), 3, 0.0);
  }
  std::vector<char> bounce(s.size(), 0);
  std::fill(bounce.begin(), bounce.begin() + 1400, 1);
  const EventRun run = runEvents(s, acc, bounce, L, 300);
  EXPECT_EQ(run.failures, 0u);
  EXPECT_EQ(run.counted, run.refreshes);
  EXPECT_GT(run.refreshes, 20u);            // the case under test happens often
  EXPECT_LT(run.builds, run.refreshes / 2); // and saves full builds
}

// A fragment alone in flight is left out of the lists' check while its clearance lasts, and
// a particle searched again may take a reference nearer to it than that clearance allowed:
// probes leave a resting block at 6 m/s towards fragments that come at 1 m/s (the fragments'
// own travel then bounds less than the probes' travel since the fragments' clearance was
// found). The probes' searches must lower the fragments' clearances, or the pairs are missed.
TEST(SphNeighbourList, PartialRebuildsLowerTheClearanceOfFragmentsInFlight) {
  SphState s;
  const double dx = 0.02, L = 0.2;
  std::vector<double> acc;
  const double rest[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) {
        const double x[3] = {i * dx, j * dx, k * dx};
        s.add(x, rest, 1.0, 1000.0, 0.0, 0);
        s.h.back() = 2.5 * dx;
      }
  // Probes from inside the block and fragments 0.2 m beyond it, 14 cm apart (no fragment
  // near another, so that each has a clearance).
  for (int p = 0; p < 4; ++p) {
    const double y = 0.03 + 0.14 * (p % 2), z = 0.03 + 0.14 * (p / 2);
    const double probe[3] = {0.11, y, z}, fragment[3] = {L + 0.2, y, z};
    const double out[3] = {6.0, 0.0, 0.0}, in[3] = {-1.0, 0.0, 0.0};
    s.add(probe, out, 1.0, 1000.0, 0.0, 0);
    s.h.back() = 2.5 * dx;
    s.add(fragment, in, 1.0, 1000.0, 0.0, 0);
    s.h.back() = 2.5 * dx;
  }
  acc.assign(3 * s.size(), 0.0);
  const std::vector<char> bounce(s.size(), 0);
  const EventRun run = runEvents(s, acc, bounce, L, 80); // they meet at about 45 ms
  EXPECT_EQ(run.failures, 0u);
  EXPECT_GT(run.refreshes, 20u);
}

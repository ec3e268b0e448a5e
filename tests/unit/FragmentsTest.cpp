// FragmentAnalysis against a brute-force oracle (all pairs, breadth-first search) on random
// contact and bond configurations, and the fragmentation and cloud shape of hand-built clouds.
#include "analysis/Fragments.h"
#include "common/Error.h"
#include "common/Random.h"

#include "ComponentsOracle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace craterkit;

namespace {
// The two labellings describe the same partition.
bool samePartition(const std::vector<long long>& a, const std::vector<int>& b) {
  std::map<long long, int> ab;
  std::map<int, long long> ba;
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto [it, fresh] = ab.emplace(a[i], b[i]);
    auto [jt, fresh2] = ba.emplace(b[i], a[i]);
    if (it->second != b[i] || jt->second != a[i])
      return false;
  }
  return true;
}
} // namespace

TEST(Fragments, ContactsAndBondsMatchABruteForceOracle) {
  Random rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    const std::size_t n = 1500;
    std::vector<double> x(3 * n), r(n), m(n), v(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k)
        x[3 * i + k] = rng.uniform(0.0, 1.0);
      r[i] = rng.uniform(0.01, 0.04);
      m[i] = r[i] * r[i] * r[i];
    }
    FragmentParams par;
    par.tolerance = 0.02;
    const FragmentResult res = analyseFragments(x, r, m, v, par);
    const auto comp = componentsOracle(n, [&](std::size_t a, std::size_t b) {
      double d2 = 0.0;
      for (int k = 0; k < 3; ++k)
        d2 += (x[3 * a + k] - x[3 * b + k]) * (x[3 * a + k] - x[3 * b + k]);
      const double cut = (r[a] + r[b]) * 1.02;
      return a != b && d2 <= cut * cut;
    });
    EXPECT_TRUE(samePartition(res.fragmentId, comp)) << "trial " << trial;
    std::size_t count = 0;
    double mass = 0.0;
    for (const Fragment& f : res.fragments)
      count += f.count, mass += f.mass;
    EXPECT_EQ(count, n);
    for (std::size_t k = 1; k < res.fragments.size(); ++k)
      EXPECT_GE(res.fragments[k - 1].mass, res.fragments[k].mass);
    EXPECT_NEAR(res.cumulativeMass.back(), 1.0, 1e-12);

    // Random bonds instead of contacts.
    FragmentParams bonded;
    std::vector<std::vector<char>> adj(n, std::vector<char>(n, 0));
    for (int k = 0; k < 1200; ++k) {
      const std::size_t a = static_cast<std::size_t>(rng.uniform() * n),
                        b = static_cast<std::size_t>(rng.uniform() * n);
      bonded.bonds.emplace_back(a, b);
      adj[a][b] = adj[b][a] = 1;
    }
    const FragmentResult rb = analyseFragments(x, r, m, v, bonded);
    EXPECT_TRUE(samePartition(rb.fragmentId, componentsOracle(n, [&](std::size_t a, std::size_t b) {
                                return adj[a][b] != 0;
                              })));
  }
}

TEST(Fragments, FragmentationAndCloudShapeOfHandBuiltClouds) {
  // Ten touching spheres in a row plus five isolated ones: six fragments of fifteen particles.
  std::vector<double> x, r, m, v;
  for (int i = 0; i < 10; ++i)
    x.insert(x.end(), {0.2 * i, 0.0, 0.0}), r.push_back(0.1), m.push_back(1.0),
        v.insert(v.end(), {1.0, 0.0, 0.0});
  for (int i = 0; i < 5; ++i)
    x.insert(x.end(), {10.0 + 5.0 * i, 3.0, 0.0}), r.push_back(0.1), m.push_back(1.0),
        v.insert(v.end(), {2.0 + i, 0.0, 0.0});
  FragmentParams par;
  FragmentResult res = analyseFragments(x, r, m, v, par);
  EXPECT_EQ(res.fragments.size(), 6u);
  EXPECT_DOUBLE_EQ(res.fragmentation, 6.0 / 15.0);
  EXPECT_DOUBLE_EQ(res.largestMassFraction, 10.0 / 15.0);
  EXPECT_EQ(res.fragments[0].count, 10u);
  EXPECT_NEAR(res.fragments[0].centre[0], 0.9, 1e-12);
  EXPECT_NEAR(res.fragments[0].velocity[0], 1.0, 1e-12);

  // An ellipsoidal cloud along x (semi-axes 3 and 1) beyond the plate at x = 0.
  Random rng(5);
  x.clear(), r.clear(), m.clear(), v.clear();
  auto add = [&](double px, double py, double pz, double vx) {
    x.insert(x.end(), {px, py, pz}), r.push_back(0.01), m.push_back(1.0),
        v.insert(v.end(), {vx, 0.0, 0.0});
  };
  add(1.0, 0.0, 0.0, 0.0), add(7.0, 0.0, 0.0, 5.0), add(4.0, 1.0, 0.0, 2.0),
      add(4.0, 0.0, -1.0, 2.0);
  while (r.size() < 2000) {
    const double u = rng.uniform(-1, 1), w = rng.uniform(-1, 1), s = rng.uniform(-1, 1);
    if (u * u + w * w + s * s <= 1.0)
      add(4.0 + 3.0 * u, w, s, 2.0 + u);
  }
  add(-0.5, 20.0, 0.0, -1.0); // behind the plate: not in the cloud
  par.cloudStart = 0.0;
  res = analyseFragments(x, r, m, v, par);
  EXPECT_EQ(res.cloudParticles, 2000u);
  EXPECT_NEAR(res.axialLength, 6.0, 1e-12);
  EXPECT_NEAR(res.radialExtent, 2.0, 1e-12);
  EXPECT_NEAR(res.ratio, 3.0, 1e-12);
  EXPECT_NEAR(res.frontSpeed, 5.0, 1e-12);

  FragmentParams bad;
  bad.axis = {0.0, 0.0, 0.0};
  EXPECT_THROW(analyseFragments(x, r, m, v, bad), InputError);
  bad = FragmentParams{};
  bad.bonds = {{0, 999999}};
  EXPECT_THROW(analyseFragments(x, r, m, v, bad), InputError);
}

// Ejecta leaving along the Maxwell Z-model's streamlines at the surface (θ = 90° from the
// downward axis: u_θ / u_R = Z − 2) have the ejection angle atan(Z − 2): 45° for Z = 3 and
// 56.3° for Z = 3.5; particles below the surface or falling back are not ejecta.
TEST(Fragments, EjectaAnglesFollowTheZModel) {
  for (double Z : {3.0, 3.5}) {
    std::vector<double> x, r, m, v;
    Random rng(3);
    for (int k = 0; k < 500; ++k) {
      const double R = rng.uniform(0.5, 2.0), phi = rng.uniform(0.0, 2.0 * M_PI);
      const double uR = 0.1 / (R * R * R),
                   uT = uR * (Z - 2.0); // at θ = 90°: e_R horizontal, e_θ up
      x.insert(x.end(), {R * std::cos(phi), R * std::sin(phi), 0.02});
      v.insert(v.end(), {uR * std::cos(phi), uR * std::sin(phi), uT});
      r.push_back(0.01), m.push_back(rng.uniform(0.5, 2.0));
    }
    x.insert(x.end(), {1.0, 0.0, -0.5}), v.insert(v.end(), {0.0, 0.0, 1.0}), r.push_back(0.01),
        m.push_back(100.0);
    x.insert(x.end(), {1.0, 0.0, 0.5}), v.insert(v.end(), {1.0, 0.0, -1.0}), r.push_back(0.01),
        m.push_back(100.0);
    const double axis[2] = {0.0, 0.0};
    const EjectaStatistics e = ejectaStatistics(x, r, m, v, 0.0, axis);
    EXPECT_EQ(e.count, 500u);
    EXPECT_NEAR(e.meanAngle, std::atan(Z - 2.0) * 180.0 / M_PI, 1e-9);
    EXPECT_NEAR(e.massAbove.back(), e.mass, 1e-12);
    for (std::size_t k = 1; k < e.speed.size(); ++k)
      EXPECT_GE(e.speed[k - 1], e.speed[k]);
  }
}

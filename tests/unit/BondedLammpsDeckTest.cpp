// The bonded LAMMPS deck without LAMMPS (bonded/BondedLammpsDeck.h): the pull-only bond table
// is Eq. 4's force on both sides of its knot at r_eq, so LAMMPS' linear interpolation between
// knots gives bondSpring's force everywhere in the table; the data file holds every particle
// bit for bit, one mass per body and only the intact bonds; the decks name the styles and
// coefficients of the mapping; bad input is refused with InputError.
#include "bonded/BondedLammpsDeck.h"
#include "bonded/BondedBody.h"
#include "bonded/WatsonSteinhauser2017.h"
#include "common/Error.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

using namespace craterkit;

namespace {

BondedSystem block() {
  ws2017::Law law;
  law.sigma = 1e-3;
  law.epsilon = 0.01;
  law.kappa = 4.56e6;
  law.rCut = 1.5e-3;
  BondedSystem s = buildBondedBox(3, 3, 2, law.rEq(), 2700.0, ws2017::sizingOf(law));
  addBoltzmannJitter(s, 1e-3, 7);
  return s;
}

BondedDeckParams deckParams() {
  BondedDeckParams p;
  p.timeStep = 1e-9;
  p.outputTimes = {1e-7, 2e-7};
  return p;
}

} // namespace

TEST(BondedLammpsDeck, TableInterpolatesToEq4) {
  const BondedSystem s = block();
  const ws2017::Law& law = s.law;
  std::istringstream in(bondedBondTable(law));
  std::vector<double> r, f;
  bool knotAtReq = false;
  for (std::string line; std::getline(in, line);) {
    int i;
    double x, e, force;
    if (std::sscanf(line.c_str(), "%d %lf %lf %lf", &i, &x, &e, &force) != 4)
      continue;
    r.push_back(x);
    f.push_back(force);
    knotAtReq = knotAtReq || x == law.rEq();
  }
  ASSERT_GT(r.size(), 100u);
  EXPECT_TRUE(knotAtReq) << "r_eq is not a knot: the kink would be interpolated across";
  EXPECT_LT(r.front(), 0.5 * law.sigma);
  EXPECT_GT(r.back(), law.rCut);
  // Midpoints of every interval: LAMMPS' linear interpolation against Eq. 4 (F = -dU/dr).
  for (std::size_t k = 0; k + 1 < r.size(); ++k) {
    const double mid = 0.5 * (r[k] + r[k + 1]), interpolated = 0.5 * (f[k] + f[k + 1]);
    double fOverR;
    ws2017::bondSpring(mid, law.rEq(), law.kappa, fOverR);
    ASSERT_NEAR(interpolated, -fOverR * mid, 1e-9 * law.kappa * law.sigma) << "r = " << mid;
  }
}

TEST(BondedLammpsDeck, DataFileHoldsTheStateAndTheIntactBonds) {
  const BondedSystem s = block();
  std::vector<std::uint8_t> broken(s.bonds.size(), 0);
  broken[0] = broken[3] = 1;
  const std::string data = bondedLammpsData(s, broken, deckParams());
  EXPECT_NE(data.find(std::to_string(s.size()) + " atoms"), std::string::npos);
  EXPECT_NE(data.find(std::to_string(s.bonds.size() - 2) + " bonds"), std::string::npos);
  // Every velocity, at %.17g, parses back to the same double.
  std::istringstream in(data.substr(data.find("Velocities")));
  std::string line;
  std::getline(in, line);
  std::size_t seen = 0;
  while (std::getline(in, line) && line.find("Bonds") == std::string::npos) {
    unsigned id;
    double v[3];
    if (std::sscanf(line.c_str(), "%u %lf %lf %lf", &id, &v[0], &v[1], &v[2]) != 4)
      continue;
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(v[k], s.velocities[3 * (id - 1) + k]);
    ++seen;
  }
  EXPECT_EQ(seen, s.size());
  // One mass per body: a body whose particles differ is refused.
  BondedSystem uneven = s;
  uneven.masses[1] *= 1.01;
  EXPECT_THROW(bondedLammpsData(uneven, {}, deckParams()), InputError);
}

TEST(BondedLammpsDeck, DecksNameTheMapping) {
  const BondedSystem s = block();
  BondedDeckParams p = deckParams();
  const std::string table = bondedLammpsInput(s, p);
  EXPECT_NE(table.find("bond_style table linear"), std::string::npos);
  EXPECT_NE(table.find("pair_modify shift yes"), std::string::npos);
  EXPECT_NE(table.find("special_bonds lj 1.0 1.0 1.0"), std::string::npos);
  char breaking[96];
  std::snprintf(breaking, sizeof breaking, "bond/break 1 1 %.17g", s.law.rCut);
  EXPECT_NE(table.find(breaking), std::string::npos);
  EXPECT_NE(table.find("run 100\n"), std::string::npos); // 1e-7 s at 1e-9 s
  p.bondStyle = BondedDeckParams::BondStyle::Harmonic;
  char harmonic[96]; // LAMMPS' K (r - r0)^2 is Eq. 4's kappa/2 (r - r0)^2
  std::snprintf(harmonic, sizeof harmonic, "bond_coeff 1 %.17g %.17g", 0.5 * s.law.kappa,
                s.law.rEq());
  EXPECT_NE(bondedLammpsInput(s, p).find(harmonic), std::string::npos);
  p.outputTimes = {2e-7, 1e-7};
  EXPECT_THROW(bondedLammpsInput(s, p), InputError);
  p = deckParams();
  p.timeStep = 0.0;
  EXPECT_THROW(bondedLammpsInput(s, p), InputError);
}

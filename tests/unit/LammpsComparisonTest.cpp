// The same oblique two-sphere collision in CraterKit and in LAMMPS (pair_style granular with
// hooke / linear_history / rolling sds / twisting sds, mapped as in docs/physics.md §1.8).
// Skipped, with a message, when LAMMPS's `lmp` is not installed (scripts/test installs it).
#include "dem/DemSolver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace craterkit;

namespace {

const char* kLammpsInput = R"(units si
atom_style sphere
atom_modify map array
boundary f f f
newton off
comm_modify vel yes
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
create_atoms 1 single 0.0 0.0 0.0 units box
create_atoms 1 single -0.1005 0.05 0.0 units box
set atom * diameter 0.1 density 2000
velocity all set 0 0 0 units box
group mover id 2
velocity mover set 1.0 0.0 0.0 units box
pair_style granular
pair_coeff * * hooke ${kn} ${etan} tangential linear_history ${kt} ${xgt} ${mus} &
  rolling sds ${kr} ${gr} ${mur} twisting sds ${ktw} ${gtw} ${mutw} damping velocity limit_damping
fix 1 all nve/sphere
timestep ${dt}
thermo 0
run ${steps}
write_dump all custom dump.out id vx vy vz omegax omegay omegaz modify format float %.15g
)";

bool haveLammps() { return std::system("command -v lmp > /dev/null 2>&1") == 0; }

struct Outcome {
  double v[2][3];
  double w[2][3];
};

Outcome runCraterKit(const ContactParams& c, double dt, int steps) {
  DemParams p;
  p.gravity.type = Gravity::Type::None;
  p.contact = c;
  p.dt = dt;
  ParticleSet s;
  const double a[3] = {0, 0, 0}, b[3] = {-0.1005, 0.05, 0};
  s.add(a, 0.05, 2000, 0, 1);
  s.add(b, 0.05, 2000, 0, 2);
  s.velocity[3] = 1.0;
  DemSolver solver(s, p);
  for (int i = 0; i < steps; ++i)
    solver.step();
  Outcome o;
  const ParticleSet& out = solver.particles(); // the solver may reorder: index by Id
  for (std::size_t j = 0; j < 2; ++j) {
    const int i = static_cast<int>(out.id[j]) - 1;
    for (int k = 0; k < 3; ++k) {
      o.v[i][k] = out.velocity[3 * j + k];
      o.w[i][k] = out.angularVelocity[3 * j + k];
    }
  }
  return o;
}

Outcome runLammps(const ContactParams& c, double dt, int steps, const std::string& dir) {
  const double r = 0.05, m = 2000 * 4.0 / 3.0 * M_PI * r * r * r, mu = m / 2, rbar = r / 2;
  const double kN = c.kN, kT = c.tangentialStiffness();
  // CraterKit's normal force never pulls (LAMMPS' limit_damping), with the damping that
  // keeps ε_n under that clipping (clippedDampingFactor).
  const double cN =
      clippedDampingFactor(NormalLawKind::LinearSpringDashpot, c.restitutionN) * std::sqrt(kN * mu);
  const double cT = dashpotCoefficient(kT, c.restitutionT, mu);
  const double b = c.beta, br = b * rbar;
  std::ofstream(dir + "/in.oblique") << kLammpsInput;
  std::ostringstream cmd;
  cmd.precision(17);
  // A stale Open MPI session can make a singleton start hang: bound it.
  cmd << "cd '" << dir << "' && timeout 120 lmp -log none -screen none -in in.oblique"
      << " -var kn " << kN << " -var etan " << cN << " -var kt " << kT << " -var xgt " << cT / cN
      << " -var mus " << c.muS << " -var kr " << kN * b * b << " -var gr " << cN * b * b
      << " -var mur " << c.muR * b << " -var ktw " << 2 * kT * br * br << " -var gtw "
      << 2 * cT * br * br << " -var mutw " << c.muT * br * c.muS << " -var dt " << dt
      << " -var steps " << steps;
  if (std::system(cmd.str().c_str()) != 0)
    throw std::runtime_error("LAMMPS failed: " + cmd.str());
  std::ifstream dump(dir + "/dump.out");
  std::string line;
  Outcome o{};
  while (std::getline(dump, line) && line.rfind("ITEM: ATOMS", 0) != 0) {
  }
  for (int k = 0; k < 2; ++k) {
    int id;
    double v[3], w[3];
    dump >> id >> v[0] >> v[1] >> v[2] >> w[0] >> w[1] >> w[2];
    if (!dump || id < 1 || id > 2)
      throw std::runtime_error("cannot parse the LAMMPS dump in " + dir);
    for (int q = 0; q < 3; ++q) {
      o.v[id - 1][q] = v[q];
      o.w[id - 1][q] = w[q];
    }
  }
  return o;
}

} // namespace

TEST(LammpsComparison, ObliqueCollisionRebound) {
  if (!haveLammps())
    GTEST_SKIP() << "LAMMPS (lmp, Debian package lammps) is not installed: comparison skipped";
  const auto dir =
      std::filesystem::temp_directory_path() / ("craterkit-lammps-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // Mostly sticking (mu_s 0.6) and mostly sliding (0.1); rolling and twisting springs on.
  for (double muS : {0.6, 0.1}) {
    ContactParams c;
    c.kN = 1e6;
    c.muS = muS;
    c.muR = 0.1;
    c.muT = 0.1;
    const double m = 2000 * 4.0 / 3.0 * M_PI * std::pow(0.05, 3);
    const double dt = M_PI * std::sqrt(0.5 * m / c.kN) / 200.0;
    const int steps = static_cast<int>(0.05 / dt);
    const Outcome ours = runCraterKit(c, dt, steps), theirs = runLammps(c, dt, steps, dir.string());
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 3; ++k)
        // Rebound velocities within 2 % of the impact speed (1 m/s).
        EXPECT_NEAR(ours.v[i][k], theirs.v[i][k], 0.02)
            << "mu_s " << muS << " particle " << i << " axis " << k;
    // Spins differ more by construction: LAMMPS rescales a slipping spring (pkdgrav zeroes
    // it) and applies the tangential force at R - δ/2 (pkdgrav at l_p). Within 10 %.
    EXPECT_NEAR(ours.w[0][2], theirs.w[0][2], 0.10 * std::abs(theirs.w[0][2])) << "mu_s " << muS;
  }
  std::filesystem::remove_all(dir);
}

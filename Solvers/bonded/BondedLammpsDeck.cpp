// LAMMPS decks of a bonded-particle state: see BondedLammpsDeck.h.
#include "bonded/BondedLammpsDeck.h"

#include "common/AtomicWrite.h"
#include "common/Error.h"
#include "common/LammpsNumber.h"
#include "dem/LammpsDeck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

namespace craterkit {

namespace {

std::string num(double v) { return lammpsNumber(v); }

// Table knots: spacing r_eq / 1200 from r_eq / 4 (far inside the repulsion, which keeps pairs
// beyond ~0.7 σ even at 10 km/s) to 2 r_eq or 1.5 r_cut, with r_eq itself a knot.
constexpr int kBelow = 900, kPerReq = 1200;
int knotsAbove(const ws2017::Law& law) {
  const double top = std::max(2.0 * law.rEq(), 1.5 * law.rCut);
  return static_cast<int>(std::ceil((top - law.rEq()) / (law.rEq() / kPerReq)));
}

void checkLaw(const ws2017::Law& law) {
  if (!(law.sigma > 0.0 && law.epsilon > 0.0 && law.kappa > 0.0 && law.rCut > law.rEq()))
    throw InputError("bonded LAMMPS deck: the law needs σ, ε, κ > 0 and r_cut > r_eq");
}

} // namespace

void BondedDeckParams::validate() const {
  if (!(timeStep > 0.0) || !std::isfinite(timeStep))
    throw InputError("bonded LAMMPS deck: the time step must be > 0, got " + num(timeStep));
  if (!(skin > 0.0))
    throw InputError("bonded LAMMPS deck: the skin must be > 0, got " + num(skin));
  checkLammpsOutputTimes(outputTimes, timeStep, "bonded LAMMPS deck");
  for (const std::string& name : {dataFile, inputFile, dumpFile, tableFile})
    checkLammpsFileName(name, "bonded LAMMPS deck");
}

std::string bondedBondTable(const ws2017::Law& law) {
  checkLaw(law);
  const double r0 = law.rEq(), dr = r0 / kPerReq;
  const int above = knotsAbove(law);
  std::ostringstream s;
  s << "# Watson & Steinhauser 2017 Eq. 4 (CraterKit bonded/BondedLammpsDeck): energy\n"
       "# 1/2 kappa (r - r0)^2 and force -kappa (r - r0) beyond r0 = r_eq, none below.\n"
       "# kappa = "
    << num(law.kappa) << " N/m, r0 = " << num(r0) << " m.\n\nWS2017_EQ4\nN " << kBelow + above + 1
    << "\n\n";
  for (int i = -kBelow; i <= above; ++i) {
    const double r = r0 + i * dr, stretch = i > 0 ? r - r0 : 0.0;
    s << i + kBelow + 1 << " " << num(r) << " " << num(0.5 * law.kappa * stretch * stretch) << " "
      << num(-law.kappa * stretch) << "\n";
  }
  return s.str();
}

std::string bondedLammpsData(const BondedSystem& sys, const std::vector<std::uint8_t>& broken,
                             const BondedDeckParams& params) {
  const std::size_t n = sys.size();
  if (n == 0)
    throw InputError("bonded LAMMPS deck: no particles");
  if (n >= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError("bonded LAMMPS deck: " + std::to_string(n) + " particles exceed 32-bit ids");
  if (!broken.empty() && broken.size() != sys.bonds.size())
    throw InputError("bonded LAMMPS deck: " + std::to_string(broken.size()) + " bond states for " +
                     std::to_string(sys.bonds.size()) + " bonds");
  int bodies = 1;
  for (std::uint8_t b : sys.body)
    bodies = std::max(bodies, b + 1);
  std::vector<double> mass(static_cast<std::size_t>(bodies), -1.0);
  for (std::size_t i = 0; i < n; ++i) {
    double& m = mass[sys.body[i]];
    if (m < 0.0)
      m = sys.masses[i];
    else if (m != sys.masses[i])
      throw InputError("bonded LAMMPS deck: particle " + std::to_string(i) + " of body " +
                       std::to_string(sys.body[i]) + " has mass " + num(sys.masses[i]) +
                       ", another of its body " + num(m) + " (LAMMPS' bond style: one per type)");
  }
  const double r0 = sys.law.rEq();
  std::size_t intact = 0;
  for (std::size_t b = 0; b < sys.bonds.size(); ++b) {
    if (!broken.empty() && broken[b])
      continue;
    ++intact;
    if (std::abs(sys.bonds[b].rest - r0) > 1e-9 * r0)
      throw InputError("bonded LAMMPS deck: bond " + std::to_string(b) + " rests at " +
                       num(sys.bonds[b].rest) + " m, not at r_eq " + num(r0) +
                       " m (one bond type)");
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -lo[k];
    for (std::size_t i = 0; i < n; ++i) {
      lo[k] = std::min(lo[k], sys.positions[3 * i + k]);
      hi[k] = std::max(hi[k], sys.positions[3 * i + k]);
    }
  }
  std::ostringstream s;
  s << "CraterKit bonded state at t = " << num(params.startTime)
    << " s (atom_style bond; atom id = index + 1, type = body + 1)\n\n"
    << n << " atoms\n"
    << bodies << " atom types\n"
    << intact << " bonds\n1 bond types\n\n";
  const char* axis = "xyz";
  for (int k = 0; k < 3; ++k) // shrink-wrapped boundaries: the box only has to hold the atoms
    s << num(lo[k] - sys.law.sigma) << " " << num(hi[k] + sys.law.sigma) << " " << axis[k] << "lo "
      << axis[k] << "hi\n";
  s << "\nMasses\n\n";
  for (int b = 0; b < bodies; ++b)
    s << b + 1 << " " << num(mass[static_cast<std::size_t>(b)] > 0.0 ? mass[b] : 1.0) << "\n";
  s << "\nAtoms # bond\n\n";
  for (std::size_t i = 0; i < n; ++i)
    s << i + 1 << " " << sys.body[i] + 1 << " " << sys.body[i] + 1 << " "
      << num(sys.positions[3 * i]) << " " << num(sys.positions[3 * i + 1]) << " "
      << num(sys.positions[3 * i + 2]) << "\n";
  s << "\nVelocities\n\n";
  for (std::size_t i = 0; i < n; ++i)
    s << i + 1 << " " << num(sys.velocities[3 * i]) << " " << num(sys.velocities[3 * i + 1]) << " "
      << num(sys.velocities[3 * i + 2]) << "\n";
  if (intact > 0) {
    s << "\nBonds\n\n";
    std::size_t id = 0;
    for (std::size_t b = 0; b < sys.bonds.size(); ++b)
      if (broken.empty() || !broken[b])
        s << ++id << " 1 " << sys.bonds[b].i + 1 << " " << sys.bonds[b].j + 1 << "\n";
  }
  return s.str();
}

std::string bondedLammpsInput(const BondedSystem& sys, const BondedDeckParams& params) {
  params.validate();
  checkLaw(sys.law);
  const ws2017::Law& law = sys.law;
  const double skin = params.skin * law.sigma;
  std::ostringstream s;
  s << "# CraterKit bonded-particle stage for LAMMPS (Watson & Steinhauser 2017; written by\n"
       "# CraterKit's BondedLammpsDeck, mapping in Solvers/bonded/BondedLammpsDeck.h and\n"
       "# docs/lammps.md). Needs the MOLECULE package (bond styles) and fix bond/break (the MC\n"
       "# package); tested with LAMMPS 29 Sep 2021. Run: scripts/run-lammps DIR RANKS.\n"
       "# Times in the dump count from the state's time "
    << num(params.startTime) << " s.\n"
    << "units si\natom_style bond\nboundary s s s\natom_modify map array\n"
    << "read_data " << params.dataFile
    << "\n"
    // fix bond/break updates the special lists of a broken bond's partners: ghosts out to two
    // bonds.
    << "comm_modify cutoff " << num(2.0 * law.rCut + 2.0 * skin) << "\n"
    << "pair_style lj/cut " << num(law.rEq()) << "\npair_coeff * * " << num(law.epsilon) << " "
    << num(law.sigma) << " " << num(law.rEq()) << "\npair_modify shift yes\n";
  if (params.bondStyle == BondedDeckParams::BondStyle::PullOnly)
    s << "bond_style table linear " << kBelow + knotsAbove(law) + 1 << "\nbond_coeff 1 "
      << params.tableFile << " WS2017_EQ4\n";
  else
    s << "bond_style harmonic\nbond_coeff 1 " << num(0.5 * law.kappa) << " " << num(law.rEq())
      << "\n";
  s << "special_bonds lj 1.0 1.0 1.0\n"
    << "neighbor " << num(skin) << " bin\nneigh_modify every 1 delay 0 check yes\n"
    << "fix integrate all nve\n"
    << "fix break all bond/break 1 1 " << num(law.rCut) << "\n"
    << "timestep " << num(params.timeStep) << "\n"
    << "thermo_style custom step time ke evdwl ebond f_break[2]\nthermo_modify norm no\n"
    << "thermo "
    << std::max<long long>(1, std::llround(params.outputTimes.back() / params.timeStep) / 20)
    << "\n";
  const std::string dump = "write_dump all custom " + params.dumpFile +
                           " id type x y z vx vy vz mass modify format float %.17g time yes"
                           " append yes\n";
  const std::string report = "print \"craterkit: time $(time:%.17g) broken $(f_break[2]) kinetic "
                             "$(ke:%.17g) repulsive $(evdwl:%.17g) bond $(ebond:%.17g)\"\n";
  long long done = 0;
  for (double t : params.outputTimes) {
    const long long steps = std::llround(t / params.timeStep);
    s << "run " << steps - done << "\n" << dump << report;
    done = steps;
  }
  return s.str();
}

BondedSystem bondedSetUpState(const ParticleSet& p, const ws2017::Law& law) {
  checkLaw(law);
  const std::size_t n = p.size();
  BondedSystem s;
  s.law = law;
  s.positions.resize(3 * n);
  s.velocities.resize(3 * n);
  s.masses.resize(n);
  s.body.resize(n);
  std::vector<char> seen(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::int64_t id = p.id[k];
    if (id < 0 || static_cast<std::size_t>(id) >= n || seen[static_cast<std::size_t>(id)])
      throw InputError("bonded LAMMPS deck: the Ids must be 0 .. " + std::to_string(n - 1) +
                       " once each (a BondedImpact output), got " + std::to_string(id));
    if (p.material[k] != 0 && p.material[k] != 1)
      throw InputError("bonded LAMMPS deck: Material " + std::to_string(p.material[k]) +
                       " is neither projectile (0) nor plate (1)");
    const std::size_t i = static_cast<std::size_t>(id);
    seen[i] = 1;
    for (int c = 0; c < 3; ++c) {
      s.positions[3 * i + c] = p.position[3 * k + c];
      s.velocities[3 * i + c] = p.velocity[3 * k + c];
    }
    s.masses[i] = p.mass[k];
    s.body[i] = static_cast<std::uint8_t>(p.material[k]);
  }
  formBonds(s);
  return s;
}

void writeBondedLammpsDeck(const std::string& dir, const BondedSystem& system,
                           const std::vector<std::uint8_t>& broken,
                           const BondedDeckParams& params) {
  const std::string input = bondedLammpsInput(system, params);
  const std::string data = bondedLammpsData(system, broken, params);
  std::filesystem::create_directories(dir);
  if (params.bondStyle == BondedDeckParams::BondStyle::PullOnly) {
    const std::string table = bondedBondTable(system.law);
    writeFileAtomically(dir + "/" + params.tableFile, "LAMMPS bond table",
                        [&](std::ostream& out) { out << table; });
  }
  writeFileAtomically(dir + "/" + params.dataFile, "LAMMPS data file",
                      [&](std::ostream& out) { out << data; });
  writeFileAtomically(dir + "/" + params.inputFile, "LAMMPS input deck",
                      [&](std::ostream& out) { out << input; });
}

} // namespace craterkit

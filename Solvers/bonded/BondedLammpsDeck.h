// LAMMPS input decks from a bonded-particle state (issue 34, item 4): the hypervelocity model of
// Watson & Steinhauser 2017 (Materials 10:379, seed 003; bonded/WatsonSteinhauser2017.h) handed
// to LAMMPS, so that a sweep of the seed can run on a cluster with MPI.
//
// The mapping, term by term (docs/lammps.md has the table):
//   repulsion  Eq. 3, 4ε[(σ/r)^12 − (σ/r)^6] + ε for r < r_eq = 2^{1/6} σ: `pair_style lj/cut`
//              cut at r_eq with `pair_modify shift yes` (WCA). Exact. Bonded pairs repel too
//              (`special_bonds lj 1 1 1`), as in BondedSolver.
//   bond       Eq. 4, ½κ(r − r0)² for r > r0 only. PullOnly (default): `bond_style table
//              linear` with the force −κ(r − r0) above r0 and 0 below, tabulated on knots that
//              include r0 (LAMMPS' linear interpolation between knots is then the exact
//              piecewise-linear force, to rounding). Harmonic: `bond_style harmonic` with
//              K = κ/2 (LAMMPS' energy K(r − r0)²), which also pushes when compressed: the
//              faster choice the speed benchmark uses (benchmarks/hvi_bonded), not Eq. 4.
//              r0 = r_eq for every bond (BondedSolver keeps each bond's set-up separation, equal
//              to r_eq to rounding on the lattice; a bond whose rest length differs by more than
//              1e-9 r_eq is refused).
//   breaking   Section 2.2.2, a bond longer than r_cut is removed for good, checked after the
//              drift: `fix bond/break 1 1 r_cut` (LAMMPS' MC package), also after the drift
//              (post_integrate). Differs: LAMMPS breaks at most one bond per atom per step (its
//              longest), BondedSolver all of them; a second bond of an atom breaks a step later.
//   integrator velocity Verlet with BondedSolver's step: `fix nve`, `timestep`.
// Data file: atom_style bond, atom id = index + 1, molecule and type = body + 1, one mass per
// body (Eq. 20: every particle of a body has its mass; otherwise InputError), the intact bonds.
// Every output time writes a dump (id type x y z vx vy vz mass, ITEM: TIME) and a line
//   craterkit: time T broken B kinetic K repulsive R bond E
// to the log (B counts the bonds LAMMPS broke since the deck's start).
#pragma once

#include "bonded/BondedBody.h"
#include "common/ParticleSet.h"

#include <cstdint>
#include <string>
#include <vector>

namespace craterkit {

struct BondedDeckParams {
  enum class BondStyle { PullOnly, Harmonic };
  BondStyle bondStyle = BondStyle::PullOnly;
  double timeStep = 0.0;           // s (> 0): BondedSolver::timeStep()
  std::vector<double> outputTimes; // s after the state's time: increasing, > 0
  double startTime = 0.0;          // simulation time of the state (for the header only)
  double skin = 0.3;               // Verlet skin in units of σ (BondedSolverParams::skin)
  std::string dataFile = "data.craterkit";
  std::string inputFile = "in.craterkit";
  std::string dumpFile = "dump.craterkit";
  std::string tableFile = "bond.table"; // PullOnly only
  void validate() const;                // throws InputError
};

// The data file (intact bonds only: BROKEN[b] != 0 leaves bond b out; empty = all intact).
std::string bondedLammpsData(const BondedSystem& system, const std::vector<std::uint8_t>& broken,
                             const BondedDeckParams& params);
std::string bondedLammpsInput(const BondedSystem& system, const BondedDeckParams& params);
// The PullOnly bond table (section WS2017_EQ4: index, r, energy, force).
std::string bondedBondTable(const ws2017::Law& law);
// The set-up state of a bonded run from its particles (a BondedImpact output at step 0: Id =
// index, Material = body, positions, velocities, masses) and its law: the bonds re-formed as
// buildBondedImpact formed them (formBonds: pairs of one body closer than r_cut). Later states
// cannot be rebuilt this way (which bonds broke is not in the particle arrays). InputError if
// the Ids are not 0 .. n-1 or a Material is not 0 or 1.
BondedSystem bondedSetUpState(const ParticleSet& particles, const ws2017::Law& law);
// Writes the deck's files into DIR (created if needed), each atomically.
void writeBondedLammpsDeck(const std::string& dir, const BondedSystem& system,
                           const std::vector<std::uint8_t>& broken, const BondedDeckParams& params);

} // namespace craterkit

// LAMMPS input decks from a CraterKit DEM state (issue 34): hands the DEM stage to LAMMPS
// (MPI, `pair_style granular`) and brings its dumps back through the LAMMPS dump reader.
//
// Writes a data file (atom_style sphere: id type diameter density x y z; Velocities: id v ω)
// and an input deck that reproduces the pkdgrav SSDEM contact law of dem/ContactModels.h
// (Schwartz, Richardson & Michel 2012, Granular Matter 14:363, Eqs. 3, 6-7, 15-19; rolling
// and twisting after Zhang et al. 2017, Icarus 294:98) as closely as `pair_style granular`
// allows. The mapping, term by term (docs/lammps.md has the table):
//   normal      hooke k_N (linear) or hertz 4/3 E* (F = k a δ, a = sqrt(R* δ)); the damping
//               `damping tsuji`, whose coefficient α sqrt(m* k) has CraterKit's form
//               f sqrt(k μ) for every pair: the deck's "restitution" e' is chosen so that
//               Tsuji's polynomial α(e') equals clippedDampingFactor(ε_n) (Hertz: times
//               sqrt(3/2), LAMMPS' knfac being 4/3 E* a where CraterKit uses 2 E* a);
//               `limit_damping` is CraterKit's clipping at zero force. Exact.
//   tangential  linear_history k_T (Hertz: mindlin 8 G* = 2(1-ν)/(2-ν) 2 E*); x_γ,t =
//               C_T / C_N, a constant ratio, so exact for every pair. Differs on slip:
//               LAMMPS rescales the spring to the Coulomb limit, pkdgrav zeroes it.
//   rolling     sds k_roll = k_N β², γ_roll = C_N β², μ_roll = μ_r β (torque R* k_roll ξ;
//               CraterKit k_N (β R*)²). γ_roll is a constant in LAMMPS: C_N taken for the
//               median grain pair (exact for a monodisperse bed); Hertz: k_N at the
//               reference overlap. LAMMPS' rolling rate lacks the unequal-radius term of
//               Kuhn & Bagi that CraterKit adds (dem/ContactModels.h rollingRate).
//   twisting    sds k = 2 k_T (β R*)², γ = 2 C_T (β R*)², μ = μ_t β R* μ_s with R* of the
//               median grain pair (LAMMPS' coefficients carry no radius).
//   lever arm   LAMMPS applies the tangential force at R - δ/2 from each centre; CraterKit
//               at the radical plane of the two spheres (the same for equal radii).
// Walls: axis-aligned planes as `fix wall/gran` planes, other planes and cylinders as
// `fix wall/gran/region`, the bowl as the union of a sphere and the cylinder above its rim
// (`fix wall/gran/region`), with the wall coefficients of a partner of infinite mass and
// radius. Refused (InputError naming the problem): disk walls, point-mass gravity,
// cohesion, tilted bowls and cylinders, Ids LAMMPS cannot hold.
// LAMMPS atom ids start at 1: atom id = Id + 1 (the data parser and the dumps' readers
// subtract it back: Id = atom id - 1).
#pragma once

#include "common/ParticleSet.h"
#include "dem/DemSolver.h"

#include <string>
#include <string_view>
#include <vector>

namespace craterkit {

struct LammpsDeckParams {
  DemParams dem;                   // contact law, walls, gravity, dt (> 0), skin
  std::vector<double> outputTimes; // s after the state's time: increasing, > 0
  double startTime = 0.0;          // simulation time of the state (for the header only)
  std::string dataFile = "data.craterkit";
  std::string inputFile = "in.craterkit";
  std::string dumpFile = "dump.craterkit"; // every output time, appended (ITEM: TIME = t)
  void validate() const;                   // throws InputError
};

// The `pair_style granular` coefficients for one kind of contact (grain pairs, or walls).
struct LammpsCoefficients {
  double kN = 0, dampingRestitution = 0;          // hooke / hertz k and Tsuji's e'
  double kT = 0, xGammaT = 0, muS = 0;            // linear_history / mindlin
  double kRoll = 0, gammaRoll = 0, muRoll = 0;    // rolling sds
  double kTwist = 0, gammaTwist = 0, muTwist = 0; // twisting sds
  bool hertz = false;
  std::string pairCoeff() const; // the model words after `pair_coeff * *`
};

// The deck's text conventions, shared with the bonded decks (bonded/BondedLammpsDeck; numbers
// are written by common/LammpsNumber.h): output times each at least one step after the
// previous (InputError prefixed with WHAT); file names without slashes, blanks or quotes.
void checkLammpsOutputTimes(const std::vector<double>& times, double dt, const std::string& what);
void checkLammpsFileName(const std::string& name, const std::string& what);

// Tsuji et al. (1992)'s damping ratio as LAMMPS evaluates it for `damping tsuji`, and the
// restitution e' in [0, 1] at which it equals ALPHA (InputError if none).
double tsujiAlpha(double e);
double tsujiRestitutionFor(double alpha);

// Coefficients for grain pairs (wall = false) or grain-wall contacts, for the state P.
LammpsCoefficients lammpsCoefficients(const ContactParams& c, const ParticleSet& p, bool wall);

// The data file and the input deck as text (ids and coefficients checked: InputError).
std::string lammpsDataFile(const ParticleSet& particles, const LammpsDeckParams& params);
std::string lammpsInputDeck(const ParticleSet& particles, const LammpsDeckParams& params);
// Writes both into DIR (created if needed), each atomically.
void writeLammpsDeck(const std::string& dir, const ParticleSet& particles,
                     const LammpsDeckParams& params);

// Parses a data file written by lammpsDataFile back (Id = atom id - 1; mass from diameter
// and density as LAMMPS computes it). Throws ParseError naming the file and line.
ParticleSet parseLammpsData(std::string_view text, const std::string& fileName);

} // namespace craterkit

// Time integration of the bonded-particle model of Watson & Steinhauser 2017 (Materials 10:379,
// seed 003, Eq. 1 with the potentials of Eqs. 3–4; see WatsonSteinhauser2017.h).
//
// Velocity Verlet with a constant Δt, no friction, no damping (Dissipation None, the paper's
// model; ShockViscosity adds a pair viscosity in fast compression as a pulse every few whole
// steps, keeping the energy it takes as internal energy: ShockViscosity.h). Δt is a fixed
// fraction of the bond period 2π√(m/κ); the default fraction gives the paper's 1e-10 s at its
// headline size and, since m ∝ σ³ and κ ∝ σ, scales with σ like every other time of the sized
// model.
//
// Every pair of particles is handled in one fused pass per particle over its pair list: the
// particles it may touch before the next rebuild (a full Verlet list: all particles within
// r_eq + skin, found in the 27 cells of the reach around its own (the common CellList's sparse
// layout, whose cells keep their size however wide the debris cloud), rebuilt when two particles
// may have closed in on each other by more than the skin, bounded region by region on their
// measured displacements (BondedListTrigger), so that the fastest fragments do not set the bound
// of particles that move with their neighbours) together with its bonded partners however far,
// each entry carrying the rest length of its
// intact bond (or none): on the lattice the nearest neighbours' are r_eq to rounding, stored as
// 4-byte float offsets from r_eq where every bond's rest length is that sum exactly (else, e.g.
// with r_cut above √2 r_eq, where the diagonal neighbours are bonded too, as doubles). One entry
// gives the pair's repulsion (closer than r_eq) and spring (stretched bond) at once
// (ws2017::pairForceOverR), and each pair is computed twice, once from each side, with exactly
// opposite results. The lists are stored in blocks of eight particles, entry k of the eight
// particles side by side (padded with the particle itself, which contributes nothing), so that the
// pass runs eight particles per SIMD instruction with every particle's own sum in its own lane, in
// the order of its list. Each step, after the drift, a bond longer than r_cut is broken for good by
// both its particles' passes alike (the squared distance has the same bits from either side); its
// spring energy is booked as dissipated (so that kinetic + repulsive + bond + dissipated energy is
// what the integrator conserves).
//
// Where the AVX-512 passes run, the second half kick of a step is left to the next step's
// kick-drift (which streams v, f and m anyway) with the operation the force pass would have done,
// so the force pass writes f only; every public call (step, advance) ends with it done. Inside
// advance(), between progress reports, the force pass also does the next step's kick-drift, chunk
// by chunk once a chunk's forces are final (the second half kick, the next first half kick, the
// drift into a second position buffer, the velocities' spread): the same operations in the same
// order, so the same bits, without a separate pass over x, v, f and m. The rebuild tests its
// candidates on a copy of the positions in the cell list's order.
//
// OpenMP without atomics (chunks handed out dynamically, which changes no result): each particle
// sums its own list entries in index order of the partners, and energies are summed over fixed-size
// chunks in chunk order. Results are therefore bit-identical for any thread count; and because
// pairs out of range contribute an exact zero and sums keep their order, a run restored from a
// checkpoint (which stores positions, velocities, forces and bond states) continues
// bit-identically.
#pragma once

#include "bonded/BondedBody.h"
#include "bonded/BondedForces.h"
#include "bonded/BondedListTrigger.h"
#include "bonded/ShockViscosity.h"
#include "common/CellList.h"
#include "common/Progress.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace craterkit {

struct BondedSolverParams {
  double timeStep = 0.0;                                         // s; 0: fraction × period
  double timeStepFraction = ws2017::referenceTimeStepFraction(); // of the bond period
  double skin = 0.3;                                             // Verlet skin, units of σ
  // The shock heating beyond the paper (ShockViscosity.h); None: the paper's model, bit for bit.
  BondedDissipation dissipation = BondedDissipation::None;
  // Calibrated against aluminium's waste heat (docs/physics.md §5.1).
  double shockViscosityLinear = 0.0;      // C_L
  double shockViscosityQuadratic = 0.05;  // C_Q
  double shockViscosityThreshold = 500.0; // w_th, m/s
  ShockViscosityParams shockViscosity() const {
    return {shockViscosityLinear, shockViscosityQuadratic, shockViscosityThreshold};
  }
  void validate() const;
};

struct BondedEnergies {
  double kinetic = 0.0, repulsive = 0.0, bond = 0.0;
  double dissipated = 0.0; // spring energy of the bonds at the moment they broke
  double internal = 0.0;   // the shock heating's internal energy (0 without it)
  double total() const { return kinetic + repulsive + bond + dissipated + internal; }
};

class BondedSolver {
public:
  BondedSolver(BondedSystem system, const BondedSolverParams& params = {});

  void step();
  // Advances `steps` steps; reports progress every ~1 % and throws Aborted (after a complete
  // step) when the callback returns false.
  void advance(std::size_t steps, const ProgressCallback& progress = {});
  // Advances to the first step at or after `time`.
  void advanceTo(double time, const ProgressCallback& progress = {});

  BondedEnergies energies() const;
  std::array<double, 3> momentum() const;

  double timeStep() const { return dt_; }
  double time() const { return dt_ * static_cast<double>(step_); }
  std::uint64_t stepCount() const { return step_; }
  std::size_t brokenBonds() const { return broken_; }
  // Pair-list builds since construction or restore (the restore's own build included).
  std::size_t listBuilds() const { return builds_; }
  // Measurements of the particles' relative motion since construction (BondedListTrigger).
  std::size_t listMeasurements() const { return trigger_.measurements(); }
  const BondedSystem& system() const { return sys_; }
  const BondedSolverParams& params() const { return params_; }
  const std::vector<std::uint8_t>& bondBroken() const { return bondBroken_; }
  const std::vector<double>& forces() const { return force_; }
  // Each particle's internal energy in J (the shock heating's; zeros without it).
  const std::vector<double>& internalEnergy() const { return internal_; }
  // Steps between the shock heating's pulses (0 without it).
  std::uint64_t dissipationInterval() const { return viscosity_ ? viscosity_->interval() : 0; }
  // Whether the pair lists hold the rest lengths as 4-byte offsets from r_eq (else as doubles).
  bool compactLists() const { return compact_; }
  // Runs the generic passes even where the AVX-512 ones could (both give the same bits there).
  void useGenericPasses() { avx512_ = false; }
  // Holds the rest lengths as doubles from now on even where the compact lists could (both give
  // the same bits there); between steps.
  void useWideLists();

  // Whole state, through writeFileAtomically; readCheckpoint gives a bit-identical run (format
  // and code: bonded/BondedCheckpoint.h, .cpp). A damaged file throws InputError naming it
  // ("PATH: the checkpoint is corrupt (checksum mismatch)"); an old one without a checksum reads
  // with a warning in warnings().
  void writeCheckpoint(const std::string& path) const;
  static BondedSolver readCheckpoint(const std::string& path);
  // Warnings about this run's state, each a sentence (an old checkpoint it was read from).
  const std::vector<std::string>& warnings() const { return warnings_; }

private:
  BondedSolver() = default;
  void prepare();
  void buildPairs();
  // The forces (and the second half kick if `kick`); if `driftNext`, the next step's kick-drift
  // too, into the second position buffer, swapped in after the pass (drifted_).
  void computeForces(bool kick, bool driftNext = false);
  void bookBreaks();
  // One step; where the AVX-512 passes run, the second half kick is left pending (kickPending_)
  // and done by the next step's kick-drift, so that the force pass does not stream v and m. With
  // `driftNext`, that kick-drift is done inside this step's force pass (the state is then not
  // whole until the next step).
  void stepDeferred(bool driftNext);
  bondedpass::VelocitySpread kickDrift();
  void settle();    // the pending half kick, if any: every public call ends with none pending
  void dissipate(); // a pulse of the shock heating, on a whole state

  BondedSystem sys_;
  BondedSolverParams params_;
  double dt_ = 0.0;
  std::uint64_t step_ = 0;
  std::size_t broken_ = 0;
  std::size_t builds_ = 0;
  double dissipated_ = 0.0;
  // The shock heating (none for the paper's model), each particle's internal energy (J) and
  // the pulses' scratch (4 doubles a particle).
  std::optional<ShockViscosity> viscosity_;
  std::vector<double> internal_;
  std::vector<double> pulseScratch_;
  std::vector<double> force_;
  BondedListTrigger trigger_; // when the lists must be rebuilt
  bool kickPending_ = false;
  bool avx512_ = bondedpass::avx512Available(); // the AVX-512 passes (x86-64-v4), else generic
  // The second position buffer the force pass drifts into; drifted_: the positions are already
  // those of the next step's drift, with the velocities' spread after its kicks.
  std::vector<double> nextX_;
  bool drifted_ = false;
  bondedpass::VelocitySpread spread_;
  std::vector<std::uint8_t> bondBroken_; // 0 intact, 1 broken
  std::vector<std::size_t> bondStart_;   // each particle's bonds: bondsOf_[bondStart_[i]...]
  std::vector<std::uint32_t> bondsOf_;
  // Pair lists in blocks of kLanes particles: block b's entries are [blockStart_[b],
  // blockStart_[b + 1]), entry k of its lane l at blockStart_[b] + k kLanes + l.
  static constexpr std::size_t kLanes = 8;
  std::vector<std::size_t> blockStart_;
  std::vector<std::uint32_t> partner_; // the other particle (the particle itself: padding)
  // Each entry's rest length of the pair's intact bond, or +∞: where every bond's rest length
  // is r_eq plus a float offset exactly (the lattice's nearest neighbours), the compact
  // lists hold the offsets (4 bytes an entry, +∞ for none; compact_, rest_ empty); else rest_.
  std::vector<float> offset_;
  std::vector<double> rest_;
  double restRef_ = 0.0; // r_eq, the offsets' reference
  bool compact_ = false;
  std::vector<std::uint32_t> blockBreaks_; // bonds broken in the last pass, per block
  // The rebuild's buffers: the cell list with a copy of the positions in its order, each chunk's
  // staged (partner, rest) lists and each particle's list length.
  CellList cells_;
  std::vector<double> cellX_, cellY_, cellZ_; // the positions in the cell list's order
  std::vector<std::uint32_t> cellId_;         // and the particles' indices
  std::vector<std::vector<std::pair<std::uint32_t, double>>> staged_;
  std::vector<std::uint32_t> listed_;
  std::vector<std::string> warnings_;
};

} // namespace craterkit

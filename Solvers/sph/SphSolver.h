// The SPH solver for the shock and excavation stage (docs/physics.md §2).
//
// Continuity (integrated or summation density), momentum with the full stress tensor and
// energy in the symmetric forms of §2.2; Monaghan artificial viscosity (§2.3) and optional
// XSPH; deviatoric stress from Hooke's law with the Jaumann rate; strength: von Mises for
// metals, Drucker–Prager matched to the Mohr–Coulomb compression cone for granular material
// (§2.5), and P–α porosity with the quadratic crush curve (§2.6), in sph/Strength.h;
// Grady–Kipp fracture (§2.7) in sph/GradyKippFracture.h; equations of state by material
// (sph/Eos.h); smoothing length following the density (h = κ (m/ρ)^{1/3}, support h);
// periodic or open boundaries; uniform or point-mass gravity; Heun's predictor–corrector (RK2)
// with the Courant and force time steps and error control (a step whose Euler predictor and
// Heun corrector differ by more than a tolerance is taken again, shorter).
//
// In the late stage, optionally, individual power-of-two time steps (SphParams::
// blockStepLevels; sph/BlockSteps.cpp): step() then takes one block cycle, after which all
// particles are at the same time again.
//
// Neighbours: Verlet lists from sparse cell lists, kept over steps (sph/NeighbourList.h).
// OpenMP over particles; each particle sums only its own rates, so results are the same bits
// for any thread count.
#pragma once

#include "sph/GradyKippFracture.h"
#include "sph/NeighbourList.h"
#include "sph/SphParams.h"
#include "sph/SphState.h"
#include "sph/WallBoundary.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

// Where a state restored from a snapshot or checkpoint stands: its time, its step count and
// the step the run would have taken next (0: the solver's own stable step).
struct SphClock {
  double time = 0.0;
  std::size_t steps = 0;
  double nextStep = 0.0;
};

class SphSolver {
public:
  // A state after the late-stage time (clock.time > SphParams::lateStageTime) is the late
  // stage's: its materials are switched before the state is first settled, and its stress is
  // not scaled again. One at that time exactly (a checkpoint written where the run stopped for
  // the switch) is still the early stage's: the next step switches and scales it.
  SphSolver(const SphState& initial, const SphParams& params, const SphClock& clock = {});
  // One Heun step of at most dt (0: the stable step); returns the step taken, shorter than
  // asked when the error control needs it.
  double step(double dt = 0.0);
  void advanceTo(double t);
  double time() const { return time_; }
  // Whether the clock stands at t: what is left is below the clock's rounding or the shortest
  // step (advanceTo's and SphRun's loops end there).
  bool reached(double t) const;
  bool lateStage() const { return late_; }
  // The late-stage law's sound speed now (0 before the switch; sph/LateStageSchedule.h).
  double lateStageSoundSpeed() const { return lateC_; }
  std::size_t steps() const { return steps_; }
  std::size_t neighbourBuilds() const { return nb_.builds(); }       // neighbour lists built so far
  std::size_t neighbourRefreshes() const { return nb_.refreshes(); } // partial rebuilds so far
  // Particle a's listed neighbours (index * 32 + periodic image code) in the current
  // lists (a full build or a partial rebuild), sorted, and its margin in that build (tests check
  // them against all pairs).
  std::vector<std::uint32_t> neighboursOf(std::size_t a) const { return nb_.sortedOf(a); }
  double neighbourMargin(std::size_t a) const { return nb_.margin(a); }
  const SphState& state() const { return s_; }
  const SphParams& params() const { return par_; }
  const std::vector<double>& pressure() const { return p_; }
  const std::vector<double>& soundSpeed() const { return c_; }
  double stableStep() const { return stableStep_; }
  // How the last step went (diagnostics): tries (1: taken at once), its Euler–Heun error and
  // the particle with the largest, and whether the step size proposed next was held back by
  // the error control's growth cap rather than by the Courant and force limits.
  struct StepRecord {
    int attempts = 0;
    double error = 0.0;
    std::size_t worst = 0;
    bool errorCapped = false;
  };
  const StepRecord& lastStep() const { return record_; }
  // The Courant and force limits of the current state and the particles that set them.
  struct Limits {
    double courant = INFINITY, force = INFINITY;
    std::size_t courantParticle = 0, forceParticle = 0;
  };
  Limits limits() const;
  // Each particle's own stable step (its Courant and force limits) in the current state: what
  // individual time steps would allow it.
  std::vector<double> particleSteps() const;
  // Block steps (late stage with SphParams::blockStepLevels > 0): the smallest steps
  // (substeps) and particle updates (rate evaluations of one particle) so far, the neighbours
  // woken by the limiter, and updates at a step beyond its particle's limit (its limit fell
  // below the cycle's smallest step).
  struct BlockStats {
    std::size_t substeps = 0, updates = 0, wakes = 0, overruns = 0;
  };
  const BlockStats& blockStats() const { return blk_.stats; }
  // Each particle's current step in the block cycle, as log2 of the cycle's ticks.
  const std::vector<int>& blockLevels() const { return blk_.level; }
  double kineticEnergy() const { return craterkit::kineticEnergy(s_); }
  double internalEnergy() const { return craterkit::internalEnergy(s_); }
  // In the uniform field and the point mass.
  double potentialEnergy() const { return craterkit::potentialEnergy(s_, par_); }
  double totalEnergy() const { return kineticEnergy() + internalEnergy() + potentialEnergy(); }
  void totalMomentum(double p[3]) const { craterkit::totalMomentum(s_, p); }
  // About the origin.
  void totalAngularMomentum(double L[3]) const { craterkit::totalAngularMomentum(s_, L); }

private:
  struct Rates {
    std::vector<double> dx, dv, drho, du, dS; // dx: the XSPH correction (empty when off)
    DamageRates damage;                       // Grady–Kipp (empty when no particle has flaws)
  };
  // Switches the materials to the late-stage equations of state and scales each particle's
  // deviatoric stress, then recomputes the current state's rates.
  void enterLateStage();
  // To the late-stage law of sound speed c; returns each material's G'/G.
  std::vector<double> switchMaterials(double c);
  // switchMaterials(c) with the state carried over (the lithostatic pressure kept, the
  // deviatoric stress scaled), then the state's pressures and rates (k1_); returns
  // computeRates' largest signal speed.
  double switchState(double c);
  // After a step in the late stage: the next stage of a falling sound speed, when it is due
  // (sph/LateStageSchedule.h).
  void followSchedule();
  // Positions into the periodic box, h from ρ, ρ by summation when asked, then pressure and
  // sound speed into p and c and the yield limit on the deviatoric stress.
  // With `need`, the walls' pressure only where need[i] != 0 (block steps).
  void settle(SphState& s, std::vector<double>& p, std::vector<double>& c,
              const std::vector<char>* need = nullptr) const;
  // With `withH`, each particle's h from its density first, in the same pass.
  void eosAndYield(SphState& s, std::vector<double>& p, std::vector<double>& c, bool withH) const;
  void densityBySummation(SphState& s) const;
  double smoothingLength(const SphState& s, std::size_t i) const; // κ (m/ρ)^{1/3}, capped
  // Rates of s (only of the particles in `active` when given; the others' entries are left as
  // they are); returns the largest signal speed over h/2.
  double computeRates(const SphState& s, const std::vector<double>& p, const std::vector<double>& c,
                      Rates& r, const std::vector<std::uint32_t>* active = nullptr) const;
  template <class K, bool Xsph> double rates(const SphState& s, const std::vector<double>& p,
                                             const std::vector<double>& c, Rates& r,
                                             const std::vector<std::uint32_t>* active) const;
  template <class K> void summation(SphState& s) const;
  // sph/HeunStep.cpp: the Euler predictor of a step of dt into mid_ (from s_ and k1_), and
  // Heun's corrector of s_ (from k1_ and the predictor's rates k2_).
  void predict(double dt);
  void correct(double dt);
  // sph/StepControl.cpp: the Courant and force limits, and the largest relative Euler–Heun
  // difference of a step of dt whose predictor's rates are k2 (worst: its particle).
  double limitStep(const SphState& s, const Rates& r, double maxSignal) const;
  double stepError(double dt, const Rates& k2, std::size_t& worst) const;
  double particleError(std::size_t i, double dt, const Rates& k2) const;
  double courantLimit(std::size_t i) const;
  double particleStep(std::size_t i) const; // its Courant and force limits
  // sph/BlockSteps.cpp. Each particle's state at its last update, when that was and when its
  // step ends (in ticks of the cycle, 2^(levels + kHeadroom) of them), its step's level (2^level
  // ticks), its next step at most (twice its last, less after a large error), the particles at
  // the end of their step and the limiter's work list.
  struct Block {
    std::vector<double> x, v, rho, u, S, damage;
    std::vector<std::uint64_t> t0, t1;
    std::vector<int> level;
    std::vector<double> cap, want;
    std::vector<std::uint32_t> active, queue;
    std::vector<char> need; // the active particles and their listed neighbours
    double tick = 0.0;
    std::uint64_t end = 0;
    BlockStats stats;
  };
  double blockCycle(double dt);
  void blockStart(double dt);
  void blockPredict(std::uint64_t t);
  double blockClose(std::uint64_t t); // returns the largest error of the updates
  int blockLevel(std::uint64_t t, double want) const;
  // The limiter's pass from the particles in `from` (nullptr: over all listed pairs).
  void blockLimit(std::uint64_t t, const std::vector<std::uint32_t>* from);
  double closeParticle(std::size_t i, double dt); // one particle's update; returns its error
  // The list entries the pair terms visit for a rigid particle: those of partners that are not
  // rigid at the same velocity (a pair of walls at rest adds only exact zeros). Follows the list.
  void filterRigidPairs(const SphState& s) const;
  void imageShift(std::uint32_t code, double d[3]) const;

  SphState s_;
  SphParams par_;
  NeighbourList nb_;
  GradyKippFracture fracture_;
  std::vector<double> hCapFactor_; // per material: κ (α0/ρ0)^{1/3} × the growth cap (0: none)
  std::vector<double> rhoFloor_;   // per material: the density floor, kg/m³ (0: none)
  std::vector<double> massCbrt_;   // m^{1/3} per particle (masses do not change)
  double floorOf(const SphState& s, std::size_t i) const {
    return rhoFloor_[static_cast<std::size_t>(s.material[i])];
  }
  Rates k1_;     // rates of the current state
  SphState mid_; // the predictor stage (members: reused, not reallocated, each step)
  Rates k2_;
  std::vector<double> pm_, cm_;
  std::vector<double> p_, c_;  // pressure and sound speed of the current state
  mutable WallBoundary walls_; // rigid particles' pressure (its cache follows the list)
  // Rigid particles' entries without their rigid partners at the same velocity (CSR over the
  // rigid particles in order; rigidSlot_ maps a particle to its row, or -1), for list version
  // rigidBuild_.
  mutable std::vector<std::uint32_t> rigidStart_, rigidEntry_;
  mutable std::vector<std::int32_t> rigidSlot_;
  mutable std::size_t rigidBuild_ = 0;
  mutable std::vector<double> signal_; // each particle's signal speed over h/2 (last rates)
  Block blk_;
  StepRecord record_;
  double time_ = 0.0, stableStep_ = 0.0;
  std::size_t steps_ = 0;
  bool late_ = false;
  double lateC_ = 0.0;      // the late-stage law's sound speed now (0: before the switch)
  double earlyAlpha_ = 0.0; // SphParams::alpha as given (the late stage scales it)
};

} // namespace craterkit

// The SPH solver for the shock and excavation stage (PHYSICS.md §2).
//
// Continuity (integrated or summation density), momentum with the full stress tensor and
// energy in the symmetric forms of §2.2; Monaghan artificial viscosity (§2.3) and optional XSPH;
// deviatoric stress from Hooke's law with the Jaumann rate; strength: von Mises for metals,
// Drucker–Prager matched to the Mohr–Coulomb compression cone for granular material (§2.5);
// P–α porosity with the quadratic crush curve (§2.6); Grady–Kipp fracture (§2.7: Weibull
// flaws, damage D growing as d(D^⅓)/dt = n_act c_g / R_s, weakening tension and shear); equations
// of state by material; smoothing length following the density (h = κ (m/ρ)^{1/3}, support h);
// periodic or open boundaries; uniform or point-mass gravity; Heun's predictor–corrector (RK2) with
// the Courant and force time steps and error control (a step whose Euler predictor and Heun
// corrector differ by more than a tolerance is taken again, shorter).
//
// Neighbours: a Verlet list built from cell lists, one grid per level of h (√2 apart, so a
// graded target's fine particles do not scan cells sized for its coarse ones), with a margin
// per particle (skin h, more for fast ones) for motion and for growth of h, kept over steps
// until some pair could have come into range unlisted. Periodic axes are handled by storing,
// with each neighbour, which image of it is near. OpenMP over particles; each particle sums only
// its own rates, so results are the same bits for any thread count.
#pragma once

#include "sph/Material.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace craterkit {

struct SphState {
  std::vector<double> x, v;            // 3 per particle
  std::vector<double> mass, rho, u, h; // kg, bulk density kg/m³, J/kg, m (support radius)
  std::vector<double> S;               // deviatoric stress, 6 per particle: xx yy zz xy xz yz (Pa)
  std::vector<double> alpha;           // distention ρ_matrix/ρ (1: no pores)
  std::vector<double> damage;          // D in [0, 1]
  std::vector<int> material;
  std::size_t size() const { return mass.size(); }
  // A particle at rest in stress, with no pores and no damage.
  void add(const double pos[3], const double vel[3], double m, double density, double energy,
           int mat);
};

struct SphParams {
  enum class Kernel { CubicSpline, WendlandC2 } kernel = Kernel::CubicSpline;
  std::vector<Material> materials; // indexed by SphState::material
  double alpha = 1.0, beta = 2.0;  // artificial viscosity
  double xsph = 0.0;               // XSPH ε (0: off)
  double kappa = 2.5;              // h = κ (m/ρ)^{1/3}
  // h grows at most to this multiple of its value at the material's reference bulk density
  // (ρ0/α0; solids only, 0: no cap). Without it a spray of expanding ejecta gets ever larger
  // h, which sizes the neighbour cells for everyone and forces a new list every step.
  double maxSmoothingGrowth = 2.0;
  // The integrated density of a particle whose material has a reference density (Tillotson,
  // Murnaghan, stiffened gas; not the ideal gas) is held at or above this fraction of the
  // material's reference bulk density ρ0/α0 (negative: 1/maxSmoothingGrowth³, where h stops
  // growing, at most 1/2; 0: no floor). A state that starts below it is raised to it at the
  // first step. Dilated material (a cohesionless bed torn apart, p = 0) otherwise keeps
  // losing density while it moves against its neighbours, without bound: its volume m/ρ then
  // dominates the neighbours' velocity gradients, and at last its density goes negative.
  double densityFloor = -1.0;
  double courant = 0.3;
  double forceFactor = 0.2;       // Δt ≤ forceFactor sqrt(h / |a|)
  std::uint64_t fractureSeed = 1; // random assignment of Grady–Kipp flaws to particles
  double skin =
      0.15; // each particle's neighbour-list margin, in units of its h (fast ones get more)
  bool rebuildEveryStep =
      false; // no list kept over steps (to check that keeping them changes nothing)
  double errorTolerance =
      0.02; // largest relative Euler–Heun difference of a step (else retaken shorter)
  double minTimeStep = 0.0;      // a step below this stops the run (0: only a non-positive step)
  bool summationDensity = false; // ρ = Σ m W (gases) instead of the integrated continuity equation
  double gravity[3] = {0, 0, 0}; // uniform, m/s²
  double pointMassGM = 0.0;      // m³/s², a point mass at pointMassAt (0: none)
  double pointMassAt[3] = {0, 0, 0};
  bool periodic[3] = {false, false, false};
  double boxLo[3] = {0, 0, 0}, boxHi[3] = {1, 1, 1}; // the periodic cell
  // Late-stage scheme (after Raducan & Jutzi 2022; PHYSICS.md §2.8): at lateStageTime (negative:
  // never) every Tillotson or Murnaghan material switches to the linear p = K (α ρ / ρ0 − 1) / α
  // with K = ρ0 c², c = lateStageSoundSpeed, keeping its Poisson ratio (so G falls by the same
  // factor, and each particle's deviatoric stress is scaled by it: the elastic strain is
  // unchanged); the distention is frozen. The Courant step grows by about the ratio of the old and
  // new sound speeds, so a run can follow the slow, gravity-driven crater growth after the shock.
  double lateStageTime = -1.0; // s
  // Particles farther than domainRadius from domainCentre (0: no limit) have left the SPH
  // domain: they get no neighbours and fly ballistically (under gravity) until they return,
  // so fast ejecta neither widen the neighbour lists nor force a new list every step.
  double domainRadius = 0.0; // m
  double domainCentre[3] = {0, 0, 0};
  double lateStageSoundSpeed = 100.0; // m/s
  void validate() const;
};

class SphSolver {
public:
  SphSolver(const SphState& initial, const SphParams& params);
  // One Heun step of at most dt (0: the stable step); returns the step taken, shorter than
  // asked when the error control needs it.
  double step(double dt = 0.0);
  void advanceTo(double t);
  double time() const { return time_; }
  // Sets the clock of a state restored from a snapshot or checkpoint.
  // A state at or after the late-stage time already has the late stage's stress.
  void restore(double time, std::size_t steps, double nextStep);
  bool lateStage() const { return late_; }
  std::size_t steps() const { return steps_; }
  std::size_t neighbourBuilds() const { return builds_; } // neighbour lists built so far
  // Particle a's listed neighbours (index * 32 + periodic image code) from the last list
  // build, sorted, and its margin in that build (tests check them against all pairs).
  std::vector<std::uint32_t> neighboursOf(std::size_t a) const;
  double neighbourMargin(std::size_t a) const { return nb_.margin[a]; }
  const SphState& state() const { return s_; }
  const SphParams& params() const { return par_; }
  const std::vector<double>& pressure() const { return p_; }
  const std::vector<double>& soundSpeed() const { return c_; }
  double stableStep() const { return stableStep_; }
  double kineticEnergy() const;
  double internalEnergy() const;
  double potentialEnergy() const; // in the uniform field and the point mass
  double totalEnergy() const { return kineticEnergy() + internalEnergy() + potentialEnergy(); }
  void totalMomentum(double p[3]) const;
  void totalAngularMomentum(double L[3]) const; // about the origin

private:
  struct Rates {
    std::vector<double> dx, dv, drho, du, dS; // dx: the XSPH correction (empty when off)
    std::vector<double> dDc, capD;            // d(D^⅓)/dt and the cap n_act/n_tot (fracture)
  };
  struct Neighbours {
    std::vector<std::uint32_t> start; // CSR offsets, size n+1
    std::vector<std::uint32_t> entry; // neighbour index * 32 + periodic image code
    std::vector<double> x, h;         // positions and smoothing lengths at the build
    std::vector<char> out;            // outside the domain at the build (no neighbours)
    std::vector<double>
        clearance; // > 0: no unlisted particle within twice the margin; this much to spare (m)
    std::vector<double>
        margin; // each particle's: a pair is listed within the larger of its two (m)
    std::vector<std::uint8_t> level; // each particle's level of h (0: the largest)
    std::size_t levels = 1;
    double grow = 1.0;
  };
  void assignFlaws();
  // Switches the materials to the late-stage equations of state (scaling each particle's
  // deviatoric stress when `scaleStress`), then recomputes the current state's rates.
  void enterLateStage(bool scaleStress);
  void integrateDamage(SphState& s, const SphState& from, double dt, const Rates& a,
                       const Rates* b) const;
  // Lists the pairs within grow max(h_a, h_b) plus the larger of their margins: each
  // particle's is skin h, or more for one that moves fast in steps of dt (none when !margins).
  void buildNeighbours(const SphState& s, double dt, bool margins = true);
  bool neighboursValid(const SphState& s, double dt) const; // for a step of dt
  // Positions into the periodic box, h from ρ, ρ by summation when asked, then pressure and
  // sound speed into p and c and the yield limit on the deviatoric stress.
  void settle(SphState& s, std::vector<double>& p, std::vector<double>& c) const;
  void eosAndYield(SphState& s, std::vector<double>& p, std::vector<double>& c) const;
  void densityBySummation(SphState& s) const;
  double smoothingLength(const SphState& s, std::size_t i) const; // κ (m/ρ)^{1/3}, capped
  bool outside(const SphState& s, std::size_t i) const;           // beyond domainRadius
  // Rates of s; returns the largest signal speed over h/2.
  double computeRates(const SphState& s, const std::vector<double>& p, const std::vector<double>& c,
                      Rates& r) const;
  template <class K, bool Xsph> double rates(const SphState& s, const std::vector<double>& p,
                                             const std::vector<double>& c, Rates& r) const;
  template <class K> void summation(SphState& s) const;
  double limitStep(const SphState& s, const Rates& r, double maxSignal) const;
  void imageShift(std::uint32_t code, double d[3]) const;

  SphState s_;
  SphParams par_;
  Neighbours nb_;
  std::vector<std::uint32_t>
      flawStart_; // Grady–Kipp activation strains per particle (CSR, ascending)
  std::vector<double> flawEps_;
  std::vector<double> hCapFactor_; // per material: κ (α0/ρ0)^{1/3} × the growth cap (0: none)
  std::vector<double> rhoFloor_;   // per material: the density floor, kg/m³ (0: none)
  double floorOf(const SphState& s, std::size_t i) const {
    return rhoFloor_[static_cast<std::size_t>(s.material[i])];
  }
  Rates k1_;     // rates of the current state
  SphState mid_; // the predictor stage (members: reused, not reallocated, each step)
  Rates k2_;
  std::vector<double> pm_, cm_;
  std::vector<double> p_, c_;           // pressure and sound speed of the current state
  mutable std::vector<double> nbMoved_; // neighboursValid's displacement bounds (reused)
  double time_ = 0.0, stableStep_ = 0.0;
  std::size_t steps_ = 0, builds_ = 0;
  bool late_ = false;
};

} // namespace craterkit

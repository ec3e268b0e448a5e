// Parameters of the SPH solver (docs/physics.md §2): kernel, materials, artificial viscosity
// (§2.3), XSPH, smoothing length, density floor, time-step control (§2.8), neighbour-list
// skin, gravity, periodic box, the late-stage scheme (§2.8) and the domain that ejecta leave.
#pragma once

#include "sph/Material.h"

#include <cstdint>
#include <vector>

namespace craterkit {

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
  // Late-stage scheme (after Raducan & Jutzi 2022; docs/physics.md §2.8): at lateStageTime
  // (negative: never) every Tillotson or Murnaghan material switches to the linear p = K (α ρ / ρ0
  // − 1) / α with K = ρ0 c², c = lateStageSoundSpeed, keeping its Poisson ratio (so G falls by the
  // same factor, and each particle's deviatoric stress is scaled by it: the elastic strain is
  // unchanged); the distention is frozen. The Courant step grows by about the ratio of the old and
  // new sound speeds, so a run can follow the slow, gravity-driven crater growth after the shock.
  double lateStageTime = -1.0; // s
  // At the switch, each particle of this material (-1: none; the impact set-up's impactor is 0)
  // is stopped in the flow of the other materials' particles within its support, momentum and
  // energy kept (sph/ImpactorStop.h).
  int lateStageStopMaterial = -1;
  // Particles farther than domainRadius from domainCentre (0: no limit) have left the SPH
  // domain: they get no neighbours and fly ballistically (under gravity) until they return,
  // so fast ejecta neither widen the neighbour lists nor force a new list every step.
  double domainRadius = 0.0; // m
  double domainCentre[3] = {0, 0, 0};
  double lateStageSoundSpeed = 100.0; // m/s
  // A late-stage sound speed that falls with the crater's flow (sph/LateStageSchedule.h): above
  // lateStageSoundSpeed, c starts at this value at the switch and falls as (t/lateStageTime)^(−q),
  // q = lateStageSoundSpeedExponent, in stages of 2^(1/4), down to lateStageSoundSpeed (0: one
  // switch, straight to lateStageSoundSpeed).
  double lateStageInitialSoundSpeed = 0.0; // m/s
  double lateStageSoundSpeedExponent = 0.6;
  // The Poisson ratio every material with strength takes at the switch, in [0, 0.5): G = 3 K
  // (1 - 2 nu) / (2 (1 + nu)) of the late-stage K. Negative: each keeps its own (the rule
  // above). A porous material whose shear modulus is the bulk's but whose K is the matrix's
  // (regolith.cfg: nu 0.4996) keeps almost none: G 0.44 Pa at c = 0.47 m/s, shear waves at
  // 2 cm/s, too soft for its yield stress to act on the late flow (docs/physics.md §2.8).
  double lateStagePoissonRatio = -1.0;
  // The target's weight through the switch (sph/Overburden.h): the bulk density ρ_o of the
  // overburden (0: none, the whole pressure falls with the bulk modulus) and the height of the
  // free surface along −gravity (the plane x·ĝ = −overburdenSurface, ĝ the unit gravity). Under
  // the surface the switch keeps the lithostatic pressure ρ_o |g| d and scales only the departure
  // from it. Uniform gravity only (the point mass is not counted).
  double overburdenDensity = 0.0; // kg/m³
  double overburdenSurface = 0.0; // m
  // The pressure, deviatoric stress and density of rigid particles: Extrapolated from the
  // adjacent material (Adami, Hu & Adams 2012; sph/WallBoundary.h), or Dynamic, from their own
  // continuity density (dynamic boundary particles, Crespo et al. 2007; the rule before
  // 2026-12-05), whose pressure falls to zero under a dilating layer and alternates from row to
  // row in a column at rest (docs/validation_history.md, "The infinite slope, analysed").
  enum class Walls { Extrapolated, Dynamic } walls = Walls::Extrapolated;
  // The artificial viscosity between a rigid particle and a non-rigid one, a factor on its
  // term (1: as between two material particles; 0, the default: none, as Adami et al.'s
  // free-slip wall; DualSPHysics's ViscoBoundFactor is such a factor). Monaghan's term acts
  // only on approaching pairs, so material sliding over the wall's particle lattice is pushed
  // away by the wall particles ahead of it and not held by those behind: a lift growing with the
  // slip speed, which lifted a granular layer sliding at 1–3 m/s off its floor and lowered the
  // floor's friction from 0.68 to 0.57 (docs/validation_history.md, "The infinite slope, analysed",
  // and sph/WallBoundary.h). The wall still holds the material by its extrapolated pressure
  // and its deviatoric stress. The impact set-up's container takes 1: it must absorb the shock
  // (sph/ImpactSetup.cpp).
  double wallViscosity = 0.0;
  // Individual time steps in the late stage (sph/BlockSteps.cpp, docs/physics.md §2.8): each
  // particle steps by its own power of two of the smallest step, up to 2^blockStepLevels of it,
  // and only particles at the end of their step have their rates evaluated (0, the default: one
  // step for all, Heun's scheme with error control). Needs the integrated density and no XSPH.
  int blockStepLevels = 0;
  void validate() const;
};

// The body force per unit mass at x: uniform gravity plus the point mass's attraction.
void bodyForce(const SphParams& par, const double* x, double g[3]);

} // namespace craterkit

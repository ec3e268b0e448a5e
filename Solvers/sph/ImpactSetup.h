// The SCI-like impact problem for the SPH solver: an impactor sphere striking a porous,
// granular target under surface gravity (issue: SPHImpact; docs/physics.md §2 and §4.1).
//
// Both bodies are cut from one cubic lattice of spacing dx = 2 a / ParticlesAcrossImpactor,
// so every particle has the volume dx³ (unless the target is graded, see `coarsening`);
// impactor particles share the impactor's mass exactly.
// The target (a hemisphere of radius R, or a half-space block of half-width R and depth R)
// has its surface at z = 0 with gravity along −z; the impactor touches the surface at the
// origin, moving at ImpactSpeed at ImpactAngle from the vertical in the x–z plane.
#pragma once

#include "common/NamedValue.h"
#include "sph/SphSolver.h"

#include <cstddef>
#include <string>
#include <vector>

namespace craterkit {

struct SphImpactSetup {
  std::string materialDirectory; // folder of *.cfg material files
  std::string impactorMaterial = "copper";
  double impactorMass = 2.0;   // kg
  double impactorRadius = 0.0; // m; 0: from the mass and the material's density
  double impactSpeed = 2000.0; // m/s
  double impactAngle = 0.0;    // degrees from the vertical, in [0, 90)
  std::string targetMaterial = "regolith";
  enum class Shape { HalfSpace, Hemisphere } targetShape = Shape::Hemisphere;
  double targetRadius = 0.4;      // m
  double targetPorosity = -1.0;   // in [0, 1); negative: the material's distention
  double frictionAngle = -1.0;    // degrees; negative: the material's
  double cohesion = -1.0;         // Pa; negative: the material's
  double surfaceGravity = 1.5e-4; // m/s², along −z (Ryugu, GM/R² with R = 448 m)
  int particlesAcrossImpactor = 4;
  // Hold the target in a rigid container of its own material, three spacings thick, around
  // its buried faces (as GranularBed's bowl holds the DEM bed). Its particles are material 2,
  // placed after the target's; they stand for the far field of a half-space, which takes up
  // the momentum of the waves that reach it instead of letting a free target drift away.
  bool container = false;
  // Graded resolution (hemispherical targets): 1 keeps the one lattice. Above 1, the lattice
  // spacing dx holds only within four impactor radii of the impact point; beyond, the target
  // is built of hemispherical shells whose spacing grows in proportion to the distance (the
  // same number of particles on every shell) up to this multiple of dx, with each particle's
  // mass set by its share of its shell's volume. Resolution goes where the shock and the
  // excavation flow start, for a fraction of the particles of a uniform lattice.
  double coarsening = 1.0;
  double memoryLimitFraction = 0.8; // refuse set-ups that need more of the machine's memory
  void validate() const;
};

// The impactor's index in SphImpactProblem::params.materials (the target's is 1, the
// container's 2): the material StopImpactorAtLateStage stops.
constexpr int kImpactorMaterial = 0;

struct SphImpactProblem {
  SphState state;
  SphParams params;                   // materials 0: impactor, 1: target; gravity set
  double spacing = 0.0;               // dx, m
  double impactorRadius = 0.0;        // m
  std::size_t impactorParticles = 0;  // the first ones in the state
  std::size_t containerParticles = 0; // the last ones in the state (material 2), if any
  double targetBulkDensity = 0.0;     // kg/m³
};

// Builds the particles; throws InputError naming the bad parameter before any work.
SphImpactProblem buildImpact(const SphImpactSetup& setup);

// The SPHImpact source's output time line: EndTime ≥ 0, OutputInterval > 0, MinTimeStep ≥ 0
// (InputError naming the property).
void checkImpactTimes(double endTime, double outputInterval, double minTimeStep);

// The run's clock, conserved totals and set-up, in the order the SPHImpact source writes them.
std::vector<NamedValue> impactFields(const SphSolver& solver, const SphImpactSetup& setup,
                                     double spacing, std::size_t containerParticles);

// One point array of the SPHImpact output: name, components per particle, values.
struct SphImpactArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};
// The output particles' arrays: the first `count` particles (the container's, the last ones,
// are left out), the deviatoric stress in the order XX YY ZZ XY YZ XZ of VTK's symmetric
// tensors (the solver stores XX YY ZZ XY XZ YZ).
std::vector<SphImpactArray> impactArrays(const SphSolver& solver, std::size_t count);

// Bytes the solver needs per particle (state, two stages, neighbour list), for memory checks.
std::size_t sphBytesPerParticle(double kappa);

} // namespace craterkit

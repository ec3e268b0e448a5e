// Setting up a DEM run (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012): the bed scan, the
// impactor, the container's walls, and the one choice of stiffness and time step.
//
// chooseStiffnessAndStep is the only place that picks k_N and the time step (Schwartz 2012
// Eqs. 4-5, 36-39; docs/physics.md §1.6): k_N is the larger of the stiffness that stops the
// fastest expected particle within the allowed overlap and the one that carries the
// lithostatic load; the step is the undamped collision time of two of the smallest
// particles over the steps per collision. The DEMIntegrator filter (through setUpDem), the
// bed settling, the heap test and the benchmark call it; the examples read its step from
// the DEMIntegrator's "TimeStep" field data.
#pragma once

#include "common/Container.h"
#include "common/Gravity.h"
#include "common/ParticleSet.h"
#include "dem/ContactModels.h"
#include "dem/DemSolver.h"
#include "dem/Impactor.h"
#include "dem/Walls.h"

#include <limits>
#include <string>
#include <vector>

namespace craterkit {

// The walls of a bed container: box = floor and four side planes; bowl = the hemispherical
// shell plus a cylinder of the same radius above its rim (so a bed filled above the rim is
// held), each acting in its own region (below and above the rim plane); both open at the top.
std::vector<Wall> containerWalls(const Container& container);

// Extent of a bed: lowest particle bottom, highest top, smallest radius and density
// (1e299 and -1e299 for no particles).
struct BedExtent {
  double bottom, top, smallestRadius, smallestDensity;
};
BedExtent scanBed(const ParticleSet& particles);

struct StiffnessInput {
  double smallestRadius;  // m
  double density;         // kg/m^3, of the smallest particles
  double maxSpeed;        // m/s, the fastest expected impact speed
  double overlapFraction; // allowed overlap / smallest radius
  double gravity;         // m/s^2 at the surface (0: none)
  double bedHeight;       // m
  double stepsPerCollision = 30.0;
  double normalStiffness = 0.0;      // given k_N, N/m; <= 0: chosen
  double tangentialStiffness = -1.0; // given k_T, N/m; < 0: 2/7 k_N (pkdgrav)
  double timeStep = 0.0;             // given, s; <= 0: from k_N
  // The normal law. Hertz: the step is the Hertz wall contact's duration at the larger of
  // maxSpeed and the speed of a fall through the bed's height (hertzCollisionTime), never
  // above the solver's stability time, over stepsPerCollision; k_N is not used by the law.
  bool hertz = false;
  double youngsModulus = 0.0; // Pa (Hertz)
  double poissonRatio = 0.0;  // (Hertz)
};

struct StiffnessChoice {
  double kN; // N/m
  // As ContactParams::kT: the given k_T, or negative for 2/7 k_N (resolved by
  // ContactParams::tangentialStiffness(), so that a checkpoint keeps the rule, not a value).
  double kT;
  double dt; // s
};
// Throws InputError if neither a speed nor gravity and a bed height are given (even with a
// given k_N: the proposal is always checked).
StiffnessChoice chooseStiffnessAndStep(const StiffnessInput& input);

// A DEM run as the DEMIntegrator proxy describes it.
struct DemSetup {
  ContactParams contact;        // all but kN; kT as StiffnessInput::tangentialStiffness
  double normalStiffness = 0.0; // N/m; <= 0: chosen
  double timeStep = 0.0;        // s; <= 0: chosen
  double stepsPerCollision = 30.0;
  double maxExpectedSpeed = 1.0; // m/s (the impactor's speed counts too)
  double maxOverlap = 0.01;      // allowed overlap / smallest radius; also the warning level
  Gravity gravity;
  bool addImpactor = false;
  ImpactorParams impactor; // its target height is surfaceHeight
  double surfaceHeight = std::numeric_limits<double>::quiet_NaN(); // NaN: the bed's top
  enum class Walls { None, Container, Cylinder };
  Walls walls = Walls::None;
  // Walls::Container: its walls; Walls::Cylinder: a cylinder of radius bowlRadius about the z
  // axis on a floor at z = -boxSize[2].
  Container container;
};

struct DemProblem {
  ParticleSet particles; // the bed and the impactor
  DemParams params;
};

// The walls of a container named "Box" or "Bowl" (Walls::Container, setup.container's type
// set); for any other name the cylinder if asked for, else none.
void chooseWalls(DemSetup& setup, const std::string& containerType, bool cylinder);

// Adds the impactor, builds the walls and chooses the stiffness and step. Throws InputError.
DemProblem setUpDem(const ParticleSet& bed, const DemSetup& setup);

} // namespace craterkit

#include "dem/DemSetup.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {
constexpr double kNone = 1.0e299; // the extent of no particles (VTK's largest double)
} // namespace

std::vector<Wall> containerWalls(const Container& c) {
  std::vector<Wall> walls;
  if (c.type == Container::Type::Box) {
    const double hx = 0.5 * c.boxSize[0], hy = 0.5 * c.boxSize[1];
    walls.push_back(Wall::plane({0, 0, -c.boxSize[2]}, {0, 0, 1}));
    walls.push_back(Wall::plane({-hx, 0, 0}, {1, 0, 0}));
    walls.push_back(Wall::plane({hx, 0, 0}, {-1, 0, 0}));
    walls.push_back(Wall::plane({0, -hy, 0}, {0, 1, 0}));
    walls.push_back(Wall::plane({0, hy, 0}, {0, -1, 0}));
  } else {
    walls.push_back(Wall::bowl({0, 0, 0}, c.bowlRadius));
    walls.push_back(Wall::cylinderAbove({0, 0, 0}, {0, 0, 1}, c.bowlRadius));
  }
  return walls;
}

BedExtent scanBed(const ParticleSet& s) {
  BedExtent e{kNone, -kNone, kNone, kNone};
  for (std::size_t i = 0; i < s.size(); ++i) {
    e.bottom = std::min(e.bottom, s.position[3 * i + 2] - s.radius[i]);
    e.top = std::max(e.top, s.position[3 * i + 2] + s.radius[i]);
    e.smallestRadius = std::min(e.smallestRadius, s.radius[i]);
    e.smallestDensity = std::min(e.smallestDensity, s.density[i]);
  }
  return e;
}

StiffnessChoice chooseStiffnessAndStep(const StiffnessInput& in) {
  const StiffnessProposal proposal =
      proposeStiffness(in.smallestRadius, in.density, in.maxSpeed, in.overlapFraction, in.gravity,
                       in.bedHeight, in.stepsPerCollision);
  StiffnessChoice c;
  c.kN = in.normalStiffness > 0.0 ? in.normalStiffness : proposal.kN;
  c.kT = in.tangentialStiffness;
  if (in.timeStep > 0.0) {
    c.dt = in.timeStep;
  } else {
    const double r = in.smallestRadius;
    const double mmin = in.density * 4.0 / 3.0 * M_PI * r * r * r;
    if (in.hertz) {
      const double E = in.youngsModulus / (1.0 - in.poissonRatio * in.poissonRatio);
      const double v = std::max(in.maxSpeed, std::sqrt(2.0 * in.gravity * in.bedHeight));
      const double t = std::min(hertzCollisionTime(mmin, r, E, v), hertzStabilityTime(mmin, r, E));
      c.dt = t / in.stepsPerCollision;
    } else {
      c.dt = pairCollisionTime(mmin, c.kN) / in.stepsPerCollision;
    }
  }
  return c;
}

namespace {
std::vector<Wall> wallsOf(const DemSetup& setup) {
  const Container& c = setup.container;
  switch (setup.walls) {
  case DemSetup::Walls::Container:
    return containerWalls(c);
  case DemSetup::Walls::Cylinder:
    return {Wall::cylinder({0, 0, 0}, {0, 0, 1}, c.bowlRadius),
            Wall::plane({0, 0, -c.boxSize[2]}, {0, 0, 1})};
  default:
    return {};
  }
}
} // namespace

DemProblem setUpDem(const ParticleSet& bed, const DemSetup& setup) {
  DemProblem out{bed, DemParams{}};
  const BedExtent bedExtent = scanBed(bed);
  double rmin = bedExtent.smallestRadius;
  double vmax = setup.maxExpectedSpeed;
  if (setup.addImpactor) {
    ImpactorParams imp = setup.impactor;
    imp.target[2] = std::isnan(setup.surfaceHeight) ? bedExtent.top : setup.surfaceHeight;
    addImpactor(out.particles, imp);
    vmax = std::max(vmax, imp.speed);
    rmin = std::min(rmin, imp.radius);
  }
  DemParams& p = out.params;
  p.contact = setup.contact;
  p.overlapWarning = setup.maxOverlap;
  p.gravity = setup.gravity;
  // The load at the bed's top on the axis, over the bed's height (at least one radius).
  const double surface[3] = {0.0, 0.0, bedExtent.top};
  const double height = std::max(bedExtent.top - bedExtent.bottom, rmin);
  StiffnessInput k{
      rmin,  bedExtent.smallestDensity, vmax, setup.maxOverlap, p.gravity.magnitudeAt(surface),
      height};
  k.stepsPerCollision = setup.stepsPerCollision;
  k.normalStiffness = setup.normalStiffness;
  k.tangentialStiffness = setup.contact.kT;
  k.timeStep = setup.timeStep;
  k.hertz = setup.contact.normalModel == "Hertz";
  k.youngsModulus = setup.contact.youngsModulus;
  k.poissonRatio = setup.contact.poissonRatio;
  const StiffnessChoice choice = chooseStiffnessAndStep(k);
  p.contact.kN = choice.kN;
  p.contact.kT = choice.kT;
  p.dt = choice.dt;
  p.walls = wallsOf(setup);
  return out;
}

void chooseWalls(DemSetup& setup, const std::string& type, bool cylinder) {
  if (type == "Box" || type == "Bowl") {
    setup.walls = DemSetup::Walls::Container;
    setup.container.type = type == "Box" ? Container::Type::Box : Container::Type::Bowl;
  } else if (cylinder)
    setup.walls = DemSetup::Walls::Cylinder;
}

} // namespace craterkit

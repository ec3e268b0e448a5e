#include "dem/ContactModels.h"

#include "common/Error.h"

#include <sstream>

namespace craterkit {

void ContactParams::validate() const {
  auto bad = [](const char* name, double v, const char* rule) {
    std::ostringstream msg;
    msg << name << " " << rule << " (got " << v << ")";
    throw InputError(msg.str());
  };
  if (normalModel != "LinearSpringDashpot" && normalModel != "Hertz")
    throw InputError("unknown normal contact law '" + normalModel +
                     "': use LinearSpringDashpot or Hertz");
  if (!(kN > 0.0) || !std::isfinite(kN))
    bad("NormalStiffness", kN, "must be positive and finite");
  if (!std::isfinite(kT) || kT == 0.0)
    bad("TangentialStiffness", kT, "must be positive, or negative for 2/7 of NormalStiffness");
  if (!(restitutionN > 0.0 && restitutionN <= 1.0))
    bad("NormalRestitution", restitutionN, "must be in (0, 1]");
  if (!(restitutionT > 0.0 && restitutionT <= 1.0))
    bad("TangentialRestitution", restitutionT, "must be in (0, 1]");
  if (!(muS >= 0.0) || !std::isfinite(muS))
    bad("StaticFriction", muS, "must be non-negative");
  if (!(muR >= 0.0) || !std::isfinite(muR))
    bad("RollingFriction", muR, "must be non-negative");
  if (!(muT >= 0.0) || !std::isfinite(muT))
    bad("TwistingFriction", muT, "must be non-negative");
  if (!(beta > 0.0) || !std::isfinite(beta))
    bad("ShapeParameter", beta, "must be positive");
  if (!(cohesion >= 0.0) || !std::isfinite(cohesion))
    bad("Cohesion", cohesion, "must be non-negative");
  if (normalModel == "Hertz") {
    if (!(youngsModulus > 0.0) || !std::isfinite(youngsModulus))
      bad("YoungsModulus", youngsModulus, "must be positive");
    if (!(poissonRatio > -1.0 && poissonRatio < 0.5))
      bad("PoissonRatio", poissonRatio, "must be in (-1, 0.5)");
  }
}

StiffnessProposal proposeStiffness(double rmin, double density, double vmax, double overlapFraction,
                                   double gravity, double bedHeight, double stepsPerCollision) {
  if (!(rmin > 0.0) || !(density > 0.0) || !(overlapFraction > 0.0) || !(stepsPerCollision > 0.0))
    throw InputError("proposeStiffness: radius, density, overlap and steps must be positive");
  const double m = density * 4.0 / 3.0 * M_PI * rmin * rmin * rmin;
  const double xmax = overlapFraction * rmin;
  const double kinetic = m * (vmax / xmax) * (vmax / xmax);
  // Lithostatic: k ≈ g ρ_bulk H s / (x/s) with ρ_bulk ≈ 0.65 ρ.
  const double stat = gravity * 0.65 * density * bedHeight * rmin / overlapFraction;
  StiffnessProposal p;
  p.kN = std::max(kinetic, stat);
  if (!(p.kN > 0.0))
    throw InputError("proposeStiffness: give a positive maximum speed or gravity and bed height");
  p.collisionTime = pairCollisionTime(m, p.kN);
  p.dt = p.collisionTime / stepsPerCollision;
  return p;
}

} // namespace craterkit

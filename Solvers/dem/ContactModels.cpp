#include "dem/ContactModels.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
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

namespace {
// One head-on collision of the clipped law in dimensionless units (m = 1, elastic force 1 at
// unit overlap, impact speed 1): ẍ = -g(x) - f sqrt(g'(x)) ẋ while that force is repulsive.
// RK4 with 20,000 steps per contact; the end is interpolated where the force or the overlap
// reaches zero. Returns the rebound speed.
double collide(NormalLawKind kind, double f, double* duration) {
  const bool hertz = kind == NormalLawKind::Hertz;
  auto force = [&](double x, double v) { // repulsive normal force, > 0 while in contact
    if (x < 0.0)
      return 0.0;
    const double elastic = hertz ? x * std::sqrt(x) : x;
    const double k = hertz ? 1.5 * std::sqrt(x) : 1.0; // d(elastic)/dx
    return elastic + f * std::sqrt(k) * v;
  };
  // The undamped contact lasts π (linear) or 3.22 (Hertz) units: steps of 1/8000 of that.
  const double h = (hertz ? 3.22 : M_PI) / 8000.0;
  double x = 0.0, v = 1.0, t = 0.0;
  for (long step = 0; step < 100000000; ++step) {
    auto acc = [&](double xx, double vv) { return -std::max(force(xx, vv), 0.0); };
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    const double fOld = force(x, v), fNew = xn > 0.0 ? force(xn, vn) : -1.0;
    if (step > 0 && (fNew <= 0.0 || xn <= 0.0)) {
      // Linear interpolation of the end inside the step.
      const double gOld = std::min(fOld, x), gNew = std::min(fNew, xn);
      const double s = gOld / (gOld - gNew);
      if (duration)
        *duration = t + s * h;
      return -(v + s * (vn - v));
    }
    x = xn, v = vn, t += h;
  }
  return 0.0;
}
} // namespace

double clippedRestitution(NormalLawKind kind, double factor, double* duration) {
  return collide(kind, factor, duration);
}

double clippedDampingFactor(NormalLawKind kind, double restitution) {
  if (restitution >= 1.0)
    return 0.0;
  double lo = 0.0, hi = 1.0;
  while (clippedRestitution(kind, hi) > restitution && hi < 1e6)
    hi *= 2.0;
  for (int i = 0; i < 60 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (clippedRestitution(kind, mid) > restitution ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
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

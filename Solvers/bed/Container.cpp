#include "Container.h"

#include "../common/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace craterkit {

std::string Container::typeName(Type t) { return t == Type::Box ? "Box" : "Bowl"; }

double Container::floorHeight() const { return type == Type::Box ? -boxSize[2] : -bowlRadius; }

void Container::validate(double r) const {
  auto fail = [](const std::string& what) { throw InputError(what); };
  if (!std::isfinite(surfaceHeight))
    fail("SurfaceHeight must be finite");
  std::ostringstream msg;
  if (type == Type::Box) {
    for (int k = 0; k < 3; ++k)
      if (!(boxSize[k] > 0.0) || !std::isfinite(boxSize[k]))
        fail("BoxSize must be three positive lengths (got a non-positive or non-finite entry)");
    if (boxSize[0] < 2 * r || boxSize[1] < 2 * r) {
      msg << "the box (" << boxSize[0] << " x " << boxSize[1]
          << " m) is narrower than one particle of radius " << r << " m";
      fail(msg.str());
    }
    if (surfaceHeight - floorHeight() < 2 * r) {
      msg << "the bed between the box floor (z = " << floorHeight() << " m) and SurfaceHeight ("
          << surfaceHeight << " m) is thinner than one particle of radius " << r << " m";
      fail(msg.str());
    }
  } else {
    if (!(bowlRadius > 0.0) || !std::isfinite(bowlRadius))
      fail("ContainerRadius must be positive and finite");
    if (surfaceHeight > 0.0) {
      msg << "SurfaceHeight (" << surfaceHeight
          << " m) is above the rim of the bowl (z = 0): the bowl is open at the top";
      fail(msg.str());
    }
    if (surfaceHeight - floorHeight() < 2 * r) {
      msg << "the bowl of radius " << bowlRadius << " m filled to SurfaceHeight " << surfaceHeight
          << " m cannot hold one particle of radius " << r << " m";
      fail(msg.str());
    }
  }
}

bool Container::inside(const double x[3], double margin) const {
  if (x[2] > surfaceHeight - margin)
    return false;
  if (type == Type::Box)
    return std::abs(x[0]) <= 0.5 * boxSize[0] - margin &&
           std::abs(x[1]) <= 0.5 * boxSize[1] - margin && x[2] >= -boxSize[2] + margin;
  const double rho = bowlRadius - margin;
  return rho >= 0.0 && x[0] * x[0] + x[1] * x[1] + x[2] * x[2] <= rho * rho;
}

void Container::project(double x[3], double r) const {
  const double top = surfaceHeight - r;
  if (type == Type::Box) {
    x[0] = std::clamp(x[0], -0.5 * boxSize[0] + r, 0.5 * boxSize[0] - r);
    x[1] = std::clamp(x[1], -0.5 * boxSize[1] + r, 0.5 * boxSize[1] - r);
    x[2] = std::clamp(x[2], -boxSize[2] + r, top);
    return;
  }
  // Ball of radius rho intersected with the half-space z <= top.
  const double rho = bowlRadius - r;
  const double d = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  if (d <= rho && x[2] <= top)
    return;
  if (d > rho) { // candidate: projection onto the ball
    const double s = rho / d;
    if (x[2] * s <= top) {
      for (int k = 0; k < 3; ++k)
        x[k] *= s;
      return;
    }
  }
  if (x[2] > top && x[0] * x[0] + x[1] * x[1] + top * top <= rho * rho) { // onto the plane
    x[2] = top;
    return;
  }
  // Otherwise the nearest point is on the circle where the plane cuts the sphere.
  const double ring = std::sqrt(std::max(0.0, rho * rho - top * top));
  const double h = std::hypot(x[0], x[1]);
  if (h > 0.0) {
    x[0] *= ring / h;
    x[1] *= ring / h;
  } else {
    x[0] = ring;
  }
  x[2] = top;
}

double Container::fillVolume(double margin) const {
  if (type == Type::Box) {
    double v = 1.0;
    v *= std::max(0.0, boxSize[0] - 2 * margin);
    v *= std::max(0.0, boxSize[1] - 2 * margin);
    return v * std::max(0.0, surfaceHeight + boxSize[2] - 2 * margin);
  }
  // Cap of height h = (surfaceHeight - margin) + rho at the bottom of a sphere of radius rho.
  const double rho = bowlRadius - margin;
  const double h = std::clamp(surfaceHeight - margin + rho, 0.0, 2.0 * std::max(rho, 0.0));
  return M_PI * h * h * (3.0 * rho - h) / 3.0;
}

void Container::bounds(double margin, double lo[3], double hi[3]) const {
  if (type == Type::Box) {
    lo[0] = -0.5 * boxSize[0] + margin;
    hi[0] = 0.5 * boxSize[0] - margin;
    lo[1] = -0.5 * boxSize[1] + margin;
    hi[1] = 0.5 * boxSize[1] - margin;
    lo[2] = -boxSize[2] + margin;
  } else {
    const double rho = bowlRadius - margin;
    lo[0] = lo[1] = -rho;
    hi[0] = hi[1] = rho;
    lo[2] = -rho;
  }
  hi[2] = surfaceHeight - margin;
}

} // namespace craterkit

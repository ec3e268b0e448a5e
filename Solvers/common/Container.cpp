#include "common/Container.h"

#include "common/Error.h"

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
  if (rho < 0.0)
    return false;
  // Above the rim (beds filled higher while settling) the wall continues as a cylinder.
  const double z2 = x[2] > 0.0 ? 0.0 : x[2] * x[2];
  return x[0] * x[0] + x[1] * x[1] + z2 <= rho * rho;
}

void Container::project(double x[3], double r) const {
  const double top = surfaceHeight - r;
  if (type == Type::Box) {
    x[0] = std::clamp(x[0], -0.5 * boxSize[0] + r, 0.5 * boxSize[0] - r);
    x[1] = std::clamp(x[1], -0.5 * boxSize[1] + r, 0.5 * boxSize[1] - r);
    x[2] = std::clamp(x[2], -boxSize[2] + r, top);
    return;
  }
  // C = ball of radius rho continued as a cylinder above z = 0, H = {z <= top}; both convex.
  // The projection onto C ∩ H is the projection onto C if that lies in H, else the
  // projection onto H if that lies in C, else the nearest point of the circle ∂C ∩ ∂H.
  const double rho = bowlRadius - r;
  if (inside(x, r))
    return;
  double c[3] = {x[0], x[1], x[2]};
  if (c[2] > 0.0) {
    const double h = std::hypot(c[0], c[1]);
    if (h > rho) {
      c[0] *= rho / h;
      c[1] *= rho / h;
    }
  } else {
    const double d = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (d > rho)
      for (int k = 0; k < 3; ++k)
        c[k] *= rho / d;
  }
  if (c[2] <= top) {
    std::copy(c, c + 3, x);
    return;
  }
  const double onPlane[3] = {x[0], x[1], top};
  if (inside(onPlane, r)) {
    x[2] = top;
    return;
  }
  const double ring = top > 0.0 ? rho : std::sqrt(std::max(0.0, rho * rho - top * top));
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
  // Cap of height h = (surfaceHeight - margin) + rho at the bottom of a sphere of radius rho,
  // plus the cylinder above the rim if the surface is above it.
  const double rho = std::max(bowlRadius - margin, 0.0);
  const double top = surfaceHeight - margin;
  const double h = std::clamp(top + rho, 0.0, rho);
  return M_PI * h * h * (3.0 * rho - h) / 3.0 + M_PI * rho * rho * std::max(top, 0.0);
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

#include "dem/Walls.h"

#include "common/Error.h"

#include <cmath>

namespace craterkit {

namespace {
std::array<double, 3> unit(std::array<double, 3> v, const char* what) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(len > 0.0) || !std::isfinite(len))
    throw InputError(std::string("wall ") + what + " must be a non-zero finite vector");
  return {v[0] / len, v[1] / len, v[2] / len};
}
} // namespace

std::string Wall::typeName(Type t) {
  switch (t) {
  case Type::Plane:
    return "Plane";
  case Type::Bowl:
    return "Bowl";
  case Type::Cylinder:
    return "Cylinder";
  case Type::CylinderAbove:
    return "CylinderAbove";
  default:
    return "Disk";
  }
}

namespace {
Wall makeWall(Wall::Type type, std::array<double, 3> point, std::array<double, 3> direction,
              double radius, const char* what) {
  Wall w;
  w.type = type;
  w.point = point;
  w.normal = unit(direction, what);
  w.radius = radius;
  w.validate();
  return w;
}
} // namespace

Wall Wall::plane(std::array<double, 3> p, std::array<double, 3> n) {
  return makeWall(Type::Plane, p, n, 0.0, "normal");
}

Wall Wall::bowl(std::array<double, 3> c, double r, std::array<double, 3> up) {
  return makeWall(Type::Bowl, c, up, r, "up direction");
}

Wall Wall::cylinder(std::array<double, 3> p, std::array<double, 3> axis, double r) {
  return makeWall(Type::Cylinder, p, axis, r, "axis");
}

Wall Wall::cylinderAbove(std::array<double, 3> p, std::array<double, 3> axis, double r) {
  return makeWall(Type::CylinderAbove, p, axis, r, "axis");
}

Wall Wall::disk(std::array<double, 3> c, std::array<double, 3> n, double r) {
  return makeWall(Type::Disk, c, n, r, "normal");
}

void Wall::validate() const {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(point[k]) || !std::isfinite(normal[k]))
      throw InputError("a " + typeName(type) + " wall has a non-finite point or direction");
  const double len2 = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
  if (std::abs(len2 - 1.0) > 1e-9)
    throw InputError("a " + typeName(type) + " wall direction must be a unit vector");
  if (type != Type::Plane && (!(radius > 0.0) || !std::isfinite(radius)))
    throw InputError("a " + typeName(type) + " wall needs a positive radius");
}

double Wall::overlap(const double x[3], double r, double n[3], double& lever) const {
  const double d[3] = {x[0] - point[0], x[1] - point[1], x[2] - point[2]};
  const double along = d[0] * normal[0] + d[1] * normal[1] + d[2] * normal[2];
  switch (type) {
  case Type::Plane:
    for (int k = 0; k < 3; ++k)
      n[k] = -normal[k];
    lever = along;
    return r - along;
  case Type::Disk: {
    // A thin disk: the contact is with its closest point (face or rim), so particles
    // sliding over the edge or hitting it from the side are handled smoothly.
    double q[3], radial2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      q[k] = d[k] - along * normal[k];
      radial2 += q[k] * q[k];
    }
    if (radial2 > radius * radius) {
      const double f = radius / std::sqrt(radial2);
      for (int k = 0; k < 3; ++k)
        q[k] *= f;
    }
    double dist2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      n[k] = q[k] - d[k];
      dist2 += n[k] * n[k];
    }
    const double dist = std::sqrt(dist2);
    if (!(dist < r) || dist == 0.0)
      return -1.0;
    for (int k = 0; k < 3; ++k)
      n[k] /= dist;
    lever = dist;
    return r - dist;
  }
  case Type::Bowl: {
    if (along > 0.0) // above the rim plane: the bowl is open
      return -1.0;
    const double dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (dist == 0.0)
      return r - radius;
    for (int k = 0; k < 3; ++k)
      n[k] = d[k] / dist;
    lever = radius - dist;
    return r - lever;
  }
  case Type::CylinderAbove:
    if (!(along > 0.0)) // at or below the rim plane the bowl holds the particle
      return -1.0;
    [[fallthrough]];
  case Type::Cylinder: {
    double rho[3];
    for (int k = 0; k < 3; ++k)
      rho[k] = d[k] - along * normal[k];
    const double dist = std::sqrt(rho[0] * rho[0] + rho[1] * rho[1] + rho[2] * rho[2]);
    if (dist == 0.0)
      return r - radius;
    for (int k = 0; k < 3; ++k)
      n[k] = rho[k] / dist;
    lever = radius - dist;
    return r - lever;
  }
  }
  return -1.0;
}

} // namespace craterkit

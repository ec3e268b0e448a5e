// Container walls for the DEM, after pkdgrav's wall types (docs/walls.tex): an infinite
// plane, a thin flat disk (contact with its closest point, face or rim),
// a hemispherical bowl (inside of the lower half of a sphere, open at the top), an infinite
// cylinder (inside), and the half of a cylinder on one side of its axis point (the wall above a
// bowl's rim: each region of a container has one wall, so no grain is pushed twice). A particle
// touching a wall feels the same contact law as a particle pair, with the wall as an immovable
// partner of infinite mass and radius.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace craterkit {

struct Wall {
  enum class Type { Plane = 0, Bowl = 1, Cylinder = 2, Disk = 3, CylinderAbove = 4 };
  Type type = Type::Plane;
  std::array<double, 3> point{0, 0, 0};  // plane: a point; disk, bowl: centre; cylinder: axis point
  std::array<double, 3> normal{0, 0, 1}; // plane, disk: unit normal into the domain; cylinder:
                                         // axis; bowl: "up", the bowl is the half below its centre
  double radius = 0.0;                   // disk, bowl and cylinder

  static Wall plane(std::array<double, 3> point, std::array<double, 3> normal);
  static Wall bowl(std::array<double, 3> centre, double radius,
                   std::array<double, 3> up = {0, 0, 1});
  static Wall cylinder(std::array<double, 3> axisPoint, std::array<double, 3> axis, double radius);
  // The cylinder where the particle's centre lies beyond axisPoint along axis (above a rim).
  static Wall cylinderAbove(std::array<double, 3> axisPoint, std::array<double, 3> axis,
                            double radius);
  static Wall disk(std::array<double, 3> centre, std::array<double, 3> normal, double radius);

  // Overlap of a sphere (centre x, radius r) with the wall; > 0 means contact. Also returns
  // the unit normal from the particle towards the wall and the distance from the centre to
  // the contact point.
  double overlap(const double x[3], double r, double n[3], double& lever) const;

  void validate() const; // throws InputError
  static std::string typeName(Type t);
};

} // namespace craterkit

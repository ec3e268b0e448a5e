// Containers that hold a granular bed: an open-topped box or a hemispherical bowl.
//
// Coordinates: z is up. The box spans x in [-L/2, L/2], y in [-W/2, W/2] with its floor
// at z = -D. The bowl is the lower half of a sphere of radius R centred at the origin
// (rim plane z = 0), as pkdgrav's shell wall with a 90 degree opening (walls.tex).
// In both the bed's free surface is the plane z = surfaceHeight.
#pragma once

#include <array>
#include <string>

namespace craterkit {

struct Container {
  enum class Type { Box = 0, Bowl = 1 };
  Type type = Type::Bowl;
  std::array<double, 3> boxSize{10.0, 10.0, 5.0}; // L, W, D, m
  double bowlRadius = 15.0;                       // m
  double surfaceHeight = 0.0;                     // m

  // Throws InputError if the container cannot hold a sphere of radius r below the surface.
  void validate(double largestRadius) const;

  // True if the point lies at least `margin` inside the walls and below the surface.
  bool inside(const double x[3], double margin) const;
  // Moves a sphere centre to the nearest point at which the sphere of radius r touches
  // neither wall nor surface (Euclidean projection onto a convex set).
  void project(double x[3], double r) const;

  // Volume of the container below the surface, shrunk by `margin` from walls and
  // surface, m^3.
  double fillVolume(double margin = 0.0) const;
  // Axis-aligned box around the region below the surface, shrunk by margin.
  void bounds(double margin, double lo[3], double hi[3]) const;
  // Height of the lowest point of the container.
  double floorHeight() const;

  static std::string typeName(Type t);
};

} // namespace craterkit

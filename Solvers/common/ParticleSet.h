// Particle state shared by the CraterKit solvers: structure of arrays, SI units.
//
// The layout mirrors the point data of ARCHITECTURE.md so that the VTK filters can copy
// each array in one pass. Vectors are stored as contiguous xyz triples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct ParticleSet {
  std::vector<double> position;        // 3 per particle, m
  std::vector<double> velocity;        // 3 per particle, m/s
  std::vector<double> angularVelocity; // 3 per particle, rad/s
  std::vector<double> radius;          // m
  std::vector<double> mass;            // kg
  std::vector<double> density;         // kg/m^3
  std::vector<int> material;           // index into the material table
  std::vector<std::int64_t> id;        // stable across time steps

  std::size_t size() const { return radius.size(); }

  void reserve(std::size_t n);
  // Appends a particle at rest.
  void add(const double x[3], double r, double rho, int mat, std::int64_t ident);
};

} // namespace craterkit

// Particle state shared by the CraterKit solvers: structure of arrays, SI units.
//
// The layout mirrors the point data of docs/architecture.md ("Data model") so that the VTK
// filters can copy each array in one pass. Vectors are stored as contiguous xyz triples.
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
  // Calls f(array, components) for every per-particle array, e.g. to permute or compact.
  template <class F> void forEachArray(F&& f) {
    f(position, 3);
    f(velocity, 3);
    f(angularVelocity, 3);
    f(radius, 1);
    f(mass, 1);
    f(density, 1);
    f(material, 1);
    f(id, 1);
  }
  // Appends a particle at rest.
  void add(const double x[3], double r, double rho, int mat, std::int64_t ident);
};

} // namespace craterkit

// The particle state of the SPH solver (docs/physics.md §2.2): positions, velocities, masses,
// bulk densities, specific internal energies, smoothing lengths (support radius), deviatoric
// stress, P–α distention (§2.6) and Grady–Kipp damage (§2.7) per particle, and the totals that
// the equations conserve (energy E = Σ m (½ v² + u) + potential, momentum, angular momentum).
#pragma once

#include <cstddef>
#include <vector>

namespace craterkit {

struct SphParams;

struct SphState {
  std::vector<double> x, v;            // 3 per particle
  std::vector<double> mass, rho, u, h; // kg, bulk density kg/m³, J/kg, m (support radius)
  std::vector<double> S;               // deviatoric stress, 6 per particle: xx yy zz xy xz yz (Pa)
  std::vector<double> alpha;           // distention ρ_matrix/ρ (1: no pores)
  std::vector<double> damage;          // D in [0, 1]
  std::vector<int> material;
  std::size_t size() const { return mass.size(); }
  // A particle at rest in stress, with no pores and no damage.
  void add(const double pos[3], const double vel[3], double m, double density, double energy,
           int mat);
};

// Throws InputError naming the first particle whose values are not a valid state for `par`
// (lengths, positive mass and density, known material, α ≥ 1, D in [0, 1], finite values,
// rigid particles at rest).
void checkState(const SphState& s, const SphParams& par);

double kineticEnergy(const SphState& s);
double internalEnergy(const SphState& s);
double potentialEnergy(const SphState& s, const SphParams& par); // uniform field and point mass
void totalMomentum(const SphState& s, double p[3]);
void totalAngularMomentum(const SphState& s, double L[3]); // about the origin

} // namespace craterkit

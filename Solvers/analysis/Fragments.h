// Fragments and debris clouds (issue: FragmentAnalysis; seed 003, Eq. 21 and Section 3.1).
//
// Fragments are the connected components of the particles linked by a contact: centres
// closer than (r_i + r_j)(1 + tolerance), or by an explicit bond list. Union-find over a cell
// list of cells of the mean diameter (O(N)), each contact found by the search of the larger of
// its two particles: one large body among small grains (an impactor) searches its own
// neighbourhood, and no other particle's search grows with it. Per fragment: count, mass,
// centre of mass and velocity (momentum over mass); summary: the fragmentation
// F = N_fragments / N_particles, the largest fragment's mass fraction, the cumulative mass
// distribution, and the debris cloud along an axis: the particles past `cloudStart` along it,
// their axial length L_a, radial extent L_r (twice the largest distance from the axis),
// R = L_a / L_r and the axial front speed (largest axial velocity).
#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace craterkit {

struct FragmentParams {
  double tolerance = 0.01; // contacts: d ≤ (r_i + r_j)(1 + tolerance)
  std::vector<std::pair<std::size_t, std::size_t>>
      bonds;                                   // if not empty: the links instead of contacts
  std::array<double, 3> axis{1.0, 0.0, 0.0};   // debris-cloud axis (impact direction)
  std::array<double, 3> origin{0.0, 0.0, 0.0}; // a point on the axis
  double cloudStart = -1e300; // cloud = particles with (x − origin)·axis > cloudStart
  void validate(std::size_t n) const;
};

struct Fragment {
  std::size_t count = 0;
  double mass = 0.0;
  std::array<double, 3> centre{}, velocity{};
};

struct FragmentResult {
  std::vector<long long> fragmentId; // per particle; fragments numbered by decreasing mass
  std::vector<Fragment> fragments;   // by decreasing mass
  double fragmentation = 0.0;        // F = N_fragments / N_particles
  double largestMassFraction = 0.0;
  std::vector<double>
      cumulativeMass; // fraction of the mass in fragments at least as heavy as fragment k
  std::size_t cloudParticles = 0;
  double axialLength = 0.0, radialExtent = 0.0, ratio = 0.0, frontSpeed = 0.0;
};

// Ejecta of a crater (docs/physics.md §4.3–4.4): particles above the original surface (centre
// higher than z0 + radius) moving upwards. Their ejection angle is measured from the horizontal
// between the upward speed and the speed away from the impact axis (a ballistic particle keeps
// it while gravity is slow to act, as in microgravity), mass-weighted on average; the Maxwell
// Z-model gives atan(Z − 2): 45° for Z = 3. Also the mass launched above each speed.
struct EjectaStatistics {
  std::size_t count = 0;
  double mass = 0.0;
  double meanAngle = 0.0;               // degrees, mass-weighted
  std::vector<double> speed, massAbove; // speeds in decreasing order; mass at or above each
};
EjectaStatistics ejectaStatistics(const std::vector<double>& positions,
                                  const std::vector<double>& radii,
                                  const std::vector<double>& masses,
                                  const std::vector<double>& velocities, double surfaceHeight,
                                  const double axis[2]);

FragmentResult analyseFragments(const std::vector<double>& positions,
                                const std::vector<double>& radii, const std::vector<double>& masses,
                                const std::vector<double>& velocities,
                                const FragmentParams& params);

} // namespace craterkit

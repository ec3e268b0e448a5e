// Fragments and debris cloud of a bonded-particle run, as measured by Watson & Steinhauser
// 2017 (Materials 10:379, seed 003, Sections 2.3.2, 3.1 and 3.3).
//
// A fragment is "an interconnected collection of simulation particles; the smallest fragment
// consists of a single particle" (Section 2.3.2): the connected components of the graph of
// intact bonds (union-find, contacts do not count). The debris cloud is the material past the
// plate's rear face along the impact axis, s = (x − origin)·axis > cloudStart. Then:
// - F = N_frag / N_part (Eq. 21): N_part the particles in the cloud, N_frag the distinct
//   fragments they belong to;
// - L_a, the cloud's axial length (max − min of s over the cloud), L_r its radial extent (twice
//   the largest distance from the axis), R = L_a / L_r (Section 3.1, Figure 6; 1.55 measured);
// - v_a, the axial expansion velocity of the cloud front (Section 3.1: the distance travelled
//   by the front between two snapshots over their interval; the front moves ballistically, so
//   this is the axial velocity of the foremost cloud particle), and v_a / v0.
#pragma once

#include "bonded/BondedBody.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct DebrisCloudParams {
  std::array<double, 3> axis{1.0, 0.0, 0.0};
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  double cloudStart = 0.0;  // the plate's rear face along the axis
  double impactSpeed = 0.0; // v0; 0 leaves v_a / v0 at 0
};

struct BondedFragmentResult {
  std::vector<std::uint32_t> fragmentId; // per particle; fragments numbered by decreasing size
  std::vector<std::size_t> fragmentSize; // particles per fragment, decreasing
  std::vector<double> fragmentMass;      // same order
  std::size_t cloudParticles = 0, cloudFragments = 0;
  double fragmentation = 0.0;                                // F of the cloud, Eq. 21
  double axialLength = 0.0, radialExtent = 0.0, ratio = 0.0; // L_a, L_r, R
  double axialVelocity = 0.0, axialVelocityRatio = 0.0;      // v_a, v_a / v0
};

// positions/velocities: 3n; bondBroken: per bond, non-zero when broken (may be empty: none).
BondedFragmentResult analyseBondedFragments(const std::vector<double>& positions,
                                            const std::vector<double>& velocities,
                                            const std::vector<double>& masses,
                                            const std::vector<BondedBond>& bonds,
                                            const std::vector<std::uint8_t>& bondBroken,
                                            const DebrisCloudParams& params);

} // namespace craterkit

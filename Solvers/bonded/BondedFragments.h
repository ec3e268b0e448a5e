// Fragments and debris cloud of a bonded-particle run, as measured by Watson & Steinhauser
// 2017 (Materials 10:379, seed 003, Sections 2.3.2, 3.1, 3.2.1 and 3.3).
//
// A fragment is "an interconnected collection of simulation particles; the smallest fragment
// consists of a single particle" (Section 2.3.2): the connected components of the graph of
// intact bonds (union-find, contacts do not count).
//
// The debris cloud C is the material that has left the plate: with s = (x − origin)·e the
// distance along the impact axis e and s_rear the plate's rear face (cloudStart), the
// particles with s > s_rear whose fragment has no particle at s ≤ s_rear (a petal or lip still
// bonded to the plate is not debris). Over C:
// - F = N_frag / N_part (Eq. 21): N_part the particles of C, N_frag the distinct fragments.
//
// The paper reads L_a, L_r and v_a off the experiment's photograph (Section 3.1, Figure 6):
// the visible outline of the bulk of the cloud, whose leading edge advances at constant speed
// between two photographs. Single particles hold too little mass to show on a photograph but
// set a max − min extent (at the headline case R ≈ 1.05 and v_a ≈ 1.2 v0 at f = 1 below). So the
// measures are mass quantiles. With m_i the masses, Q_w(q) the mass quantile of a quantity w
// over C (the smallest w_k such that the mass of the particles with w ≤ w_k is at least q M_C)
// and f = massFraction, q± = (1 ± f) / 2:
//   leading edge   s_f = Q_s(q+),   rear edge  s_b = Q_s(q−),   L_a = s_f − s_b;
//   L_r = Q_u(q+) − Q_u(q−), u the transverse coordinates (x − origin)·e1 and ·e2 of every
//         particle, each with mass m_i: the width of the cloud's silhouette seen from the side
//         (two perpendicular views pooled), as on the photograph;   R = L_a / L_r;
//   v_a = Q_{v·e}(q+), the axial velocity of the leading edge of the bulk; v_a / v0;
//   front width w_f = Q_s(0.99) − Q_s(0.90), the depth of the leading 10 % of the mass less its
//         last 1 %: a sharp front holds much mass in a thin layer (w_f / L_a small), a diffuse
//         one spreads it ahead of the bulk (independent of f).
// Both extents hold the same fraction f of the mass and both are side-view coordinates, so
// for any cloud whose density is a function of (s/a)² + (ρ/b)² (a filled or hollow spheroid
// of semi-axes a, b) R → a / b with many particles, whatever f: the coordinates s/a and u/b then
// share one distribution. For a ballistic cloud, x_i(t) = x_c + v_i (t − t_0), the order of the
// particles in s is their order in v·e, so s_f(t) = s_c + v_a (t − t_0): v_a is the distance
// the leading edge travels between two snapshots over their interval, the experiment's
// measure (Section 3.1), from one snapshot. f = 1 gives the envelope of every particle (the
// max − min measures; v_a that of the fastest particle).
//
// Default f = 0.95 (2.5 % of the cloud's mass trimmed at each end): the outline of a
// photograph, which leaves out the sparse spray holding a few per cent of the mass. A choice,
// not a fit: the simulated cloud is no spheroid and its R depends on f (headline case at 10⁴
// particles: 1.83, 1.61, 1.25 at f = 0.90, 0.95, 0.99; docs/proxies/BondedImpact.md).
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
  double cloudStart = 0.0;    // the plate's rear face along the axis
  double impactSpeed = 0.0;   // v0; 0 leaves v_a / v0 at 0
  double massFraction = 0.95; // f in (0, 1]: the cloud's mass inside the measured extents
};

struct BondedFragmentResult {
  std::vector<std::uint32_t> fragmentId; // per particle; fragments numbered by decreasing size
  std::vector<std::size_t> fragmentSize; // particles per fragment, decreasing
  std::vector<double> fragmentMass;      // same order
  std::size_t cloudParticles = 0, cloudFragments = 0;
  double cloudMass = 0.0, largestCloudFragmentMass = 0.0;
  double fragmentation = 0.0;                                // F of the cloud, Eq. 21
  double leadingEdge = 0.0, rearEdge = 0.0;                  // s_f, s_b along the axis
  double axialLength = 0.0, radialExtent = 0.0, ratio = 0.0; // L_a, L_r, R
  double axialVelocity = 0.0, axialVelocityRatio = 0.0;      // v_a, v_a / v0
  double frontWidth = 0.0;                                   // w_f = Q_s(0.99) − Q_s(0.90)
};

// positions/velocities: 3n; bondBroken: per bond, non-zero when broken (may be empty: none).
BondedFragmentResult analyseBondedFragments(const std::vector<double>& positions,
                                            const std::vector<double>& velocities,
                                            const std::vector<double>& masses,
                                            const std::vector<BondedBond>& bonds,
                                            const std::vector<std::uint8_t>& bondBroken,
                                            const DebrisCloudParams& params);

} // namespace craterkit

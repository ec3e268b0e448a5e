// The axisymmetric granular column collapse, the standard test of a DEM contact model's
// granular rheology (Lube, Huppert, Sparks & Hallworth 2004, J. Fluid Mech. 508:175;
// Lajeunesse, Mangeney-Castelnau & Vilotte 2004, Phys. Fluids 16:2371).
//
// A column of monodisperse spheres of radius r0 and height h0 (aspect ratio a = h0 / r0) is
// poured and settled inside a cylinder standing on a rough floor (a plane with the model's
// friction), the cylinder is lifted away at once, and the spreading deposit is run to rest.
// The runout (r_inf - r0) / r0 is compared with Lube et al.'s laboratory fits (their
// Eqs. 3.1-3.2): 1.24 a for a < 1.7 and 1.6 a^(1/2) above. r_inf is the radius of the deposit's
// edge as Lube et al. read it off their photographs: where the floor stops being covered.
// Azimuthally averaged, in rings one grain diameter wide, the fraction of the floor the grains
// cover seen from above (Σ π r_i² of the grains centred in a ring over the ring's area); the
// edge is the outermost radius where that cover falls through half that of a dense monolayer
// (π / (2 √3) / 2 = 0.453), interpolated linearly between ring centres. Grains that rolled away
// one by one cover little floor and do not set it. The radius holding 99 % of the grains
// (plus one grain radius) is reported beside it: it follows such stray grains.
#pragma once

#include "dem/ContactModels.h"

#include <cstddef>
#include <vector>

namespace craterkit {

struct ColumnCollapseResult {
  std::size_t particles = 0;
  double columnRadius = 0.0; // r0, m (inner radius of the cylinder)
  double columnHeight = 0.0; // h0, m: the settled column's top
  double aspectRatio = 0.0;  // a = h0 / r0 as settled
  double finalRadius = 0.0;  // r_inf, m: the continuous deposit's mean edge
  double radius99 = 0.0;     // m: the radius holding 99 % of the grains, plus a grain radius
  double finalHeight = 0.0;  // m, the deposit's top
  double runout = 0.0;       // (r_inf - r0) / r0
  double time = 0.0;         // s from the release until at rest
};

// Lube et al. 2004's fit of the normalised runout for aspect ratio a.
double lubeRunout(double aspectRatio);

// The radius where a deposit's cover of the floor around the z axis falls through half that
// of a dense monolayer (see above), in rings one mean grain diameter wide.
double depositEdgeRadius(const std::vector<double>& positions, const std::vector<double>& radii);

// contact: the model under test (k_N and Δt are chosen here); aspectRatio: h0 / r0 to aim
// for; radiusInGrains: r0 in grain radii (the column holds about 0.6 a (r0/r)^3 / (4/3)
// grains). Grains of radius 1 cm and 2500 kg/m^3 under g = 9.81 m/s^2.
ColumnCollapseResult runColumnCollapse(const ContactParams& contact, double aspectRatio,
                                       double radiusInGrains);

} // namespace craterkit

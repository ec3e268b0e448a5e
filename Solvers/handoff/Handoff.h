// The SPH → DEM hand-off of the hybrid method (docs/physics.md §3; issue: ImpactHandoff).
//
// 1. Split the SPH particles into compact material (|v| ≤ EjectaSpeedLimit) and ejecta.
// 2. Alpha shape (CGAL Fixed_alpha_shape_3; α is the squared radius in CGAL's convention,
//    the radius r_α here) of the compact particles; its boundary is returned as triangles.
// 3. Carve the settled bed: inside the region the SPH target occupied before the impact, a
//    bed particle is kept only if its centre lies inside the shape or within half a particle
//    spacing of a compact SPH particle (the volume an outer SPH particle stands for); the rest
//    is the cavity the SPH stage opened. Bed particles outside that region are kept as they are.
// 4. Map velocities onto the kept bed particles inside the region: a kernel-weighted linear
//    fit of the compact SPH velocities within one support radius (exact for rigid motions;
//    limited, as Barth & Jespersen limit a reconstruction, to the range of the neighbours'
//    velocities, so that a grain beyond one-sided neighbours gets no invented speed;
//    Shepard's average where the fit is ill-posed, the nearest SPH particle's where none is in
//    reach); spin ω = ½ ∇×v from the same fit. Then
//    correct so the mapped particles carry exactly the compact SPH material's linear and
//    angular momentum (about the origin): a uniform velocity shift, then a rigid rotation
//    about their centre of mass (which leaves the linear momentum unchanged).
// 5. Ejecta become DEM particles of equal mass and velocity (grain density of the bed), at
//    their SPH positions (or, grouped, one per cube of the bed's mean particle diameter, at the
//    group's centre of mass with its momentum and its angular momentum about that centre as
//    spin; a group lighter than half a mean bed grain then joins the nearest group within
//    groupReach cube edges that stays within two bed grains, so that a sparse curtain makes no
//    grains much smaller than the bed's, which would set the DEM's time step; a group still that
//    light, with none within reach to join, becomes no grain and its totals are reported:
//    sphLoneDropped), moved along their own velocity (which changes neither momentum nor
//    angular momentum) to the nearest place, forward first, where they overlap nothing by more
//    than 1 % of a radius and stay inside the container's walls; one with no such place keeps
//    its position with a smaller radius (same mass and momentum) that fits, if one does, and
//    otherwise takes the place of the bed particles it overlaps. The momentum correction of
//    step 4 is made after this, on the bed particles that remain. Compact material above the
//    surface (the curtain of a late hand-off) becomes particles the same way (curtainAsParticles),
//    and the mapped bed then carries the momentum of the compact material below it.
// 6. Ejecta and curtain whose ballistic flight (uniform gravity) comes down to the surface
//    level outside the container's footprint leave the simulated domain (landsInside): they
//    become no particles and their totals are reported (sphEscaped). They would land on ground
//    the bed does not hold, and only the fastest of them would set the DEM's stiffness.
#pragma once

#include "common/NamedValue.h"
#include "common/ParticleSet.h"

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace craterkit {

struct SphSnapshot {
  std::vector<double> x, v; // 3 per particle
  std::vector<double> mass; // kg
  std::vector<double> h;    // support radius, m (0: unknown)
  std::size_t size() const { return mass.size(); }
};

// The region the SPH target filled before the impact (surface z = surfaceHeight).
struct TargetRegion {
  enum class Shape { Hemisphere, HalfSpace, Everywhere } shape = Shape::Everywhere;
  double radius = 0.0; // hemisphere radius or half-width and depth of the block
  double surfaceHeight = 0.0;
  bool contains(const double x[3]) const;
};

struct HandoffParams {
  double ejectaSpeedLimit = 1.0; // m/s
  double alphaRadius = 0.0; // m; 0: 1.75 × the mean nearest-neighbour spacing of the compact set
  int minNeighbours = 1; // below this many SPH particles in the support: the nearest one's velocity
  double ejectaDensity = 0.0; // kg/m³ of ejecta grains; 0: the bed's mean grain density
  int ejectaMaterial = -1;    // -1: the bed's first particle's material
  bool groupEjecta =
      false; // one particle per cube of the bed's mean diameter instead of per SPH particle
  // Grouped: a cube's piece lighter than half a mean bed grain joins the nearest piece within
  // this many cube edges (0: never), so that a sparse curtain does not make small grains.
  double groupReach = 2.0;
  // Grouped: a piece still lighter than half a mean bed grain after that (none within reach to
  // join) becomes no particle; its totals are reported (sphLoneDropped). One such piece would
  // set the DEM's time step for the whole bed (a 1e5-grain SCI bed at Ryugu's gravity: a piece
  // of 1 % of a grain's mass, 4.5 times more steps). False: it stays as a small grain.
  bool dropLoneLightPieces = true;
  bool dropEjecta =
      false; // no particles for the ejecta (they escape): only their totals are reported
  // Compact SPH material above the target's surface (higher than one alpha radius over it: the
  // ejecta curtain of a late hand-off, slower than the limit) has no bed particle to lend its
  // momentum to: it becomes particles as the ejecta do (never dropped: it lands), and the
  // mapped bed carries the momentum of the rest. False: it is mapped with the rest.
  bool curtainAsParticles = true;
  // Where a sphere of radius r centred at x may be put (inside the container's walls); empty:
  // anywhere. Ejecta are moved along their velocity, forward first, then backward, to the
  // nearest place that is allowed and free.
  std::function<bool(const double* x, double r)> allowed;
  // Where ballistic material may come down (the container's footprint: x, y at the surface
  // level); empty: everywhere, nothing escapes. Flights use `gravity` (m/s², along −z); with
  // none, material moving up never comes down and escapes.
  std::function<bool(double x, double y)> landsInside;
  double gravity = 0.0;
  void validate() const;
};

struct HandoffTotals {
  double mass = 0.0;
  std::array<double, 3> momentum{}, angularMomentum{}; // angular about the origin, spin included
};

struct HandoffResult {
  ParticleSet particles;             // kept bed, then ejecta
  std::vector<int> origin;           // 0 bed, 1 ejecta
  std::vector<double> surfacePoints; // alpha-shape boundary: 3 per vertex
  std::vector<long long> triangles;  // 3 vertex indices per triangle, outward normals
  double alphaRadius = 0.0;
  std::size_t compactCount = 0, ejectaCount = 0, bedRemoved = 0, bedMapped = 0;
  std::size_t curtainCount = 0; // compact SPH particles above the surface (escaped ones included)
  std::size_t escapedCount = 0; // curtain and kept ejecta that land outside the container
  std::size_t loneDropped =
      0; // grouped pieces lighter than half a bed grain, none to join: no particle
  std::size_t ejectaShrunk = 0; // ejecta with no free place on their path, made smaller to fit
  std::size_t bedEvicted = 0;   // bed particles whose place an ejecta particle took
  HandoffTotals sphCompact, sphEjecta, demMapped, demEjecta,
      demBefore; // demBefore: mapped set before correction
  HandoffTotals
      sphCurtain; // the part of sphCompact above the surface (in demEjecta, not demMapped)
  HandoffTotals sphEscaped;     // curtain and kept ejecta landing outside (in neither)
  HandoffTotals sphLoneDropped; // lone light pieces (loneDropped): in none of the above
  double shapeVolume = 0.0;     // volume of the alpha shape's interior cells, m³
  std::vector<std::string> warnings;
  struct Timing {
    double split = 0, alphaShape = 0, carve = 0, map = 0, correct = 0, ejecta = 0;
  } seconds;
};

// Throws InputError naming the problem (empty compact set, bad parameters, empty shape, no
// overlap between the bed and the SPH target).
HandoffResult handoff(const SphSnapshot& sph, const ParticleSet& bed, const TargetRegion& region,
                      const HandoffParams& params);

HandoffTotals totalsOf(const ParticleSet& p, const std::vector<std::size_t>* subset = nullptr);

// The mapped bed's mass over the compact SPH mass it takes over (below the curtain); 0 if none.
double compactMassRatio(const HandoffResult& r);

// The figures a hand-off reports, named and ordered as ImpactHandoff's field data: each
// total's Mass, Momentum and AngularMomentum, the counts, and StepSeconds (split, alpha shape,
// carve, map, correct, ejecta).
std::vector<NamedValue> reportedFigures(const HandoffResult& r);

struct Container;
// Ejecta stay inside the bed's container (its walls go on above the surface: Container::inside);
// with dropLandingOutside, what comes down outside its footprint leaves the domain.
void confineToContainer(HandoffParams& params, const Container& container, bool dropLandingOutside);

} // namespace craterkit

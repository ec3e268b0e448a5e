// Crater profile and dimensions from particles (issue: CraterProfile; docs/physics.md §4).
//
// The surface is found in radial × azimuthal bins around the impact axis: in each bin the
// top of the highest particle that belongs to the bulk (at least `minNeighbours` other
// particles within `neighbourFactor` of its radius), so isolated ejecta above the surface do
// not count. The azimuthal average of the bins gives the profile h(r). From it, measured
// against the original surface z0:
//   - depth: z0 minus the lowest point of the profile (below the original surface);
//   - depth below the rim: the rim crest's height minus that lowest point (rim crest to floor,
//     the depth of remote-sensing crater catalogues);
//   - diameter: twice the radius where the profile first rises back to z0 from the centre;
//   - rim: the highest point of the profile between that radius and twice it (rim-to-rim
//     diameter, height), its radius the middle of the bins within a quarter particle diameter
//     of the highest; a rim height below that tolerance means no raised rim;
//   - excavated volume: ∫ 2π r max(0, z0 − h(r)) dr inside the diameter.
// The same measures are made for each side of the section through the axis (the azimuthal
// bins within 60° of −x and of +x), for the asymmetry. The deepest point is the lowest single
// (radial, azimuthal) bin's top inside the crater's edge, not averaged over azimuth: a central
// pit narrower than a ring of bins shows there first.
//
// Particles count as bulk by their own range (neighbourFactor times their radius), searched on
// cells sized by the mean radius: one large body among small grains (an impactor) widens only
// its own search, not every particle's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace craterkit {

struct CraterProfileParams {
  double axis[2] = {0.0, 0.0}; // impact axis (x, y)
  double surfaceHeight = 0.0;  // z0, the pre-impact surface
  double maxRadius = 0.0;      // m; 0: the particles' extent from the axis
  int radialBins = 0;          // 0: maxRadius over 2.5 mean particle diameters
  int azimuthalBins = 16;
  int minNeighbours = 3;        // a surface particle needs this many others ...
  double neighbourFactor = 3.0; // ... within this many of its radii
  double slabHalfWidth = 0.0;   // m, half-width of the cross-section slab; 0: two mean diameters
  void validate() const;
};

struct CraterMeasures {
  double depth = 0.0, diameter = 0.0, rimDiameter = 0.0, rimHeight = 0.0, volume = 0.0;
  double depthBelowRim = 0.0; // rim crest to the profile's lowest point
  bool found = false;         // false when the profile never dips below z0
};

struct CraterProfileResult {
  std::vector<double> radius, height; // the profile: bin centres and h(r) (NaN where empty)
  std::vector<int> binsUsed;          // azimuthal bins contributing to each radial bin
  CraterMeasures all, negativeHalf, positiveHalf; // whole profile, x < axis, x > axis
  // The lowest single bin's top inside the crater's edge: its depth below z0 and below the
  // rim crest of the whole profile (0 when no crater was found).
  double deepestDepth = 0.0, deepestDepthBelowRim = 0.0;
  std::vector<std::size_t> slab; // particles within slabHalfWidth of the x–z plane through the axis
  std::size_t surfaceParticles = 0, rejectedAsEjecta = 0;
};

// positions: 3 per particle; radii: per particle (DEM radius or SPH h/2).
CraterProfileResult craterProfile(const std::vector<double>& positions,
                                  const std::vector<double>& radii,
                                  const CraterProfileParams& params);

// The measures of one profile h(r) against z0 (exposed for tests); the rim is the middle of
// the bins within `tolerance` of the highest between the crater's edge and twice its radius.
CraterMeasures measureProfile(const std::vector<double>& radius, const std::vector<double>& height,
                              double z0, double tolerance = 0.0);

// A crater in a vertical 2D section (the hard-disk model's ground, docs/physics.md §4.3): the
// surface's top in bins of width `bin` along x (bin b centred at (b + 0.5) bin), measured
// against the original surface z0 around the impact point impactX:
//   - depth: z0 minus the lowest top (0 when no top is below z0);
//   - width: the run of bins around the impact point whose top is more than `drop` below z0
//     (0 when the impact point's bin is not).
struct SectionCrater {
  double depth = 0.0, width = 0.0;
};
SectionCrater measureSection(const std::vector<double>& top, double bin, double impactX, double z0,
                             double drop);

} // namespace craterkit

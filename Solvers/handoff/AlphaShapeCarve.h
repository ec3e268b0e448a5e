// Steps 2 and 3 of the SPH → DEM hand-off (docs/physics.md §3.2, §3.3 steps 3–4; Handoff.h): the
// alpha shape of the compact SPH material (Edelsbrunner & Mücke 1994; CGAL's
// Fixed_alpha_shape_3, whose α is the squared radius r_α²) and the carving of the settled bed
// with it. Inside the region the SPH target filled, a bed particle is kept only if its centre
// lies inside the shape or within half a particle spacing of a compact SPH particle (the volume
// an outer SPH particle stands for); the rest is the cavity the SPH stage opened.
// The only file that includes CGAL (compiled with -frounding-math, Solvers/CMakeLists.txt).
#pragma once

#include "handoff/Handoff.h"
#include "handoff/Split.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace craterkit {

struct Carving {
  std::vector<std::size_t> keep;   // bed indices kept, in bed order
  std::vector<std::size_t> mapped; // indices into keep: the kept particles inside the region
  std::size_t removed = 0;
};

class AlphaShapeCarve {
public:
  // The Delaunay triangulation of the compact particles and the alpha radius: `alphaRadius`,
  // or if 0 1.75 × their mean nearest-neighbour spacing (throws InputError if they are all at
  // one point).
  AlphaShapeCarve(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                  double alphaRadius);
  ~AlphaShapeCarve();
  double alphaRadius() const { return alphaRadius_; }

  // The alpha shape: the volume of its interior cells and its boundary triangles, oriented
  // outwards (3 coordinates per vertex, 3 vertex indices per triangle). Throws InputError if
  // the shape is empty.
  void buildShape(double& volume, std::vector<double>& surfacePoints,
                  std::vector<long long>& triangles);

  // The carving of the bed (after buildShape). Throws InputError if no bed particle lies in the
  // region.
  Carving carve(const ParticleSet& bed, const TargetRegion& region, const CompactCloud& cloud);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double alphaRadius_ = 0.0;
  std::size_t compactCount_ = 0;
};

// A warning when more than 1 % of the compact particles below the curtain lie more than one
// alpha radius outside the bed's extent (the bed should cover the SPH target); empty if not.
std::string coverageWarning(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                            const ParticleSet& bed, const CurtainTest& inCurtain,
                            double alphaRadius);

} // namespace craterkit

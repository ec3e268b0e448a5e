#include "handoff/AlphaShapeCarve.h"

#include "common/Error.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <utility>

namespace craterkit {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vbi = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
using Vb = CGAL::Fixed_alpha_shape_vertex_base_3<K, Vbi>;
using Cb = CGAL::Fixed_alpha_shape_cell_base_3<K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
using AlphaShape = CGAL::Fixed_alpha_shape_3<Delaunay>;
using Point = K::Point_3;
} // namespace

struct AlphaShapeCarve::Impl {
  template <class It> Impl(It first, It last) : dt(first, last) {}
  Delaunay dt;
  std::unique_ptr<AlphaShape> shape;
};

AlphaShapeCarve::AlphaShapeCarve(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                                 double alphaRadius)
    : compactCount_(compact.size()) {
  std::vector<std::pair<Point, std::size_t>> pts;
  pts.reserve(compact.size());
  for (std::size_t k = 0; k < compact.size(); ++k) {
    const std::size_t i = compact[k];
    pts.emplace_back(Point(sph.x[3 * i], sph.x[3 * i + 1], sph.x[3 * i + 2]), k);
  }
  impl_ = std::make_unique<Impl>(pts.begin(), pts.end());
  const Delaunay& dt = impl_->dt;
  if (alphaRadius == 0.0) {
    // Mean nearest-neighbour spacing: the nearest neighbour is always a Delaunay neighbour.
    std::vector<double> nearest(compact.size(), INFINITY);
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      const auto a = e->first->vertex(e->second), b = e->first->vertex(e->third);
      const double d = std::sqrt(CGAL::squared_distance(a->point(), b->point()));
      nearest[a->info()] = std::min(nearest[a->info()], d);
      nearest[b->info()] = std::min(nearest[b->info()], d);
    }
    double sum = 0.0;
    std::size_t count = 0;
    for (double d : nearest)
      if (std::isfinite(d))
        sum += d, ++count;
    if (count == 0 || !(sum > 0.0))
      throw InputError("ImpactHandoff: the compact SPH particles are all at one point");
    alphaRadius = 1.75 * sum / static_cast<double>(count);
  }
  alphaRadius_ = alphaRadius;
}

AlphaShapeCarve::~AlphaShapeCarve() = default;

void AlphaShapeCarve::buildShape(double& volume, std::vector<double>& surfacePoints,
                                 std::vector<long long>& triangles) {
  // CGAL's alpha is the squared radius.
  impl_->shape = std::make_unique<AlphaShape>(impl_->dt, alphaRadius_ * alphaRadius_);
  AlphaShape& shape = *impl_->shape;
  std::size_t interior = 0;
  for (auto c = shape.finite_cells_begin(); c != shape.finite_cells_end(); ++c)
    if (shape.classify(c) == AlphaShape::INTERIOR) {
      ++interior;
      const Point& a = c->vertex(0)->point();
      volume += std::abs(
          CGAL::volume(a, c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point()));
    }
  if (interior == 0)
    throw InputError(
        "ImpactHandoff: the alpha shape is empty: no tetrahedron of the " +
        std::to_string(compactCount_) +
        " compact SPH particles fits in a sphere of radius Alpha (" + std::to_string(alphaRadius_) +
        " m): Alpha is below the particle spacing, or the compact "
        "particles are too few and scattered (raise EjectaSpeedLimit or hand off earlier)");
  // Boundary triangles, oriented outwards (away from the interior cell).
  std::vector<AlphaShape::Facet> facets;
  shape.get_alpha_shape_facets(std::back_inserter(facets), AlphaShape::REGULAR);
  std::map<AlphaShape::Vertex_handle, long long> index;
  auto id = [&](AlphaShape::Vertex_handle v) {
    auto it = index.find(v);
    if (it != index.end())
      return it->second;
    const long long k = static_cast<long long>(index.size());
    index.emplace(v, k);
    surfacePoints.insert(surfacePoints.end(), {v->point().x(), v->point().y(), v->point().z()});
    return k;
  };
  for (AlphaShape::Facet f : facets) {
    if (shape.is_infinite(f.first) || shape.classify(f.first) != AlphaShape::INTERIOR)
      f = shape.mirror_facet(f);
    const auto c = f.first;
    const int i = f.second;
    AlphaShape::Vertex_handle v[3] = {c->vertex((i + 1) & 3), c->vertex((i + 2) & 3),
                                      c->vertex((i + 3) & 3)};
    const Point& opposite = c->vertex(i)->point();
    if (CGAL::orientation(v[0]->point(), v[1]->point(), v[2]->point(), opposite) == CGAL::POSITIVE)
      std::swap(v[1], v[2]); // the fourth vertex (inside) must be on the negative side
    for (auto& vh : v)
      triangles.push_back(id(vh));
  }
}

Carving AlphaShapeCarve::carve(const ParticleSet& bed, const TargetRegion& region,
                               const CompactCloud& cloud) {
  // A particle of the SPH lattice stands for the volume around it, so the material reaches half
  // a spacing beyond the shape through the outer particles: a bed particle within half a
  // spacing of a compact SPH particle is kept too.
  AlphaShape& shape = *impl_->shape;
  const std::vector<double>& cx = cloud.x;
  const double halfSpacing = 0.5 * alphaRadius_ / 1.75;
  auto nearCompact = [&](const double* x) {
    bool found = false;
    cloud.cells.forEachCandidate(x, halfSpacing, [&](std::size_t k) {
      const double d2 = (cx[3 * k] - x[0]) * (cx[3 * k] - x[0]) +
                        (cx[3 * k + 1] - x[1]) * (cx[3 * k + 1] - x[1]) +
                        (cx[3 * k + 2] - x[2]) * (cx[3 * k + 2] - x[2]);
      found = found || d2 < halfSpacing * halfSpacing;
    });
    return found;
  };
  Carving out;
  std::size_t inRegion = 0;
  AlphaShape::Cell_handle hint;
  for (std::size_t i = 0; i < bed.size(); ++i) {
    const double* x = &bed.position[3 * i];
    if (!region.contains(x)) {
      out.keep.push_back(i);
      continue;
    }
    ++inRegion;
    hint = shape.locate(Point(x[0], x[1], x[2]), hint);
    if ((!shape.is_infinite(hint) && shape.classify(hint) == AlphaShape::INTERIOR) ||
        nearCompact(x)) {
      out.mapped.push_back(out.keep.size());
      out.keep.push_back(i);
    } else {
      ++out.removed;
    }
  }
  if (inRegion == 0)
    throw InputError("ImpactHandoff: no bed particle lies in the region the SPH target occupied: "
                     "the bed and the SPH target do not overlap");
  return out;
}

std::string coverageWarning(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                            const ParticleSet& bed, const CurtainTest& inCurtain,
                            double alphaRadius) {
  // (the bed's extent counts its particles' radii: its surface is their tops, not centres)
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < bed.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], bed.position[3 * i + k] - bed.radius[i]);
      hi[k] = std::max(hi[k], bed.position[3 * i + k] + bed.radius[i]);
    }
  std::size_t outside = 0;
  for (std::size_t i : compact) {
    if (inCurtain(sph, i))
      continue; // the curtain becomes particles
    const double* x = &sph.x[3 * i];
    bool in = true;
    for (int k = 0; k < 3; ++k)
      in = in && x[k] >= lo[k] - alphaRadius && x[k] <= hi[k] + alphaRadius;
    outside += in ? 0 : 1;
  }
  if (outside <= compact.size() / 100)
    return {};
  return std::to_string(outside) + " of " + std::to_string(compact.size()) +
         " compact SPH particles lie outside the bed: the bed and the SPH target do not cover "
         "the same region";
}

} // namespace craterkit

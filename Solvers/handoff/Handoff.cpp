#include "handoff/Handoff.h"

#include "common/CellList.h"
#include "common/Error.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <queue>
#include <unordered_map>

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

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Cubic spline with support h (Kernels.h), as a weight.
double weight(double r, double h) {
  const double q = r / h;
  if (q >= 1.0)
    return 0.0;
  const double t = 1.0 - q;
  return q < 0.5 ? 6.0 * q * q * q - 6.0 * q * q + 1.0 : 2.0 * t * t * t;
}

Eigen::Vector3d vec(const std::vector<double>& a, std::size_t i) {
  return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}

// A hash key of integer cell coordinates (for sparse grids in unordered containers).
long long keyOf(long long a, long long b, long long c) {
  return (a * 73856093LL) ^ (b * 19349663LL) ^ (c * 83492791LL);
}

// The integer coordinates of the grid cell (cubes `cell` wide) that holds x.
void cellOf(const double* x, double cell, long long c[3]) {
  for (int a = 0; a < 3; ++a)
    c[a] = static_cast<long long>(std::floor(x[a] / cell));
}

double meanMass(const ParticleSet& p) {
  double m = 0.0;
  for (double mi : p.mass)
    m += mi;
  return p.size() ? m / static_cast<double>(p.size()) : 0.0;
}

// What becomes one ejecta particle: mass, centre of mass, velocity, and the angular momentum
// about its centre (its spin).
struct Piece {
  double m = 0.0, x[3] = {0, 0, 0}, v[3] = {0, 0, 0}, L[3] = {0, 0, 0};
};

// Merges piece b into a: mass and momentum add, the centre is the common centre of mass, and
// the angular momentum about it keeps the two pieces' motions relative to it, so mass, momentum
// and angular momentum about any point are unchanged.
void merge(Piece& a, const Piece& b) {
  const double m = a.m + b.m;
  Eigen::Vector3d X, V;
  for (int k = 0; k < 3; ++k) {
    X(k) = (a.m * a.x[k] + b.m * b.x[k]) / m;
    V(k) = (a.m * a.v[k] + b.m * b.v[k]) / m;
  }
  Eigen::Vector3d L(a.L[0] + b.L[0], a.L[1] + b.L[1], a.L[2] + b.L[2]);
  for (const Piece* q : {static_cast<const Piece*>(&a), &b}) {
    const Eigen::Vector3d r = Eigen::Vector3d(q->x[0], q->x[1], q->x[2]) - X;
    const Eigen::Vector3d u = Eigen::Vector3d(q->v[0], q->v[1], q->v[2]) - V;
    L += q->m * r.cross(u);
  }
  a.m = m;
  for (int k = 0; k < 3; ++k)
    a.x[k] = X(k), a.v[k] = V(k), a.L[k] = L(k);
}

// The grouped ejecta of a thin or sparse curtain fill their cubes only in part: a cube with one
// SPH particle would give a grain a fraction of the bed's size, and the smallest grain sets the
// DEM's time step. So each piece lighter than `light`, the lightest first, joins the nearest
// piece (centre to centre) within `reach` that stays at most `heavy` with it; a piece with none
// at its turn stays as it is, unless `dropLone`: a piece still lighter than `light` at the end
// (none within reach to join) is taken out and returned, so that it becomes no grain. The
// search runs on a grid of cells `reach` wide (a piece that moves, as merged centres do, is listed
// again in its new cell; the distance is always taken from where it is now), so it costs about the
// number of pieces times their neighbours.
std::vector<Piece> mergeLightPieces(std::vector<Piece>& pieces, double light, double heavy,
                                    double reach, bool dropLone) {
  std::vector<Piece> lone;
  if (!(light > 0.0) || !(reach > 0.0) || pieces.size() < 2)
    return lone;
  std::unordered_map<long long, std::vector<std::size_t>> grid;
  auto list = [&](std::size_t k) {
    long long c[3];
    cellOf(pieces[k].x, reach, c);
    grid[keyOf(c[0], c[1], c[2])].push_back(k);
  };
  std::vector<char> alive(pieces.size(), 1);
  using Entry = std::pair<double, std::size_t>; // mass, piece
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> lightest;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    list(k);
    if (pieces[k].m < light)
      lightest.push({pieces[k].m, k});
  }
  while (!lightest.empty()) {
    const auto [m, k] = lightest.top();
    lightest.pop();
    if (!alive[k] || m != pieces[k].m)
      continue; // merged away, or grown since
    // Nearest first, then the lower index: the same choice whatever the grid's order.
    std::size_t best = pieces.size();
    double bestD2 = reach * reach;
    long long c[3];
    cellOf(pieces[k].x, reach, c);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto cell = grid.find(keyOf(c[0] + dx, c[1] + dy, c[2] + dz));
          if (cell == grid.end())
            continue;
          for (std::size_t j : cell->second) {
            if (j == k || !alive[j] || pieces[j].m + m > heavy)
              continue;
            double d2 = 0.0;
            for (int a = 0; a < 3; ++a)
              d2 += (pieces[j].x[a] - pieces[k].x[a]) * (pieces[j].x[a] - pieces[k].x[a]);
            if (d2 < bestD2 || (d2 == bestD2 && j < best))
              bestD2 = d2, best = j;
          }
        }
    if (best == pieces.size())
      continue; // no piece within reach that can take it: it stays as light as it is
    long long before[3], after[3];
    cellOf(pieces[best].x, reach, before);
    merge(pieces[best], pieces[k]);
    alive[k] = 0;
    cellOf(pieces[best].x, reach, after);
    if (before[0] != after[0] || before[1] != after[1] || before[2] != after[2])
      list(best);
    if (pieces[best].m < light)
      lightest.push({pieces[best].m, best});
  }
  std::size_t w = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (!alive[k])
      continue;
    if (dropLone && pieces[k].m < light)
      lone.push_back(pieces[k]);
    else
      pieces[w++] = pieces[k];
  }
  pieces.resize(w);
  return lone;
}

HandoffTotals totalsOf(const std::vector<Piece>& pieces) {
  HandoffTotals t;
  for (const Piece& q : pieces) {
    t.mass += q.m;
    const Eigen::Vector3d x(q.x[0], q.x[1], q.x[2]),
        p = q.m * Eigen::Vector3d(q.v[0], q.v[1], q.v[2]);
    const Eigen::Vector3d l = x.cross(p) + Eigen::Vector3d(q.L[0], q.L[1], q.L[2]);
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += p(a), t.angularMomentum[a] += l(a);
  }
  return t;
}

} // namespace

bool TargetRegion::contains(const double x[3]) const {
  const double z = x[2] - surfaceHeight;
  switch (shape) {
  case Shape::Everywhere:
    return true;
  case Shape::Hemisphere:
    return z <= 0.0 && x[0] * x[0] + x[1] * x[1] + z * z <= radius * radius;
  case Shape::HalfSpace:
    return z <= 0.0 && z >= -radius && std::abs(x[0]) <= radius && std::abs(x[1]) <= radius;
  }
  return false;
}

void HandoffParams::validate() const {
  if (!(ejectaSpeedLimit > 0.0) || !std::isfinite(ejectaSpeedLimit))
    throw InputError("ImpactHandoff: EjectaSpeedLimit must be a positive speed in m/s");
  if (!(alphaRadius >= 0.0) || !std::isfinite(alphaRadius))
    throw InputError("ImpactHandoff: Alpha must not be negative (0: automatic)");
  if (minNeighbours < 1)
    throw InputError("ImpactHandoff: the neighbour count must be at least 1");
  if (!(ejectaDensity >= 0.0) || !std::isfinite(ejectaDensity))
    throw InputError("ImpactHandoff: the ejecta grain density must not be negative (0: the bed's)");
  if (!(gravity >= 0.0) || !std::isfinite(gravity))
    throw InputError(
        "ImpactHandoff: the gravity for ballistic landing must be finite and not negative");
  if (!(groupReach >= 0.0) || !std::isfinite(groupReach))
    throw InputError(
        "ImpactHandoff: the reach for merging light ejecta groups must not be negative");
}

HandoffTotals totalsOf(const ParticleSet& p, const std::vector<std::size_t>* subset) {
  HandoffTotals t;
  const std::size_t n = subset ? subset->size() : p.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = subset ? (*subset)[k] : k;
    const double m = p.mass[i];
    const double* x = &p.position[3 * i];
    const double* v = &p.velocity[3 * i];
    const double* w = &p.angularVelocity[3 * i];
    const double I = 0.4 * m * p.radius[i] * p.radius[i];
    t.mass += m;
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += m * v[a];
    t.angularMomentum[0] += m * (x[1] * v[2] - x[2] * v[1]) + I * w[0];
    t.angularMomentum[1] += m * (x[2] * v[0] - x[0] * v[2]) + I * w[1];
    t.angularMomentum[2] += m * (x[0] * v[1] - x[1] * v[0]) + I * w[2];
  }
  return t;
}

namespace {
HandoffTotals sphTotals(const SphSnapshot& s, const std::vector<std::size_t>& subset) {
  HandoffTotals t;
  for (std::size_t i : subset) {
    const double m = s.mass[i];
    const double* x = &s.x[3 * i];
    const double* v = &s.v[3 * i];
    t.mass += m;
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += m * v[a];
    t.angularMomentum[0] += m * (x[1] * v[2] - x[2] * v[1]);
    t.angularMomentum[1] += m * (x[2] * v[0] - x[0] * v[2]);
    t.angularMomentum[2] += m * (x[0] * v[1] - x[1] * v[0]);
  }
  return t;
}
} // namespace

HandoffResult handoff(const SphSnapshot& sph, const ParticleSet& bed, const TargetRegion& region,
                      const HandoffParams& params) {
  params.validate();
  HandoffResult out;
  const std::size_t ns = sph.size();
  if (ns == 0)
    throw InputError("ImpactHandoff: the SPH input has no particles");
  if (sph.x.size() != 3 * ns || sph.v.size() != 3 * ns)
    throw InputError(
        "ImpactHandoff: the SPH input needs positions, Velocity and Mass for every particle");
  if (bed.size() == 0)
    throw InputError("ImpactHandoff: the bed input has no particles");
  for (std::size_t i = 0; i < ns; ++i) {
    if (!(sph.mass[i] > 0.0) || !std::isfinite(sph.mass[i]))
      throw InputError("ImpactHandoff: SPH particle " + std::to_string(i) +
                       " has a non-positive Mass");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(sph.x[3 * i + k]) || !std::isfinite(sph.v[3 * i + k]))
        throw InputError("ImpactHandoff: SPH particle " + std::to_string(i) +
                         " has a non-finite position or Velocity");
  }

  // 1. Split.
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::size_t> compact, ejecta;
  for (std::size_t i = 0; i < ns; ++i) {
    const double v2 = sph.v[3 * i] * sph.v[3 * i] + sph.v[3 * i + 1] * sph.v[3 * i + 1] +
                      sph.v[3 * i + 2] * sph.v[3 * i + 2];
    (v2 > params.ejectaSpeedLimit * params.ejectaSpeedLimit ? ejecta : compact).push_back(i);
  }
  if (compact.size() < 4) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.3g", params.ejectaSpeedLimit);
    throw InputError(
        "ImpactHandoff: fewer than 4 SPH particles are slower than EjectaSpeedLimit (" +
        std::string(limit) + " m/s): no compact material to build a shape from");
  }
  out.compactCount = compact.size();
  out.ejectaCount = ejecta.size();
  out.sphCompact = sphTotals(sph, compact);
  out.sphEjecta = sphTotals(sph, ejecta);
  out.seconds.split = seconds(t0);

  // 2. Delaunay triangulation and alpha shape of the compact material.
  t0 = std::chrono::steady_clock::now();
  std::vector<std::pair<Point, std::size_t>> pts;
  pts.reserve(compact.size());
  for (std::size_t k = 0; k < compact.size(); ++k) {
    const std::size_t i = compact[k];
    pts.emplace_back(Point(sph.x[3 * i], sph.x[3 * i + 1], sph.x[3 * i + 2]), k);
  }
  Delaunay dt(pts.begin(), pts.end());
  double alphaRadius = params.alphaRadius;
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
  out.alphaRadius = alphaRadius;
  // The curtain: compact material higher than one alpha radius above the surface.
  auto inCurtain = [&](std::size_t i) {
    return params.curtainAsParticles && sph.x[3 * i + 2] > region.surfaceHeight + alphaRadius;
  };
  std::vector<std::size_t> curtain;
  for (std::size_t i : compact)
    if (inCurtain(i))
      curtain.push_back(i);
  out.curtainCount = curtain.size();
  out.sphCurtain = sphTotals(sph, curtain);
  AlphaShape shape(dt, alphaRadius * alphaRadius); // CGAL's alpha is the squared radius
  std::size_t interior = 0;
  for (auto c = shape.finite_cells_begin(); c != shape.finite_cells_end(); ++c)
    if (shape.classify(c) == AlphaShape::INTERIOR) {
      ++interior;
      const Point& a = c->vertex(0)->point();
      out.shapeVolume += std::abs(
          CGAL::volume(a, c->vertex(1)->point(), c->vertex(2)->point(), c->vertex(3)->point()));
    }
  if (interior == 0)
    throw InputError(
        "ImpactHandoff: the alpha shape is empty: no tetrahedron of the " +
        std::to_string(compact.size()) +
        " compact SPH particles fits in a sphere of radius Alpha (" + std::to_string(alphaRadius) +
        " m): Alpha is below the particle spacing, or the compact "
        "particles are too few and scattered (raise EjectaSpeedLimit or hand off earlier)");
  // Boundary triangles, oriented outwards (away from the interior cell).
  {
    std::vector<AlphaShape::Facet> facets;
    shape.get_alpha_shape_facets(std::back_inserter(facets), AlphaShape::REGULAR);
    std::map<AlphaShape::Vertex_handle, long long> index;
    auto id = [&](AlphaShape::Vertex_handle v) {
      auto it = index.find(v);
      if (it != index.end())
        return it->second;
      const long long k = static_cast<long long>(index.size());
      index.emplace(v, k);
      out.surfacePoints.insert(out.surfacePoints.end(),
                               {v->point().x(), v->point().y(), v->point().z()});
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
      if (CGAL::orientation(v[0]->point(), v[1]->point(), v[2]->point(), opposite) ==
          CGAL::POSITIVE)
        std::swap(v[1], v[2]); // the fourth vertex (inside) must be on the negative side
      for (auto& vh : v)
        out.triangles.push_back(id(vh));
    }
  }
  out.seconds.alphaShape = seconds(t0);

  // 3. Carve. A particle of the SPH lattice stands for the volume around it, so the material
  // reaches half a spacing beyond the shape through the outer particles: a bed particle
  // within half a spacing of a compact SPH particle is kept too.
  t0 = std::chrono::steady_clock::now();
  double hmax = 0.0;
  std::vector<double> hs(compact.size()), cx(3 * compact.size());
  for (std::size_t k = 0; k < compact.size(); ++k) {
    const std::size_t i = compact[k];
    hs[k] = i < sph.h.size() && sph.h[i] > 0.0 ? sph.h[i] : 2.0 * alphaRadius;
    hmax = std::max(hmax, hs[k]);
    for (int a = 0; a < 3; ++a)
      cx[3 * k + a] = sph.x[3 * i + a];
  }
  CellList cells;
  cells.build(cx.data(), compact.size(), hmax);
  const double halfSpacing = 0.5 * alphaRadius / 1.75;
  auto nearCompact = [&](const double* x) {
    bool found = false;
    cells.forEachCandidate(x, halfSpacing, [&](std::size_t k) {
      const double d2 = (cx[3 * k] - x[0]) * (cx[3 * k] - x[0]) +
                        (cx[3 * k + 1] - x[1]) * (cx[3 * k + 1] - x[1]) +
                        (cx[3 * k + 2] - x[2]) * (cx[3 * k + 2] - x[2]);
      found = found || d2 < halfSpacing * halfSpacing;
    });
    return found;
  };
  std::vector<std::size_t> keep, mapped;
  std::size_t inRegion = 0;
  AlphaShape::Cell_handle hint;
  for (std::size_t i = 0; i < bed.size(); ++i) {
    const double* x = &bed.position[3 * i];
    if (!region.contains(x)) {
      keep.push_back(i);
      continue;
    }
    ++inRegion;
    hint = shape.locate(Point(x[0], x[1], x[2]), hint);
    if ((!shape.is_infinite(hint) && shape.classify(hint) == AlphaShape::INTERIOR) ||
        nearCompact(x)) {
      mapped.push_back(keep.size());
      keep.push_back(i);
    } else {
      ++out.bedRemoved;
    }
  }
  if (inRegion == 0)
    throw InputError("ImpactHandoff: no bed particle lies in the region the SPH target occupied: "
                     "the bed and the "
                     "SPH target do not overlap");
  out.seconds.carve = seconds(t0);

  // The bed should cover the SPH target; say so when it does not.
  {
    // (the bed's extent counts its particles' radii: its surface is their tops, not centres)
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < bed.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], bed.position[3 * i + k] - bed.radius[i]);
        hi[k] = std::max(hi[k], bed.position[3 * i + k] + bed.radius[i]);
      }
    std::size_t outside = 0;
    for (std::size_t i : compact) {
      if (inCurtain(i))
        continue; // the curtain becomes particles
      const double* x = &sph.x[3 * i];
      bool in = true;
      for (int k = 0; k < 3; ++k)
        in = in && x[k] >= lo[k] - alphaRadius && x[k] <= hi[k] + alphaRadius;
      outside += in ? 0 : 1;
    }
    if (outside > compact.size() / 100)
      out.warnings.push_back(
          std::to_string(outside) + " of " + std::to_string(compact.size()) +
          " compact SPH particles lie outside the bed: the bed and the SPH target do not cover "
          "the same region");
  }

  ParticleSet& p = out.particles;
  p.reserve(keep.size() + ejecta.size());
  for (std::size_t i : keep) {
    p.position.insert(p.position.end(), &bed.position[3 * i], &bed.position[3 * i] + 3);
    p.velocity.insert(p.velocity.end(), &bed.velocity[3 * i], &bed.velocity[3 * i] + 3);
    p.angularVelocity.insert(p.angularVelocity.end(), &bed.angularVelocity[3 * i],
                             &bed.angularVelocity[3 * i] + 3);
    p.radius.push_back(bed.radius[i]);
    p.mass.push_back(bed.mass[i]);
    p.density.push_back(bed.density[i]);
    p.material.push_back(bed.material[i]);
    p.id.push_back(bed.id[i]);
  }
  out.origin.assign(keep.size(), 0);
  out.bedMapped = mapped.size();

  // 4. Map velocity and spin from the compact SPH particles: a weighted linear fit
  // v(x') ≈ v̄ + G (x' − x̄) over the SPH particles within one support radius (exact for
  // rigid motions), Shepard's average where the fit is ill-posed, the nearest particle where
  // none is in reach.
  t0 = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t q = 0; q < mapped.size(); ++q) {
    const std::size_t j = mapped[q];
    const Eigen::Vector3d x = vec(p.position, j);
    double wsum = 0.0;
    Eigen::Vector3d xbar = Eigen::Vector3d::Zero(), vbar = Eigen::Vector3d::Zero();
    std::vector<std::pair<std::size_t, double>> near;
    std::size_t nearest = 0;
    double best = INFINITY;
    cells.forEachCandidate(x.data(), hmax, [&](std::size_t k) {
      const Eigen::Vector3d d = vec(cx, k) - x;
      const double r = d.norm();
      if (r < best)
        best = r, nearest = k;
      const double w = weight(r, hs[k]) * sph.mass[compact[k]];
      if (w > 0.0)
        near.emplace_back(k, w);
    });
    Eigen::Vector3d v, omega = Eigen::Vector3d::Zero();
    if (static_cast<int>(near.size()) < params.minNeighbours || near.empty()) {
      if (!std::isfinite(best)) { // nothing within hmax: search everything (rare)
        for (std::size_t k = 0; k < compact.size(); ++k) {
          const double r = (vec(cx, k) - x).norm();
          if (r < best)
            best = r, nearest = k;
        }
      }
      v = vec(sph.v, compact[nearest]);
    } else {
      for (const auto& [k, w] : near) {
        wsum += w;
        xbar += w * vec(cx, k);
        vbar += w * vec(sph.v, compact[k]);
      }
      xbar /= wsum;
      vbar /= wsum;
      v = vbar;
      if (near.size() >= 4) {
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
        for (const auto& [k, w] : near) {
          const Eigen::Vector3d d = vec(cx, k) - xbar;
          A += w * d * d.transpose();
          B += w * (vec(sph.v, compact[k]) - vbar) * d.transpose();
        }
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
        const Eigen::Vector3d ev = eig.eigenvalues(); // ascending
        if (ev(0) > 1e-6 * ev(2)) { // the neighbours span 3D: the fit is well posed
          const Eigen::Matrix3d G = B * A.inverse();
          // Limited as Barth & Jespersen (1989) limit a reconstruction: no velocity component
          // beyond the range of the neighbours'. A linear field inside their hull is never
          // limited (rigid motions stay exact); an extrapolation past one-sided neighbours (a
          // grain at a cavity wall or in a thin sheet) would otherwise invent speeds many
          // times the fastest SPH particle's.
          Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
          for (const auto& nk : near) {
            lo = lo.cwiseMin(vec(sph.v, compact[nk.first]));
            hi = hi.cwiseMax(vec(sph.v, compact[nk.first]));
          }
          const Eigen::Vector3d dv = G * (x - xbar);
          double limit = 1.0;
          for (int a = 0; a < 3; ++a) {
            const double room = dv(a) > 0.0 ? hi(a) - vbar(a) : vbar(a) - lo(a);
            if (std::abs(dv(a)) > room)
              limit = std::min(limit, std::max(0.0, room) / std::abs(dv(a)));
          }
          v = vbar + limit * dv;
          omega = 0.5 * limit *
                  Eigen::Vector3d(G(2, 1) - G(1, 2), G(0, 2) - G(2, 0), G(1, 0) - G(0, 1));
        }
      }
    }
    for (int a = 0; a < 3; ++a) {
      p.velocity[3 * j + a] = v(a);
      p.angularVelocity[3 * j + a] = omega(a);
    }
  }
  out.seconds.map = seconds(t0);

  // 5. Ejecta as particles of equal mass and velocity, moved forward along their velocity
  // until they overlap nothing by more than 1 % of their radius.
  t0 = std::chrono::steady_clock::now();
  if (params.dropEjecta) // escaping: out.sphEjecta keeps what they carry away
    ejecta.clear();
  ejecta.insert(ejecta.end(), curtain.begin(), curtain.end()); // the curtain lands
  if (params.landsInside) {
    // Ballistic flight down to the surface level: z(t) = z + v_z t − g t²/2 = surfaceHeight.
    std::vector<std::size_t> staying, escaped;
    for (std::size_t i : ejecta) {
      const double* x = &sph.x[3 * i];
      const double* v = &sph.v[3 * i];
      const double up = std::max(0.0, x[2] - region.surfaceHeight), g = params.gravity;
      double t = INFINITY;
      if (g > 0.0)
        t = (v[2] + std::sqrt(v[2] * v[2] + 2.0 * g * up)) / g;
      else if (v[2] < 0.0)
        t = up / -v[2];
      const bool lands = std::isfinite(t) && params.landsInside(x[0] + v[0] * t, x[1] + v[1] * t);
      (lands ? staying : escaped).push_back(i);
    }
    ejecta.swap(staying);
    out.escapedCount = escaped.size();
    out.sphEscaped = sphTotals(sph, escaped);
  }
  double rhoGrain = params.ejectaDensity, rmax = 0.0;
  if (rhoGrain == 0.0) {
    double m = 0.0, vol = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i)
      m += bed.mass[i], vol += bed.mass[i] / bed.density[i];
    rhoGrain = m / vol;
  }
  const int ejectaMat = params.ejectaMaterial >= 0 ? params.ejectaMaterial : bed.material[0];
  std::int64_t nextId = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    nextId = std::max(nextId, p.id[i] + 1), rmax = std::max(rmax, p.radius[i]);
  // The pieces that become particles: each ejecta SPH particle, or (grouped) the ejecta in
  // each cube of the bed's mean particle diameter merged into one particle at their centre of
  // mass with their momentum and, as spin, their angular momentum about that centre, so that
  // mass, momentum and angular momentum are all kept.
  std::vector<Piece> pieces;
  if (params.groupEjecta && !ejecta.empty()) {
    double rb = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i)
      rb += bed.radius[i];
    const double edge = 2.0 * rb / static_cast<double>(bed.size());
    std::map<std::array<long long, 3>, std::vector<std::size_t>> groups;
    for (std::size_t i : ejecta) {
      std::array<long long, 3> c;
      for (int a = 0; a < 3; ++a)
        c[a] = static_cast<long long>(std::floor(sph.x[3 * i + a] / edge));
      groups[c].push_back(i);
    }
    for (const auto& [cellKey, members] : groups) {
      Piece q;
      for (std::size_t i : members) {
        q.m += sph.mass[i];
        for (int a = 0; a < 3; ++a)
          q.x[a] += sph.mass[i] * sph.x[3 * i + a], q.v[a] += sph.mass[i] * sph.v[3 * i + a];
      }
      for (int a = 0; a < 3; ++a)
        q.x[a] /= q.m, q.v[a] /= q.m;
      for (std::size_t i : members) {
        const Eigen::Vector3d r = vec(sph.x, i) - Eigen::Vector3d(q.x[0], q.x[1], q.x[2]);
        const Eigen::Vector3d u = vec(sph.v, i) - Eigen::Vector3d(q.v[0], q.v[1], q.v[2]);
        const Eigen::Vector3d l = sph.mass[i] * r.cross(u);
        for (int a = 0; a < 3; ++a)
          q.L[a] += l(a);
      }
      pieces.push_back(q);
    }
    const std::vector<Piece> lone =
        mergeLightPieces(pieces, 0.5 * meanMass(bed), 2.0 * meanMass(bed), params.groupReach * edge,
                         params.dropLoneLightPieces);
    out.loneDropped = lone.size();
    out.sphLoneDropped = totalsOf(lone);
  } else {
    for (std::size_t i : ejecta) {
      Piece q;
      q.m = sph.mass[i];
      for (int a = 0; a < 3; ++a)
        q.x[a] = sph.x[3 * i + a], q.v[a] = sph.v[3 * i + a];
      pieces.push_back(q);
    }
  }
  std::vector<double> er(pieces.size());
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    er[k] = std::cbrt(3.0 * pieces[k].m / (4.0 * M_PI * rhoGrain));
    rmax = std::max(rmax, er[k]);
  }
  const double cell = 2.0 * rmax;
  // Cells by integer coordinates: neighbours are found by offsetting the integers, never by
  // re-dividing shifted positions (which can round into the wrong cell).
  auto key = [&](const double* x) {
    long long c[3];
    cellOf(x, cell, c);
    return keyOf(c[0], c[1], c[2]);
  };
  std::unordered_multimap<long long, std::size_t> grid;
  grid.reserve(p.size() + pieces.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    grid.emplace(key(&p.position[3 * i]), i);
  // Calls f(iterator, j, distance) for every particle j in the 27 cells around x; f returns
  // the iterator to continue from (so that it may erase the entry).
  auto forNearby = [&](const double* x, auto&& f) {
    long long c[3];
    cellOf(x, cell, c);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = grid.equal_range(keyOf(c[0] + dx, c[1] + dy, c[2] + dz));
          for (auto it = range.first; it != range.second;) {
            const std::size_t j = it->second;
            const double d =
                std::sqrt((x[0] - p.position[3 * j]) * (x[0] - p.position[3 * j]) +
                          (x[1] - p.position[3 * j + 1]) * (x[1] - p.position[3 * j + 1]) +
                          (x[2] - p.position[3 * j + 2]) * (x[2] - p.position[3 * j + 2]));
            it = f(it, j, d);
          }
        }
  };
  auto worstOverlap = [&](const double* x, double r) {
    double worst = 0.0;
    forNearby(x, [&](auto it, std::size_t j, double d) {
      worst = std::max(worst, (r + p.radius[j] - d) / std::min(r, p.radius[j]));
      return std::next(it);
    });
    return worst;
  };
  std::size_t unresolved = 0;
  const std::size_t nBed = p.size();
  std::vector<char> gone(nBed, 0);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Piece& q = pieces[k];
    double x[3] = {q.x[0], q.x[1], q.x[2]};
    const double* v = q.v;
    const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    auto fits = [&](const double* y) {
      return worstOverlap(y, er[k]) <= 0.01 && (!params.allowed || params.allowed(y, er[k]));
    };
    // Along v (r × v, hence L, unchanged): forward first, then backward, in quarter radii.
    bool placed = fits(x);
    for (int dir = 1; dir >= -1 && !placed; dir -= 2)
      for (int step = 1; step <= 400 && !placed; ++step) {
        double y[3];
        for (int a = 0; a < 3; ++a)
          y[a] = x[a] + dir * step * 0.25 * er[k] * v[a] / speed;
        if (fits(y)) {
          std::copy(y, y + 3, x);
          placed = true;
        }
      }
    double radius = er[k];
    if (!placed) {
      // No free place along its path: keep it where it is, smaller (same mass and momentum,
      // denser) so that it fits among its neighbours, if that leaves it at least a fifth.
      double fit = radius;
      forNearby(x, [&](auto it, std::size_t j, double d) {
        fit = std::min(fit, d - p.radius[j]);
        return std::next(it);
      });
      if (fit >= 0.2 * radius && (!params.allowed || params.allowed(x, fit))) {
        radius = fit;
        ++out.ejectaShrunk;
      } else {
        // Fast SPH material sits where a bed particle is: the ejecta particle takes its place
        // (the bed particle leaves the mapped set before the momentum correction below).
        forNearby(x, [&](auto it, std::size_t j, double d) {
          if (j < nBed && (radius + p.radius[j] - d) / std::min(radius, p.radius[j]) > 0.01) {
            gone[j] = 1;
            ++out.bedEvicted;
            return grid.erase(it);
          }
          return std::next(it);
        });
        // Then, among the ejecta placed before it, as large as fits.
        double room = radius;
        forNearby(x, [&](auto it, std::size_t j, double d) {
          room = std::min(room, d - p.radius[j]);
          return std::next(it);
        });
        if (room < radius && room > 0.0) {
          radius = room;
          ++out.ejectaShrunk;
        }
        if (worstOverlap(x, radius) > 0.01)
          ++unresolved;
      }
    }
    p.position.insert(p.position.end(), x, x + 3);
    p.velocity.insert(p.velocity.end(), v, v + 3);
    const double inertia = 0.4 * q.m * radius * radius;
    p.angularVelocity.insert(p.angularVelocity.end(),
                             {q.L[0] / inertia, q.L[1] / inertia, q.L[2] / inertia});
    p.radius.push_back(radius);
    p.mass.push_back(q.m);
    p.density.push_back(q.m / (4.0 / 3.0 * M_PI * radius * radius * radius));
    p.material.push_back(ejectaMat);
    p.id.push_back(nextId++);
    out.origin.push_back(1);
    grid.emplace(key(x), p.size() - 1);
  }
  if (unresolved > 0)
    out.warnings.push_back(
        std::to_string(unresolved) +
        " ejecta particles still overlap a neighbour by more than 1 % of a radius");
  if (out.bedEvicted > 0) {
    std::vector<std::size_t> newIndex(p.size());
    std::size_t w = 0;
    for (std::size_t j = 0; j < p.size(); ++j) {
      newIndex[j] = w;
      if (j < nBed && gone[j])
        continue;
      p.forEachArray([&](auto& array, int comps) {
        for (int a = 0; a < comps; ++a)
          array[comps * w + a] = array[comps * j + a];
      });
      out.origin[w] = out.origin[j];
      ++w;
    }
    p.forEachArray([&](auto& array, int comps) { array.resize(comps * w); });
    out.origin.resize(w);
    std::vector<std::size_t> still;
    for (std::size_t j : mapped)
      if (!gone[j])
        still.push_back(newIndex[j]);
    mapped.swap(still);
    out.bedMapped = mapped.size();
  }
  std::vector<std::size_t> ej;
  for (std::size_t j = 0; j < p.size(); ++j)
    if (out.origin[j] == 1)
      ej.push_back(j);
  out.demEjecta = totalsOf(p, &ej);
  out.seconds.ejecta = seconds(t0);

  // Conservation: the mapped set carries the compact SPH material's momentum and angular
  // momentum exactly.
  t0 = std::chrono::steady_clock::now();
  out.demBefore = totalsOf(p, &mapped);
  HandoffTotals target =
      out.sphCompact; // what the mapped bed carries: the compact material below the curtain
  target.mass -= out.sphCurtain.mass;
  for (int a = 0; a < 3; ++a) {
    target.momentum[a] -= out.sphCurtain.momentum[a];
    target.angularMomentum[a] -= out.sphCurtain.angularMomentum[a];
  }
  if (!mapped.empty()) {
    const HandoffTotals before = out.demBefore;
    Eigen::Vector3d dV;
    for (int a = 0; a < 3; ++a)
      dV(a) = (target.momentum[a] - before.momentum[a]) / before.mass;
    for (std::size_t j : mapped)
      for (int a = 0; a < 3; ++a)
        p.velocity[3 * j + a] += dV(a);
    const HandoffTotals shifted = totalsOf(p, &mapped);
    Eigen::Vector3d cm = Eigen::Vector3d::Zero();
    for (std::size_t j : mapped)
      cm += p.mass[j] * vec(p.position, j);
    cm /= shifted.mass;
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    for (std::size_t j : mapped) {
      const Eigen::Vector3d r = vec(p.position, j) - cm;
      I += p.mass[j] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    Eigen::Vector3d dL;
    for (int a = 0; a < 3; ++a)
      dL(a) = target.angularMomentum[a] - shifted.angularMomentum[a];
    Eigen::FullPivLU<Eigen::Matrix3d> lu(I);
    if (lu.isInvertible()) {
      const Eigen::Vector3d dW = lu.solve(dL);
      for (std::size_t j : mapped) {
        const Eigen::Vector3d add = dW.cross(vec(p.position, j) - cm);
        for (int a = 0; a < 3; ++a)
          p.velocity[3 * j + a] += add(a);
      }
    } else {
      out.warnings.push_back(
          "the mapped bed particles are collinear: angular momentum could not be corrected");
    }
  } else {
    out.warnings.push_back(
        "no bed particle lies inside the alpha shape: the compact SPH material's momentum is lost");
  }
  out.demMapped = totalsOf(p, &mapped);
  out.seconds.correct = seconds(t0);

  return out;
}

} // namespace craterkit

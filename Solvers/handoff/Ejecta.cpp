#include "handoff/Ejecta.h"

#include "common/CellList.h"
#include "common/Container.h"
#include "common/SparseGrid.h"
#include "handoff/Split.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <string>
#include <utility>

namespace craterkit {

namespace {

Eigen::Vector3d vec(const std::vector<double>& a, std::size_t i) {
  return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
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
// search runs on a grid of cells `reach` wide (a piece that moves, as merged centres do, is
// listed again in its new cell; the distance is always taken from where it is now), so it costs
// about the number of pieces times their neighbours.
std::vector<Piece> mergeLightPieces(std::vector<Piece>& pieces, double light, double heavy,
                                    double reach, bool dropLone) {
  std::vector<Piece> lone;
  if (!(light > 0.0) || !(reach > 0.0) || pieces.size() < 2)
    return lone;
  SparseGrid grid(reach);
  std::vector<char> alive(pieces.size(), 1);
  using Entry = std::pair<double, std::size_t>; // mass, piece
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> lightest;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    grid.insert(pieces[k].x, k);
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
    grid.forEachNear(pieces[k].x, [&, m = m, k = k](std::size_t j) {
      if (j == k || !alive[j] || pieces[j].m + m > heavy)
        return false;
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a)
        d2 += (pieces[j].x[a] - pieces[k].x[a]) * (pieces[j].x[a] - pieces[k].x[a]);
      if (d2 < bestD2 || (d2 == bestD2 && j < best))
        bestD2 = d2, best = j;
      return false;
    });
    if (best == pieces.size())
      continue; // no piece within reach that can take it: it stays as light as it is
    const SparseGrid::Cell before = grid.cellOf(pieces[best].x);
    merge(pieces[best], pieces[k]);
    alive[k] = 0;
    if (grid.cellOf(pieces[best].x) != before)
      grid.insert(pieces[best].x, best);
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
    const Eigen::Vector3d x(q.x[0], q.x[1], q.x[2]);
    const Eigen::Vector3d p = q.m * Eigen::Vector3d(q.v[0], q.v[1], q.v[2]);
    const Eigen::Vector3d l = x.cross(p) + Eigen::Vector3d(q.L[0], q.L[1], q.L[2]);
    for (int a = 0; a < 3; ++a)
      t.momentum[a] += p(a), t.angularMomentum[a] += l(a);
  }
  return t;
}

// Keeps in `ejecta` what comes down inside the footprint (ballistic flight down to the surface
// level: z(t) = z + v_z t − g t²/2 = surfaceHeight); sets the escaped figures.
void dropLandingOutside(const SphSnapshot& sph, std::vector<std::size_t>& ejecta,
                        const TargetRegion& region, const HandoffParams& params,
                        HandoffResult& out) {
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

// The pieces that become particles: each ejecta SPH particle, or (grouped) the ejecta in each
// cube of the bed's mean particle diameter merged into one particle at their centre of mass
// with their momentum and, as spin, their angular momentum about that centre, so that mass,
// momentum and angular momentum are all kept.
std::vector<Piece> piecesOf(const SphSnapshot& sph, const std::vector<std::size_t>& ejecta,
                            const ParticleSet& bed, const HandoffParams& params,
                            HandoffResult& out) {
  std::vector<Piece> pieces;
  if (!params.groupEjecta || ejecta.empty()) {
    for (std::size_t i : ejecta) {
      Piece q;
      q.m = sph.mass[i];
      for (int a = 0; a < 3; ++a)
        q.x[a] = sph.x[3 * i + a], q.v[a] = sph.v[3 * i + a];
      pieces.push_back(q);
    }
    return pieces;
  }
  double rb = 0.0;
  for (std::size_t i = 0; i < bed.size(); ++i)
    rb += bed.radius[i];
  const double edge = 2.0 * rb / static_cast<double>(bed.size());
  SparseGrid groups(edge);
  for (std::size_t i : ejecta)
    groups.insert(&sph.x[3 * i], i);
  groups.forEachCellInOrder([&](const std::vector<std::size_t>& members) {
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
  });
  const std::vector<Piece> lone =
      mergeLightPieces(pieces, 0.5 * meanMass(bed), 2.0 * meanMass(bed), params.groupReach * edge,
                       params.dropLoneLightPieces);
  out.loneDropped = lone.size();
  out.sphLoneDropped = totalsOf(lone);
  return pieces;
}

double distance(const double* x, const double* y) {
  return std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                   (x[2] - y[2]) * (x[2] - y[2]));
}

// Places each piece (radius er) as the header says and appends it to out.particles; marks in
// `gone` the bed particles (the first nBed) whose place an ejecta particle took.
void place(const std::vector<Piece>& pieces, const std::vector<double>& er, double rmax,
           int material, const HandoffParams& params, std::vector<char>& gone, HandoffResult& out) {
  ParticleSet& p = out.particles;
  const std::size_t nBed = p.size();
  std::int64_t nextId = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    nextId = std::max(nextId, p.id[i] + 1);
  // Only the particles a sphere (x, r) overlaps decide where it goes (the worst overlap, the
  // room left and the evictions are a maximum, a minimum and a set), so the search needs to
  // find those, in any order. The cells fit the ordinary radii (common/CellList.h,
  // sizeClasses, over the bed's and the pieces' radii); the few larger particles are listed
  // on cells of their own (common/SparseGrid.h, SphereGrid).
  std::vector<double> radii(p.radius);
  radii.insert(radii.end(), er.begin(), er.end());
  const SizeClasses sizes = sizeClasses(radii.data(), radii.size());
  SphereGrid grid(sizes.large ? sizes.ordinaryMax : rmax, rmax);
  grid.reserve(p.size() + pieces.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    grid.insert(&p.position[3 * i], p.radius[i], i);
  // Calls f(j, distance) for every particle j that a sphere (x, r) overlaps, and for others
  // near it; f returns true to take j off the grid.
  auto forNearby = [&](const double* x, double r, auto&& f) {
    grid.forEachOverlapCandidate(
        x, r, [&](std::size_t j) { return f(j, distance(x, &p.position[3 * j])); });
  };
  auto worstOverlap = [&](const double* x, double r) {
    double worst = 0.0;
    forNearby(x, r, [&](std::size_t j, double d) {
      worst = std::max(worst, (r + p.radius[j] - d) / std::min(r, p.radius[j]));
      return false;
    });
    return worst;
  };
  auto room = [&](const double* x, double r) { // the largest radius up to r that touches none
    forNearby(x, r, [&](std::size_t j, double d) {
      r = std::min(r, d - p.radius[j]);
      return false;
    });
    return r;
  };
  std::size_t unresolved = 0;
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
      const double fit = room(x, radius);
      if (fit >= 0.2 * radius && (!params.allowed || params.allowed(x, fit))) {
        radius = fit;
        ++out.ejectaShrunk;
      } else {
        // Fast SPH material sits where a bed particle is: the ejecta particle takes its place
        // (the bed particle leaves the mapped set before the momentum correction).
        forNearby(x, radius, [&](std::size_t j, double d) {
          if (j < nBed && (radius + p.radius[j] - d) / std::min(radius, p.radius[j]) > 0.01) {
            gone[j] = 1;
            ++out.bedEvicted;
            return true;
          }
          return false;
        });
        // Then, among the ejecta placed before it, as large as fits.
        const double spare = room(x, radius);
        if (spare < radius && spare > 0.0) {
          radius = spare;
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
    p.material.push_back(material);
    p.id.push_back(nextId++);
    out.origin.push_back(1);
    grid.insert(x, radius, p.size() - 1);
  }
  if (unresolved > 0)
    out.warnings.push_back(std::to_string(unresolved) + " ejecta particles still overlap a "
                                                        "neighbour by more than 1 % of a radius");
}

// Takes the bed particles marked `gone` out of out.particles and renumbers `mapped`.
void removeEvicted(const std::vector<char>& gone, std::vector<std::size_t>& mapped,
                   HandoffResult& out) {
  ParticleSet& p = out.particles;
  const std::size_t nBed = gone.size();
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

} // namespace

void addEjecta(const SphSnapshot& sph, std::vector<std::size_t> ejecta,
               const std::vector<std::size_t>& curtain, const ParticleSet& bed,
               const TargetRegion& region, const HandoffParams& params,
               std::vector<std::size_t>& mapped, HandoffResult& out) {
  if (params.dropEjecta) // escaping: out.sphEjecta keeps what they carry away
    ejecta.clear();
  ejecta.insert(ejecta.end(), curtain.begin(), curtain.end()); // the curtain lands
  if (params.landsInside)
    dropLandingOutside(sph, ejecta, region, params, out);
  double rhoGrain = params.ejectaDensity, rmax = 0.0;
  if (rhoGrain == 0.0) {
    double m = 0.0, vol = 0.0;
    for (std::size_t i = 0; i < bed.size(); ++i)
      m += bed.mass[i], vol += bed.mass[i] / bed.density[i];
    rhoGrain = m / vol;
  }
  const int material = params.ejectaMaterial >= 0 ? params.ejectaMaterial : bed.material[0];
  const ParticleSet& p = out.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    rmax = std::max(rmax, p.radius[i]);
  const std::vector<Piece> pieces = piecesOf(sph, ejecta, bed, params, out);
  std::vector<double> er(pieces.size());
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    er[k] = std::cbrt(3.0 * pieces[k].m / (4.0 * M_PI * rhoGrain));
    rmax = std::max(rmax, er[k]);
  }
  std::vector<char> gone(p.size(), 0);
  place(pieces, er, rmax, material, params, gone, out);
  if (out.bedEvicted > 0)
    removeEvicted(gone, mapped, out);
  std::vector<std::size_t> ej;
  for (std::size_t j = 0; j < p.size(); ++j)
    if (out.origin[j] == 1)
      ej.push_back(j);
  out.demEjecta = totalsOf(p, &ej);
}

void confineToContainer(HandoffParams& params, const Container& container,
                        bool dropLandingOutside) {
  // The walls as ejecta meet them: without a lid (they go on above the bed's surface, the bowl
  // as the cylinder above its rim), as Container::inside tests a sphere against them.
  Container walls = container;
  walls.surfaceHeight = INFINITY;
  params.allowed = [walls](const double* x, double r) { return walls.inside(x, r); };
  if (dropLandingOutside) // the footprint: the points of the rim plane z = 0 inside the walls
    params.landsInside = [walls](double x, double y) {
      const double at[3] = {x, y, 0.0};
      return walls.inside(at, 0.0);
    };
}

} // namespace craterkit

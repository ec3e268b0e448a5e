#include "handoff/VelocityMap.h"

#include "sph/Kernels.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace craterkit {

namespace {

// The cubic spline with support h as a weight: its normalisation cancels in the fit.
double weight(double r, double h) {
  const double q = r / h;
  if (q >= 1.0)
    return 0.0;
  return cubicShape(q);
}

Eigen::Vector3d vec(const std::vector<double>& a, std::size_t i) {
  return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}

struct Fit {
  Eigen::Vector3d v, omega = Eigen::Vector3d::Zero();
};

// With wide particles (CompactCloud): the nearest of the particles in the cells of cloud.orderGrid
// that a search of reach hmax around x visits, the first of equals in that search's order (by
// cell, then by index), found on the ordinary cells; best stays infinite if those cells are
// empty. Without wide particles the map's own search visits exactly these.
template <class Distance> void nearestInOrderCells(const double* x, const CompactCloud& cloud,
                                                   Distance&& distance, double& best,
                                                   std::size_t& nearest) {
  std::uint64_t bestKey = 0;
  auto consider = [&](std::size_t k, double r) {
    const std::uint64_t key = cloud.orderKey[k];
    if (r < best || (r == best && (key < bestKey || (key == bestKey && k < nearest))))
      best = r, nearest = k, bestKey = key;
  };
  // Those cells hold every particle within hmax of x: if one is that close, the nearest of
  // them is the nearest of all, found by searching outwards on the ordinary cells.
  for (double reach = cloud.hOrdinary;; reach = std::min(2.0 * reach, cloud.hmax)) {
    cloud.cells.forEachCandidate(x, reach * (1.0 + 1e-9), [&](std::size_t k) {
      const double r = distance(k);
      if (r <= reach)
        consider(k, r);
    });
    if (std::isfinite(best) || reach >= cloud.hmax)
      break;
  }
  if (std::isfinite(best))
    return;
  // None that close: the nearest of the particles filed in those cells.
  const CellList::DenseGeometry& g = cloud.orderGrid;
  std::array<long, 3> lo{}, hi{};
  if (!g.visited(x, cloud.hmax, lo, hi))
    return;
  double centre[3], half = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double from = g.origin[a] + static_cast<double>(lo[a]) * g.cellSize;
    const double to = g.origin[a] + static_cast<double>(hi[a] + 1) * g.cellSize;
    centre[a] = 0.5 * (from + to);
    half = std::max(half, 0.5 * (to - from));
  }
  // (a margin of a millionth of a cell for the rounding of the division that files a point)
  cloud.cells.forEachCandidate(centre, half + 1e-6 * g.cellSize, [&](std::size_t k) {
    const std::uint64_t key = cloud.orderKey[k];
    const long c[3] = {static_cast<long>(key % g.dims[0]),
                       static_cast<long>(key / g.dims[0] % g.dims[1]),
                       static_cast<long>(key / g.dims[0] / g.dims[1])};
    for (int a = 0; a < 3; ++a)
      if (c[a] < lo[a] || c[a] > hi[a])
        return;
    consider(k, distance(k));
  });
}

// The velocity and spin at x from the compact particles around it.
Fit fitAt(const Eigen::Vector3d& x, const SphSnapshot& sph, const std::vector<std::size_t>& compact,
          const CompactCloud& cloud, int minNeighbours) {
  const std::vector<double>& cx = cloud.x;
  double wsum = 0.0;
  Eigen::Vector3d xbar = Eigen::Vector3d::Zero(), vbar = Eigen::Vector3d::Zero();
  std::vector<std::pair<std::size_t, double>> near;
  std::size_t nearest = 0;
  double best = INFINITY;
  auto distance = [&](std::size_t k) {
    const Eigen::Vector3d d = vec(cx, k) - x;
    return d.norm();
  };
  cloud.forEachCandidateSupport(x.data(), [&](std::size_t k) {
    const double r = distance(k);
    if (r < best)
      best = r, nearest = k;
    const double w = weight(r, cloud.h[k]) * sph.mass[compact[k]];
    if (w > 0.0)
      near.emplace_back(k, w);
  });
  const bool wide = !cloud.wide.empty();
  if (wide) // summed in the order of a search on cells hmax wide (CompactCloud)
    std::sort(near.begin(), near.end(), [&](const auto& a, const auto& b) {
      const std::uint64_t ka = cloud.orderKey[a.first], kb = cloud.orderKey[b.first];
      return ka != kb ? ka < kb : a.first < b.first;
    });
  Fit fit;
  if (static_cast<int>(near.size()) < minNeighbours || near.empty()) {
    if (wide) { // the nearest among the candidates of a search on cells hmax wide
      best = INFINITY;
      nearestInOrderCells(x.data(), cloud, distance, best, nearest);
    }
    if (!std::isfinite(best)) { // nothing within hmax: search everything (rare)
      for (std::size_t k = 0; k < compact.size(); ++k) {
        const double r = (vec(cx, k) - x).norm();
        if (r < best)
          best = r, nearest = k;
      }
    }
    fit.v = vec(sph.v, compact[nearest]);
    return fit;
  }
  for (const auto& [k, w] : near) {
    wsum += w;
    xbar += w * vec(cx, k);
    vbar += w * vec(sph.v, compact[k]);
  }
  xbar /= wsum;
  vbar /= wsum;
  fit.v = vbar;
  if (near.size() < 4)
    return fit;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
  for (const auto& [k, w] : near) {
    const Eigen::Vector3d d = vec(cx, k) - xbar;
    A += w * d * d.transpose();
    B += w * (vec(sph.v, compact[k]) - vbar) * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ev = eig.eigenvalues(); // ascending
  if (!(ev(0) > 1e-6 * ev(2)))
    return fit; // the neighbours do not span 3D: the fit is ill-posed
  const Eigen::Matrix3d G = B * A.inverse();
  // Limited as Barth & Jespersen (1989) limit a reconstruction: no velocity component beyond
  // the range of the neighbours'. A linear field inside their hull is never limited (rigid
  // motions stay exact); an extrapolation past one-sided neighbours (a grain at a cavity wall or
  // in a thin sheet) would otherwise invent speeds many times the fastest SPH particle's.
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
  fit.v = vbar + limit * dv;
  fit.omega =
      0.5 * limit * Eigen::Vector3d(G(2, 1) - G(1, 2), G(0, 2) - G(2, 0), G(1, 0) - G(0, 1));
  return fit;
}

} // namespace

void mapVelocities(const SphSnapshot& sph, const std::vector<std::size_t>& compact,
                   const CompactCloud& cloud, int minNeighbours,
                   const std::vector<std::size_t>& mapped, ParticleSet& p) {
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t q = 0; q < mapped.size(); ++q) {
    const std::size_t j = mapped[q];
    const Fit fit = fitAt(vec(p.position, j), sph, compact, cloud, minNeighbours);
    for (int a = 0; a < 3; ++a) {
      p.velocity[3 * j + a] = fit.v(a);
      p.angularVelocity[3 * j + a] = fit.omega(a);
    }
  }
}

} // namespace craterkit

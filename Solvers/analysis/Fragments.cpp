#include "analysis/Fragments.h"

#include "common/CellList.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace craterkit {

namespace {
struct UnionFind {
  std::vector<std::size_t> parent, size;
  explicit UnionFind(std::size_t n) : parent(n), size(n, 1) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  std::size_t find(std::size_t a) {
    while (parent[a] != a)
      a = parent[a] = parent[parent[a]]; // path halving
    return a;
  }
  void unite(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a == b)
      return;
    if (size[a] < size[b])
      std::swap(a, b);
    parent[b] = a, size[a] += size[b];
  }
};
} // namespace

void FragmentParams::validate(std::size_t n) const {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
    throw InputError("FragmentAnalysis: the contact tolerance must not be negative");
  const double len = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(len > 0.0) || !std::isfinite(len))
    throw InputError("FragmentAnalysis: the cloud axis must be a non-zero vector");
  for (const auto& [a, b] : bonds)
    if (a >= n || b >= n)
      throw InputError("FragmentAnalysis: a bond names particle " + std::to_string(std::max(a, b)) +
                       " of " + std::to_string(n));
}

FragmentResult analyseFragments(const std::vector<double>& x, const std::vector<double>& r,
                                const std::vector<double>& m, const std::vector<double>& v,
                                const FragmentParams& par) {
  const std::size_t n = r.size();
  if (n == 0)
    throw InputError("FragmentAnalysis: no particles");
  if (x.size() != 3 * n || m.size() != n || v.size() != 3 * n)
    throw InputError("FragmentAnalysis: positions, radii, masses and velocities differ in count");
  par.validate(n);
  double rmean = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(r[i] > 0.0) || !std::isfinite(r[i]) || !(m[i] > 0.0))
      throw InputError("FragmentAnalysis: particle " + std::to_string(i) +
                       " has a non-positive radius or mass");
    rmean += r[i];
  }
  rmean /= static_cast<double>(n);
  UnionFind uf(n);
  if (!par.bonds.empty()) {
    for (const auto& [a, b] : par.bonds)
      uf.unite(a, b);
  } else {
    // Each contact is found once, by the larger of its two particles (by radius, then by
    // index): a particle searches twice its own radius, on cells of the mean diameter, so one
    // large body scans its own neighbourhood and no other particle's search grows with it.
    // The fragments depend only on which pairs are linked, not on the order of the unions
    // (the numbering below goes by mass and smallest member).
    const double grow = 1.0 + par.tolerance;
    CellList cells;
    cells.build(x.data(), n, 2.0 * rmean * grow);
    for (std::size_t i = 0; i < n; ++i)
      cells.forEachCandidate(&x[3 * i], 2.0 * r[i] * grow * (1.0 + 1e-12), [&](std::size_t j) {
        if (r[j] > r[i] || (r[j] == r[i] && j <= i))
          return; // the pair is the larger one's (or i itself)
        const double d2 = (x[3 * i] - x[3 * j]) * (x[3 * i] - x[3 * j]) +
                          (x[3 * i + 1] - x[3 * j + 1]) * (x[3 * i + 1] - x[3 * j + 1]) +
                          (x[3 * i + 2] - x[3 * j + 2]) * (x[3 * i + 2] - x[3 * j + 2]);
        const double cut = (r[i] + r[j]) * grow;
        if (d2 <= cut * cut)
          uf.unite(i, j);
      });
  }
  // Fragments, then numbered by decreasing mass (ties: by smallest member index).
  std::vector<long long> root(n, -1);
  std::vector<Fragment> frags;
  std::vector<std::size_t> firstMember;
  FragmentResult out;
  out.fragmentId.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t rt = uf.find(i);
    if (root[rt] < 0) {
      root[rt] = static_cast<long long>(frags.size());
      frags.emplace_back();
      firstMember.push_back(i);
    }
    Fragment& f = frags[static_cast<std::size_t>(root[rt])];
    ++f.count;
    f.mass += m[i];
    for (int a = 0; a < 3; ++a)
      f.centre[a] += m[i] * x[3 * i + a], f.velocity[a] += m[i] * v[3 * i + a];
    out.fragmentId[i] = root[rt];
  }
  for (Fragment& f : frags)
    for (int a = 0; a < 3; ++a)
      f.centre[a] /= f.mass, f.velocity[a] /= f.mass;
  std::vector<std::size_t> order(frags.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return frags[a].mass != frags[b].mass ? frags[a].mass > frags[b].mass
                                          : firstMember[a] < firstMember[b];
  });
  std::vector<long long> rank(frags.size());
  double total = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    rank[order[k]] = static_cast<long long>(k);
    out.fragments.push_back(frags[order[k]]);
    total += frags[order[k]].mass;
  }
  for (long long& id : out.fragmentId)
    id = rank[static_cast<std::size_t>(id)];
  double cum = 0.0;
  for (const Fragment& f : out.fragments)
    out.cumulativeMass.push_back((cum += f.mass) / total);
  out.fragmentation = static_cast<double>(out.fragments.size()) / static_cast<double>(n);
  out.largestMassFraction = out.fragments.front().mass / total;

  // Debris cloud along the axis.
  const double len =
      std::sqrt(par.axis[0] * par.axis[0] + par.axis[1] * par.axis[1] + par.axis[2] * par.axis[2]);
  const double e[3] = {par.axis[0] / len, par.axis[1] / len, par.axis[2] / len};
  double lo = INFINITY, hi = -INFINITY, radial = 0.0, front = -INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    double d[3], s = 0.0, u = 0.0;
    for (int a = 0; a < 3; ++a)
      d[a] = x[3 * i + a] - par.origin[a], s += d[a] * e[a], u += v[3 * i + a] * e[a];
    if (!(s > par.cloudStart))
      continue;
    ++out.cloudParticles;
    lo = std::min(lo, s), hi = std::max(hi, s);
    const double p2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s * s;
    radial = std::max(radial, std::sqrt(std::max(0.0, p2)));
    front = std::max(front, u);
  }
  if (out.cloudParticles > 0) {
    out.axialLength = hi - lo;
    out.radialExtent = 2.0 * radial;
    out.ratio = out.radialExtent > 0.0 ? out.axialLength / out.radialExtent : 0.0;
    out.frontSpeed = front;
  }
  return out;
}

EjectaStatistics ejectaStatistics(const std::vector<double>& x, const std::vector<double>& r,
                                  const std::vector<double>& m, const std::vector<double>& v,
                                  double z0, const double axis[2]) {
  EjectaStatistics out;
  std::vector<std::pair<double, double>> bySpeed; // (speed, mass)
  double angleSum = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double* p = &x[3 * i];
    const double* u = &v[3 * i];
    if (!(p[2] > z0 + r[i]) || !(u[2] > 0.0))
      continue;
    const double dx = p[0] - axis[0], dy = p[1] - axis[1], rho = std::hypot(dx, dy);
    const double outward = rho > 0.0 ? (u[0] * dx + u[1] * dy) / rho : std::hypot(u[0], u[1]);
    const double angle = std::atan2(u[2], outward) * 180.0 / M_PI;
    ++out.count;
    out.mass += m[i];
    angleSum += m[i] * angle;
    bySpeed.emplace_back(std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), m[i]);
  }
  if (out.count == 0)
    return out;
  out.meanAngle = angleSum / out.mass;
  std::sort(bySpeed.begin(), bySpeed.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  double cum = 0.0;
  for (const auto& [s, mm] : bySpeed) {
    cum += mm;
    out.speed.push_back(s);
    out.massAbove.push_back(cum);
  }
  return out;
}

} // namespace craterkit

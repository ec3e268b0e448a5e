#include "bonded/BondedFragments.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>

namespace craterkit {
namespace {

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Components of the intact bond graph, numbered by decreasing size (ties: lowest particle).
void labelFragments(std::size_t n, const std::vector<BondedBond>& bonds,
                    const std::vector<std::uint8_t>& broken, const std::vector<double>& masses,
                    BondedFragmentResult& out) {
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (!broken.empty() && broken[b])
      continue;
    const std::uint32_t ri = findRoot(parent, bonds[b].i), rj = findRoot(parent, bonds[b].j);
    if (ri != rj)
      parent[std::max(ri, rj)] = std::min(ri, rj);
  }
  std::vector<std::uint32_t> rootIndex(n, UINT32_MAX);
  std::vector<std::size_t> size;
  std::vector<std::uint32_t> first;
  out.fragmentId.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = findRoot(parent, static_cast<std::uint32_t>(i));
    if (rootIndex[r] == UINT32_MAX) {
      rootIndex[r] = static_cast<std::uint32_t>(size.size());
      size.push_back(0);
      first.push_back(static_cast<std::uint32_t>(i));
    }
    out.fragmentId[i] = rootIndex[r];
    ++size[rootIndex[r]];
  }
  std::vector<std::uint32_t> order(size.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return size[a] != size[b] ? size[a] > size[b] : first[a] < first[b];
  });
  std::vector<std::uint32_t> rank(size.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    rank[order[k]] = static_cast<std::uint32_t>(k);
  out.fragmentSize.assign(size.size(), 0);
  out.fragmentMass.assign(size.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    out.fragmentId[i] = rank[out.fragmentId[i]];
    ++out.fragmentSize[out.fragmentId[i]];
    out.fragmentMass[out.fragmentId[i]] += masses[i];
  }
}

// Q_w(q): the smallest w_k such that the particles with w ≤ w_k hold at least q of the mass
// (pairs of value and mass, sorted by value). q = 0 gives the minimum, q = 1 the maximum.
double massQuantile(const std::vector<std::pair<double, double>>& sorted, double total, double q) {
  double cumulative = 0.0;
  for (const auto& vm : sorted)
    if ((cumulative += vm.second) >= q * total)
      return vm.first;
  return sorted.back().first; // rounding: q * total above the running sum's last value
}

// Q_w(qLo) and Q_w(qHi), the pairs sorted once.
std::pair<double, double> massQuantiles(std::vector<std::pair<double, double>>& valueMass,
                                        double qLo, double qHi) {
  std::sort(valueMass.begin(), valueMass.end());
  double total = 0.0;
  for (const auto& vm : valueMass)
    total += vm.second;
  return {massQuantile(valueMass, total, qLo), massQuantile(valueMass, total, qHi)};
}

// Two unit vectors perpendicular to e and to each other: the two side views.
void sideViews(const double e[3], double e1[3], double e2[3]) {
  const int k = std::fabs(e[0]) < 0.9 ? 0 : 1; // a basis vector far from e
  double a[3] = {0.0, 0.0, 0.0};
  a[k] = 1.0;
  const double ae = a[0] * e[0] + a[1] * e[1] + a[2] * e[2];
  double n = 0.0;
  for (int c = 0; c < 3; ++c) {
    e1[c] = a[c] - ae * e[c];
    n += e1[c] * e1[c];
  }
  for (int c = 0; c < 3; ++c)
    e1[c] /= std::sqrt(n);
  e2[0] = e[1] * e1[2] - e[2] * e1[1];
  e2[1] = e[2] * e1[0] - e[0] * e1[2];
  e2[2] = e[0] * e1[1] - e[1] * e1[0];
}

// The cloud's extents and leading-edge speed as mass quantiles (header: L_a, L_r, v_a).
void measureCloud(const std::vector<double>& x, const std::vector<double>& v,
                  const std::vector<double>& m, const std::vector<std::uint8_t>& inCloud,
                  const double o[3], const double e[3], const DebrisCloudParams& p,
                  BondedFragmentResult& out) {
  double e1[3], e2[3];
  sideViews(e, e1, e2);
  std::vector<std::pair<double, double>> axial, side, speed;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (!inCloud[i])
      continue;
    double s = 0.0, u1 = 0.0, u2 = 0.0, w = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = x[3 * i + c] - o[c];
      s += d * e[c], u1 += d * e1[c], u2 += d * e2[c], w += v[3 * i + c] * e[c];
    }
    axial.emplace_back(s, m[i]);
    side.emplace_back(u1, m[i]);
    side.emplace_back(u2, m[i]);
    speed.emplace_back(w, m[i]);
  }
  const double qHi = 0.5 * (1.0 + p.massFraction), qLo = 0.5 * (1.0 - p.massFraction);
  std::tie(out.rearEdge, out.leadingEdge) = massQuantiles(axial, qLo, qHi);
  out.axialLength = out.leadingEdge - out.rearEdge;
  const auto [front90, front99] = massQuantiles(axial, 0.90, 0.99);
  out.frontWidth = front99 - front90;
  const auto [sideLo, sideHi] = massQuantiles(side, qLo, qHi);
  out.radialExtent = sideHi - sideLo;
  out.ratio = out.radialExtent > 0.0 ? out.axialLength / out.radialExtent : 0.0;
  out.axialVelocity = massQuantiles(speed, qLo, qHi).second;
  out.axialVelocityRatio = p.impactSpeed > 0.0 ? out.axialVelocity / p.impactSpeed : 0.0;
}

} // namespace

BondedFragmentResult analyseBondedFragments(const std::vector<double>& positions,
                                            const std::vector<double>& velocities,
                                            const std::vector<double>& masses,
                                            const std::vector<BondedBond>& bonds,
                                            const std::vector<std::uint8_t>& bondBroken,
                                            const DebrisCloudParams& params) {
  const std::size_t n = masses.size();
  if (positions.size() != 3 * n || velocities.size() != 3 * n)
    throw InputError("BondedFragments: positions, velocities and masses differ in size");
  if (!bondBroken.empty() && bondBroken.size() != bonds.size())
    throw InputError("BondedFragments: one broken flag per bond expected");
  for (const BondedBond& b : bonds)
    if (b.i >= n || b.j >= n)
      throw InputError("BondedFragments: a bond names a particle that does not exist");
  if (!(params.massFraction > 0.0 && params.massFraction <= 1.0))
    throw InputError("BondedFragments: CloudMassFraction must be in (0, 1]");
  const auto& ax = params.axis;
  const double norm = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw InputError("BondedFragments: the cloud axis must be a non-zero vector");
  const double e[3] = {ax[0] / norm, ax[1] / norm, ax[2] / norm};
  const double o[3] = {params.origin[0], params.origin[1], params.origin[2]};

  BondedFragmentResult out;
  labelFragments(n, bonds, bondBroken, masses, out);

  // Past the rear face, and not bonded to anything at or before it.
  std::vector<std::uint8_t> inCloud(n, 0), anchored(out.fragmentSize.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k)
      s += (positions[3 * i + k] - o[k]) * e[k];
    inCloud[i] = s > params.cloudStart;
    if (!inCloud[i])
      anchored[out.fragmentId[i]] = 1;
  }
  std::vector<double> cloudMassOf(out.fragmentSize.size(), 0.0);
  std::vector<std::uint8_t> seen(out.fragmentSize.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    inCloud[i] = inCloud[i] && !anchored[out.fragmentId[i]];
    if (!inCloud[i])
      continue;
    ++out.cloudParticles;
    out.cloudMass += masses[i];
    if (!seen[out.fragmentId[i]]) {
      seen[out.fragmentId[i]] = 1;
      ++out.cloudFragments;
    }
    cloudMassOf[out.fragmentId[i]] += masses[i];
  }
  if (out.cloudParticles == 0)
    return out;
  out.largestCloudFragmentMass = *std::max_element(cloudMassOf.begin(), cloudMassOf.end());
  out.fragmentation = static_cast<double>(out.cloudFragments) / out.cloudParticles;
  measureCloud(positions, velocities, masses, inCloud, o, e, params, out);
  return out;
}

} // namespace craterkit

#include "bonded/BondedFragments.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <numeric>

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
  const auto& ax = params.axis;
  const double norm = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw InputError("BondedFragments: the cloud axis must be a non-zero vector");
  const double e[3] = {ax[0] / norm, ax[1] / norm, ax[2] / norm};

  BondedFragmentResult out;
  labelFragments(n, bonds, bondBroken, masses, out);

  std::vector<std::uint8_t> seen(out.fragmentSize.size(), 0);
  double lo = INFINITY, hi = -INFINITY, radial2 = 0.0, frontVelocity = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double d[3], s = 0.0;
    for (int k = 0; k < 3; ++k) {
      d[k] = positions[3 * i + k] - params.origin[k];
      s += d[k] * e[k];
    }
    if (!(s > params.cloudStart))
      continue;
    ++out.cloudParticles;
    if (!seen[out.fragmentId[i]]) {
      seen[out.fragmentId[i]] = 1;
      ++out.cloudFragments;
    }
    double p2 = 0.0;
    for (int k = 0; k < 3; ++k)
      p2 += (d[k] - s * e[k]) * (d[k] - s * e[k]);
    radial2 = std::max(radial2, p2);
    lo = std::min(lo, s);
    if (s > hi) {
      hi = s;
      frontVelocity =
          velocities[3 * i] * e[0] + velocities[3 * i + 1] * e[1] + velocities[3 * i + 2] * e[2];
    }
  }
  if (out.cloudParticles > 0) {
    out.fragmentation = static_cast<double>(out.cloudFragments) / out.cloudParticles;
    out.axialLength = hi - lo;
    out.radialExtent = 2.0 * std::sqrt(radial2);
    out.ratio = out.radialExtent > 0.0 ? out.axialLength / out.radialExtent : 0.0;
    out.axialVelocity = frontVelocity;
    out.axialVelocityRatio = params.impactSpeed > 0.0 ? frontVelocity / params.impactSpeed : 0.0;
  }
  return out;
}

} // namespace craterkit

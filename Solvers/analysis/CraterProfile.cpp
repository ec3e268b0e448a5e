#include "analysis/CraterProfile.h"

#include "common/CellList.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

void CraterProfileParams::validate() const {
  if (!std::isfinite(axis[0]) || !std::isfinite(axis[1]) || !std::isfinite(surfaceHeight))
    throw InputError("CraterProfile: the impact axis and the surface height must be finite");
  if (!(maxRadius >= 0.0) || !std::isfinite(maxRadius))
    throw InputError("CraterProfile: MaxRadius must not be negative (0: automatic)");
  if (radialBins < 0 || radialBins > 100000 || azimuthalBins < 1 || azimuthalBins > 3600)
    throw InputError("CraterProfile: RadialBins must be in [0, 100000] (0: automatic) and "
                     "AzimuthalBins in [1, 3600]");
  if (minNeighbours < 0 || !(neighbourFactor > 0.0))
    throw InputError("CraterProfile: the ejecta filter needs a non-negative neighbour count and a "
                     "positive range");
  if (!(slabHalfWidth >= 0.0) || !std::isfinite(slabHalfWidth))
    throw InputError("CraterProfile: the slab half-width must not be negative (0: automatic)");
}

CraterMeasures measureProfile(const std::vector<double>& radius, const std::vector<double>& height,
                              double z0, double tolerance) {
  CraterMeasures m;
  std::vector<double> r, h;
  for (std::size_t i = 0; i < radius.size(); ++i)
    if (std::isfinite(height[i]))
      r.push_back(radius[i]), h.push_back(height[i]);
  if (r.size() < 2)
    return m;
  const std::size_t lowest =
      static_cast<std::size_t>(std::min_element(h.begin(), h.end()) - h.begin());
  if (!(h[lowest] < z0))
    return m;
  m.depth = z0 - h[lowest];
  // First rise back to z0 outwards from the lowest point, interpolated linearly.
  std::size_t k = lowest;
  while (k + 1 < h.size() && h[k + 1] < z0)
    ++k;
  if (k + 1 >= h.size())
    return m; // still below z0 at the edge: the crater is wider than the profile
  const double t = (z0 - h[k]) / (h[k + 1] - h[k]);
  const double edge = r[k] + t * (r[k + 1] - r[k]);
  m.diameter = 2.0 * edge;
  // The rim: the highest point within one crater radius beyond the edge (a rim crest lies at
  // 1.1-1.3 crater radii; a high point farther out is the surrounding terrain, or the
  // container's edge, and a crater without a raised rim would otherwise report one there).
  const double reach = 2.0 * edge;
  std::size_t rim = k + 1;
  for (std::size_t j = k + 1; j < h.size() && r[j] <= reach; ++j)
    if (h[j] > h[rim])
      rim = j;
  // The rim's radius: the middle of the run of bins around the highest that are within
  // `tolerance` of it (a surface of particles is stepped; its top is flat over a few bins).
  std::size_t first = rim, last = rim;
  while (first > k + 1 && h[first - 1] >= h[rim] - tolerance)
    --first;
  while (last + 1 < h.size() && r[last + 1] <= reach && h[last + 1] >= h[rim] - tolerance)
    ++last;
  m.rimDiameter = r[first] + r[last];
  m.rimHeight = h[rim] - z0;
  m.depthBelowRim = h[rim] - h[lowest];
  // Excavated volume inside the edge (trapezoids of 2π r (z0 − h) dr).
  auto depthAt = [&](std::size_t j) { return std::max(0.0, z0 - h[j]); };
  double prevR = 0.0, prevF = 0.0; // the integrand 2π r (z0 − h) vanishes on the axis
  for (std::size_t j = 0; j <= k; ++j) {
    const double f = 2.0 * M_PI * r[j] * depthAt(j);
    m.volume += 0.5 * (f + prevF) * (r[j] - prevR);
    prevR = r[j], prevF = f;
  }
  m.volume += 0.5 * prevF * (edge - prevR);
  m.found = true;
  return m;
}

SectionCrater measureSection(const std::vector<double>& top, double bin, double impactX, double z0,
                             double drop) {
  SectionCrater m;
  if (top.empty())
    return m;
  const std::size_t centre = std::min(top.size() - 1, static_cast<std::size_t>(impactX / bin));
  m.depth = std::max(0.0, z0 - *std::min_element(top.begin(), top.end()));
  std::size_t lo = centre, hi = centre;
  if (top[centre] < z0 - drop) {
    while (lo > 0 && top[lo - 1] < z0 - drop)
      --lo;
    while (hi + 1 < top.size() && top[hi + 1] < z0 - drop)
      ++hi;
    m.width = (hi - lo + 1) * bin;
  }
  return m;
}

CraterProfileResult craterProfile(const std::vector<double>& positions,
                                  const std::vector<double>& radii,
                                  const CraterProfileParams& par) {
  par.validate();
  const std::size_t n = radii.size();
  if (n == 0 || positions.size() != 3 * n)
    throw InputError("CraterProfile: no particles (or positions and radii of different counts)");
  double rmean = 0.0, extent = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(radii[i] > 0.0) || !std::isfinite(radii[i]))
      throw InputError("CraterProfile: particle " + std::to_string(i) +
                       " has a non-positive radius");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(positions[3 * i + k]))
        throw InputError("CraterProfile: particle " + std::to_string(i) +
                         " has a non-finite position");
    rmean += radii[i];
    extent = std::max(
        extent, std::hypot(positions[3 * i] - par.axis[0], positions[3 * i + 1] - par.axis[1]));
  }
  rmean /= static_cast<double>(n);
  const double R = par.maxRadius > 0.0 ? par.maxRadius : extent;
  const int nr =
      par.radialBins > 0 ? par.radialBins : std::max(4, static_cast<int>(R / (5.0 * rmean)));
  const int na = par.azimuthalBins;
  const double dr = R / nr;

  // Bulk particles: enough neighbours close by (isolated ejecta have none). Each particle
  // searches its own range on cells of the mean range, so that a large body does not make
  // every particle scan the cells of its size.
  CellList cells;
  cells.build(positions.data(), n, par.neighbourFactor * rmean);
  std::vector<char> bulk(n, 0);
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::size_t i = 0; i < n; ++i) {
    int count = 0;
    const double* x = &positions[3 * i];
    const double range = par.neighbourFactor * radii[i];
    cells.forEachCandidate(x, range, [&](std::size_t j) {
      if (j == i)
        return;
      const double* y = &positions[3 * j];
      const double d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                        (x[2] - y[2]) * (x[2] - y[2]);
      count += d2 < range * range;
    });
    bulk[i] = count >= par.minNeighbours;
  }

  // Top of the highest bulk particle in each (radial, azimuthal) bin.
  std::vector<double> top(static_cast<std::size_t>(nr) * na, -INFINITY);
  std::vector<double> topR(top.size(),
                           0.0); // distance from the axis of the particle giving the top
  CraterProfileResult out;
  const double slab = par.slabHalfWidth > 0.0 ? par.slabHalfWidth : 4.0 * rmean;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = positions[3 * i] - par.axis[0], dy = positions[3 * i + 1] - par.axis[1];
    if (std::abs(dy) <= slab)
      out.slab.push_back(i);
    const double r = std::hypot(dx, dy);
    if (r >= R)
      continue;
    if (!bulk[i]) {
      ++out.rejectedAsEjecta;
      continue;
    }
    const int ir = std::min(nr - 1, static_cast<int>(r / dr));
    double phi = std::atan2(dy, dx);
    if (phi < 0.0)
      phi += 2.0 * M_PI;
    const int ia = std::min(na - 1, static_cast<int>(phi / (2.0 * M_PI) * na));
    const std::size_t bin = static_cast<std::size_t>(ir) * na + ia;
    if (positions[3 * i + 2] + radii[i] > top[bin])
      top[bin] = positions[3 * i + 2] + radii[i], topR[bin] = r;
  }
  out.radius.resize(nr);
  out.height.assign(nr, NAN);
  out.binsUsed.assign(nr, 0);
  std::vector<double> neg(nr, NAN), pos(nr, NAN);
  for (int ir = 0; ir < nr; ++ir) {
    // The profile point of a radial bin sits at the mean distance of the particles that give
    // its tops, not at the bin's centre: on a slope the highest particle of a bin is at its
    // upper edge, and the centre would shift the profile by up to half a bin.
    double sum = 0.0, sumN = 0.0, sumP = 0.0, sumR = 0.0;
    int used = 0, usedN = 0, usedP = 0;
    for (int ia = 0; ia < na; ++ia) {
      const double t = top[static_cast<std::size_t>(ir) * na + ia];
      if (!std::isfinite(t))
        continue;
      sum += t, ++used;
      sumR += topR[static_cast<std::size_t>(ir) * na + ia];
      const double phi = (ia + 0.5) * 2.0 * M_PI / na;
      const double c = std::cos(phi);
      if (c < -0.5)
        sumN += t, ++usedN;
      else if (c > 0.5)
        sumP += t, ++usedP;
    }
    out.radius[ir] = used > 0 ? sumR / used : (ir + 0.5) * dr;
    out.binsUsed[ir] = used;
    if (used > 0)
      out.height[ir] = sum / used;
    if (usedN > 0)
      neg[ir] = sumN / usedN;
    if (usedP > 0)
      pos[ir] = sumP / usedP;
    out.surfaceParticles += static_cast<std::size_t>(used);
  }
  const double tolerance = 0.5 * rmean; // a quarter of a particle diameter
  out.all = measureProfile(out.radius, out.height, par.surfaceHeight, tolerance);
  out.negativeHalf = measureProfile(out.radius, neg, par.surfaceHeight, tolerance);
  out.positiveHalf = measureProfile(out.radius, pos, par.surfaceHeight, tolerance);
  if (out.all.found) {
    double lowest = INFINITY;
    for (int ir = 0; ir < nr && (ir + 0.5) * dr <= 0.5 * out.all.diameter; ++ir)
      for (int ia = 0; ia < na; ++ia) {
        const double t = top[static_cast<std::size_t>(ir) * na + ia];
        if (std::isfinite(t)) // an empty bin has no top
          lowest = std::min(lowest, t);
      }
    if (std::isfinite(lowest)) {
      out.deepestDepth = par.surfaceHeight - lowest;
      out.deepestDepthBelowRim = out.all.rimHeight + out.deepestDepth;
    }
  }
  return out;
}

} // namespace craterkit

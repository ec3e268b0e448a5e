#include "analysis/HeapAngle.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace craterkit {

HeapAngle measureHeapAngle(const ParticleSet& s, double floor, double lo, double hi) {
  const std::size_t n = s.size();
  if (n < 10)
    throw InputError("a heap needs at least 10 particles");
  double cx = 0.0, cy = 0.0, mass = 0.0, rmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    cx += s.mass[i] * s.position[3 * i];
    cy += s.mass[i] * s.position[3 * i + 1];
    mass += s.mass[i];
    rmax = std::max(rmax, s.radius[i]);
  }
  cx /= mass;
  cy /= mass;
  // Extent: the radius that holds 99 % of the particles (ignores a few strays).
  std::vector<double> rho(n);
  for (std::size_t i = 0; i < n; ++i)
    rho[i] = std::hypot(s.position[3 * i] - cx, s.position[3 * i + 1] - cy);
  std::vector<double> sorted = rho;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(0.99 * (n - 1)),
                   sorted.end());
  const double extent = sorted[static_cast<std::size_t>(0.99 * (n - 1))] + rmax;
  const double width = 2.0 * rmax;
  const int nbins = std::max(1, static_cast<int>(std::ceil(extent / width)));
  std::vector<double> top(nbins, floor);
  for (std::size_t i = 0; i < n; ++i) {
    const int b = std::min(nbins - 1, static_cast<int>(rho[i] / width));
    top[b] = std::max(top[b], s.position[3 * i + 2] + s.radius[i]);
  }
  HeapAngle out;
  out.extent = extent;
  out.height = *std::max_element(top.begin(), top.end()) - floor;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int b = 0; b < nbins; ++b) {
    const double x = (b + 0.5) * width;
    if (x < lo * extent || x > hi * extent)
      continue;
    sx += x;
    sy += top[b];
    sxx += x * x;
    sxy += x * top[b];
    ++out.bins;
  }
  if (out.bins < 3)
    throw InputError("the heap is too small to fit its flank (fewer than 3 radial bins)");
  const double slope = (out.bins * sxy - sx * sy) / (out.bins * sxx - sx * sx);
  out.degrees = std::atan(-slope) * 180.0 / M_PI;
  return out;
}

} // namespace craterkit

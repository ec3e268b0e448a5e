#include "bed/RandomFill.h"

#include "bed/BedPreparation.h"
#include "common/CellList.h"
#include "common/Error.h"
#include "common/Random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <vector>

namespace craterkit {

namespace {

// Random placement: start at this packing fraction, inflate over about kGrowthSweeps
// sweeps while the worst relative overlap stays below kGrowthOverlap.
constexpr double kStartFraction = 0.30;
constexpr double kGrowthSweeps = 300.0;
constexpr double kGrowthOverlap = 0.02;
constexpr double kRelaxSpacing = 1e-3;
constexpr double kWallDepletion = 0.5; // in mean radii

double sphereVolume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

// One Jacobi sweep at radii `scale` times their full size: stores in `shift` the move of each
// sphere away from the spheres it overlaps, pushing each pair to `spacing` times contact, and
// returns the worst overlap relative to the smaller radius.
double overlapShifts(const ParticleSet& s, const CellList& cells, double scale, double rmax,
                     double spacing, std::vector<double>& shift) {
  const std::size_t n = s.size();
  const double* radius = s.radius.data();
  const double* x = s.position.data();
  double worst = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    double d[3] = {0.0, 0.0, 0.0};
    const double ri = scale * radius[i], vi = ri * ri * ri;
    cells.forEachCandidate(&x[3 * i], ri + rmax, [&](std::size_t j) {
      if (j == i)
        return;
      const double rj = scale * radius[j];
      double e[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
      const double dist2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
      const double contact = (ri + rj) * spacing;
      if (dist2 >= contact * contact)
        return;
      double dist = std::sqrt(dist2);
      worst = std::max(worst, (ri + rj - dist) / std::min(ri, rj));
      if (dist == 0.0) { // coincident centres: separate along an index-dependent axis
        e[i < j ? 0 : 1] = 1.0;
        dist = 1.0;
      }
      const double vj = rj * rj * rj;
      const double move = (contact - std::sqrt(dist2)) * vj / (vi + vj) / dist;
      for (int k = 0; k < 3; ++k)
        d[k] += move * e[k];
    });
    for (int k = 0; k < 3; ++k)
      shift[3 * i + k] = d[k];
  }
  return worst;
}

// Removes all overlaps by Jacobi relaxation while the radii grow from a fraction of their
// final size (force-biased inflation) over about `growthSweeps`: overlaps stay small at every
// sweep, so the relaxation converges in a few hundred sweeps instead of untangling a dense
// random start. Stops once the radii are full and no pair overlaps by more than `tolerance`
// (relative to the smaller radius). Returns the number of sweeps.
int relaxOverlaps(ParticleSet& s, const GranularBedParams& p, const Container& container,
                  double rmax, bool inflate, const ProgressCallback& progress,
                  double tolerance = 0.0, double growthSweeps = kGrowthSweeps) {
  const std::size_t n = s.size();
  const double* radius = s.radius.data();
  std::vector<double> shift(3 * n);
  CellList cells;
  // Pairs are pushed slightly past contact: it speeds up convergence and leaves no pair
  // overlapping by round-off once the sweep finds none.
  const double spacing = 1.0 + kRelaxSpacing;
  double scale = inflate ? std::min(1.0, std::cbrt(kStartFraction / p.packingFraction)) : 1.0;
  const double growth = std::max(1e-4, -std::log(scale) / growthSweeps);
  for (int sweep = 0; sweep < p.maxRelaxationIterations; ++sweep) {
    if (sweep % 16 == 0) {
      // 0.8 over the growth's sweeps, then on towards 1 while the last overlaps go (that can
      // take as long again: the bar must keep moving, not sit at its end).
      const double g2 = 2.0 * growthSweeps;
      reportProgress(progress, sweep < g2 ? 0.8 * sweep / g2 : 0.8 + 0.2 * (1.0 - g2 / sweep));
    }
    double* x = s.position.data();
    cells.build(x, n, 2.0 * rmax);
    const double worst = overlapShifts(s, cells, scale, rmax, spacing, shift);
    if (worst <= tolerance && scale == 1.0)
      return sweep;
#pragma omp parallel for schedule(static) if (n >= 512)
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k)
        x[3 * i + k] += shift[3 * i + k];
      container.project(&x[3 * i], scale * radius[i]);
    }
    // Grow only while the packing keeps up, so that jams are not forced.
    if (worst < std::max(kGrowthOverlap, tolerance))
      scale = std::min(1.0, scale * (1.0 + growth));
  }
  std::ostringstream msg;
  msg << "could not place " << n << " particles without overlap at PackingFraction "
      << p.packingFraction << " within " << p.maxRelaxationIterations
      << " relaxation sweeps: lower PackingFraction (random placement jams near 0.6)";
  throw InputError(msg.str());
}

// Radii drawn from the size distribution until their volume reaches the target.
std::vector<double> drawRadii(const GranularBedParams& p, const RandomFillSpec& spec, Random& rng) {
  const double target =
      p.packingFraction * spec.container.fillVolume(kWallDepletion * p.sizes.moment(1));
  std::vector<double> radii;
  double volume = 0.0;
  while (volume < target) {
    if (static_cast<std::int64_t>(radii.size()) >= spec.maxParticles)
      checkCap(static_cast<double>(radii.size()) + 1.0, spec.maxParticles);
    radii.push_back(p.sizes.sample(rng));
    volume += sphereVolume(radii.back());
  }
  return radii;
}

} // namespace

ParticleSet randomFill(const GranularBedParams& p, const RandomFillSpec& spec,
                       GranularBedReport& report, const ProgressCallback& progress) {
  auto clock = std::chrono::steady_clock::now();
  const Container& c = spec.container;
  Random rng(p.seed);
  const std::vector<double> radii = drawRadii(p, spec, rng);
  ParticleSet out;
  out.reserve(radii.size());
  std::int64_t next = 0;
  for (double r : radii) {
    double lo[3], hi[3], x[3];
    c.bounds(r, lo, hi);
    do {
      for (int k = 0; k < 3; ++k)
        x[k] = rng.uniform(lo[k], hi[k]);
    } while (!c.inside(x, r));
    out.add(x, r, p.particleDensity, p.material, next++);
  }
  endStage(report, "placement", clock);
  report.relaxationIterations = relaxOverlaps(out, p, c, p.sizes.largest(), true, progress,
                                              spec.overlapTolerance, spec.growthSweeps);
  endStage(report, "relaxation", clock);
  return out;
}

ParticleSet randomBed(const GranularBedParams& p, GranularBedReport& report,
                      const ProgressCallback& progress) {
  return randomFill(p, {p.container, p.maxParticles, 0.0, kGrowthSweeps}, report, progress);
}

} // namespace craterkit

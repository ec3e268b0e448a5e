#include "bed/GranularBed.h"

#include "bed/BedPreparation.h"
#include "bed/LatticeBed.h"
#include "bed/RandomFill.h"
#include "bed/SettleAndUnload.h"
#include "common/CellList.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace craterkit {

namespace {

constexpr double kMaxRandomFraction = 0.62;

// Runs the preparation method the parameters choose. Each method is one function in a file
// of its own (bed/LatticeBed.h, bed/RandomFill.h, bed/SettleAndUnload.h): a new method is a
// new file and a new case here.
ParticleSet prepareBed(const GranularBedParams& p, GranularBedReport& report,
                       const ProgressCallback& progress) {
  switch (p.packing) {
  case GranularBedParams::Packing::HCP:
    return hcpLatticeBed(p, progress);
  case GranularBedParams::Packing::RCP:
    return p.settle ? settledRandomBed(p, report, progress) : randomBed(p, report, progress);
  case GranularBedParams::Packing::Loose:
    return settledRandomBed(p, report, progress);
  }
  throw InputError("unknown packing");
}

} // namespace

void GranularBedParams::validate() const {
  sizes.validate();
  container.validate(sizes.largest());
  std::ostringstream msg;
  if (!(particleDensity > 0.0) || !std::isfinite(particleDensity)) {
    msg << "ParticleDensity must be positive and finite (got " << particleDensity << " kg/m^3)";
    throw InputError(msg.str());
  }
  if (maxParticles <= 0) {
    msg << "MaxParticles must be positive (got " << maxParticles << ")";
    throw InputError(msg.str());
  }
  if (packing == Packing::HCP && sizes.type != SizeDistribution::Type::Monodisperse)
    throw InputError("HCP packing is a lattice of equal spheres: choose the Monodisperse "
                     "size distribution, or RCP for a range of radii");
  if (packing != Packing::HCP &&
      (!(packingFraction > 0.0) || packingFraction > kMaxRandomFraction)) {
    msg << "PackingFraction must be in (0, " << kMaxRandomFraction << "] for random placement (got "
        << packingFraction << "); denser beds come from settling with the DEM";
    throw InputError(msg.str());
  }
  if (maxRelaxationIterations <= 0)
    throw InputError("the relaxation sweep limit must be positive");
  if (settles()) {
    if (!(settlingGravity > 0.0) || !std::isfinite(settlingGravity)) {
      msg << "SettlingGravity must be positive (got " << settlingGravity << " m/s^2)";
      throw InputError(msg.str());
    }
    if (!(settlingFriction >= 0.0) || !std::isfinite(settlingFriction)) {
      msg << "SettlingFriction must be non-negative (got " << settlingFriction << ")";
      throw InputError(msg.str());
    }
    if (!(stageMaxExpectedSpeed >= 0.0) || !std::isfinite(stageMaxExpectedSpeed)) {
      msg << "DEMMaxExpectedSpeed must be non-negative and finite (got " << stageMaxExpectedSpeed
          << " m/s)";
      throw InputError(msg.str());
    }
    if (!(stageMaxOverlap > 0.0) || !(stageMaxOverlap < 1.0)) {
      msg << "DEMMaxOverlap must lie in (0, 1) (got " << stageMaxOverlap << ")";
      throw InputError(msg.str());
    }
    if (!std::isfinite(stageNormalStiffness)) {
      msg << "DEMNormalStiffness must be finite (got " << stageNormalStiffness << " N/m)";
      throw InputError(msg.str());
    }
  }
  checkCap(expectedParticles(*this), maxParticles);
}

ParticleSet generateGranularBed(const GranularBedParams& params, GranularBedReport* report,
                                const ProgressCallback& progress) {
  params.validate();
  GranularBedReport local;
  GranularBedReport& rep = report ? *report : local;
  rep = GranularBedReport{};
  ParticleSet bed = prepareBed(params, rep, progress);
  if (bed.size() == 0)
    throw InputError("the container holds no particle of the requested size");
  rep.particles = bed.size();
  rep.topHeight = std::numeric_limits<double>::lowest();
  for (std::size_t i = 0; i < bed.size(); ++i)
    rep.topHeight = std::max(rep.topHeight, bed.position[3 * i + 2] + bed.radius[i]);
  rep.bulkPackingFraction =
      measurePackingFraction(bed, params.container, 3.0 * params.sizes.largest(), 200000);
  rep.coordinationNumber = coordinationNumber(bed, params.container, 3.0 * params.sizes.largest());
  reportProgress(progress, 1.0);
  return bed;
}

double measurePackingFraction(const ParticleSet& s, const Container& container, double margin,
                              std::size_t samples) {
  const std::size_t n = s.size();
  if (n == 0 || samples == 0)
    return std::numeric_limits<double>::quiet_NaN();
  const double rmax = *std::max_element(s.radius.begin(), s.radius.end());
  CellList cells;
  cells.build(s.position.data(), n, 2.0 * rmax);
  double lo[3], hi[3];
  container.bounds(margin, lo, hi);
  for (int k = 0; k < 3; ++k)
    if (!(hi[k] > lo[k]))
      return std::numeric_limits<double>::quiet_NaN();
  // R3 sequence (Roberts 2018): alpha_k = g^-k with g the real root of x^4 = x + 1.
  const double g = 1.2207440846057594754;
  const double alpha[3] = {1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g)};
  long long accepted = 0, covered = 0;
#pragma omp parallel for schedule(static) reduction(+ : accepted, covered)
  for (std::size_t m = 0; m < samples; ++m) {
    double x[3];
    for (int k = 0; k < 3; ++k) {
      const double f = 0.5 + alpha[k] * static_cast<double>(m + 1);
      x[k] = lo[k] + (f - std::floor(f)) * (hi[k] - lo[k]);
    }
    if (!container.inside(x, margin))
      continue;
    ++accepted;
    bool hit = false;
    cells.forEachCandidate(x, rmax, [&](std::size_t j) {
      if (hit)
        return;
      const double* c = &s.position[3 * j];
      const double d2 = (x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
                        (x[2] - c[2]) * (x[2] - c[2]);
      hit = d2 < s.radius[j] * s.radius[j];
    });
    covered += hit ? 1 : 0;
  }
  return accepted ? static_cast<double>(covered) / static_cast<double>(accepted)
                  : std::numeric_limits<double>::quiet_NaN();
}

double coordinationNumber(const ParticleSet& s, const Container& container, double margin) {
  const std::size_t n = s.size();
  if (n == 0)
    return std::numeric_limits<double>::quiet_NaN();
  const double rmax = *std::max_element(s.radius.begin(), s.radius.end());
  CellList cells;
  cells.build(s.position.data(), n, 2.0 * rmax);
  long long grains = 0, contacts = 0;
#pragma omp parallel for schedule(static) reduction(+ : grains, contacts) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    const double* a = &s.position[3 * i];
    if (!container.inside(a, margin))
      continue;
    ++grains;
    cells.forEachCandidate(a, s.radius[i] + rmax, [&](std::size_t j) {
      if (j == i)
        return;
      const double* b = &s.position[3 * j];
      const double d2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]);
      const double reach = (s.radius[i] + s.radius[j]) * (1.0 + 1e-9);
      contacts += d2 <= reach * reach ? 1 : 0;
    });
  }
  return grains ? static_cast<double>(contacts) / static_cast<double>(grains)
                : std::numeric_limits<double>::quiet_NaN();
}

double smallestGap(const ParticleSet& s, std::size_t* first, std::size_t* second) {
  const std::size_t n = s.size();
  double best = std::numeric_limits<double>::infinity();
  if (n < 2)
    return best;
  const double rmax = *std::max_element(s.radius.begin(), s.radius.end());
  CellList cells;
  cells.build(s.position.data(), n, 2.0 * rmax);
  for (std::size_t i = 0; i < n; ++i)
    cells.forEachCandidate(&s.position[3 * i], s.radius[i] + rmax, [&](std::size_t j) {
      if (j <= i)
        return;
      const double* a = &s.position[3 * i];
      const double* b = &s.position[3 * j];
      const double d = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                 (a[2] - b[2]) * (a[2] - b[2]));
      const double gap = d - s.radius[i] - s.radius[j];
      if (gap < best) {
        best = gap;
        if (first)
          *first = i;
        if (second)
          *second = j;
      }
    });
  return best;
}

} // namespace craterkit

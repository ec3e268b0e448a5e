#include "bed/GranularBed.h"

#include "common/CellList.h"
#include "common/Error.h"
#include "dem/DemSetup.h"
#include "dem/DemSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace craterkit {

namespace {

constexpr double kHcpFraction = 0.74048048969306104; // π / (3 √2)
constexpr double kMaxRandomFraction = 0.62;
// Lattice sites and relaxed centres may touch a wall to this relative tolerance.
constexpr double kWallTolerance = 1e-12;
// Random placement: start at this packing fraction, inflate over about kGrowthSweeps
// sweeps while the worst relative overlap stays below kGrowthOverlap.
constexpr double kStartFraction = 0.30;
constexpr double kGrowthSweeps = 300.0;
constexpr double kGrowthOverlap = 0.02;
constexpr double kRelaxSpacing = 1e-3;
// Settling (docs/physics.md §7). The loose fill may keep overlaps up to kLooseOverlap (relative
// to the smaller radius) and grows over kLooseGrowthSweeps: the soft DEM law pushes them apart.
constexpr double kLooseOverlap = 0.1;
constexpr double kLooseGrowthSweeps = 30.0;
// The soft settling law: k_N from the lithostatic load of the fill at this overlap fraction
// (proposeStiffness), kSettleStepsPerContact steps per contact (the solver's floor is 10),
// restitution kSettleRestitution (strong damping; a trial at 0.1 with this step did not come to
// rest within the time limit). Overlaps of a few per cent are expected while settling.
constexpr double kSettleOverlap = 0.006;
constexpr double kSettleStepsPerContact = 12.0;
constexpr double kSettleRestitution = 0.3;
constexpr double kSettleOverlapWarning = 0.3;
// Settling runs at least this fraction of the fill's free-fall time.
constexpr double kMinFall = 0.5;
// Unloading: gravity lowered to this fraction over this many steps per grain layer.
constexpr double kUnloadGravity = 1.0 / 64.0;
constexpr double kUnloadStepsPerLayer = 25.0;
constexpr double kWallDepletion = 0.5; // in mean radii

// Appends the seconds since `start` to the report's stage times under `name`, restarts it.
void endStage(GranularBedReport& report, const char* name,
              std::chrono::steady_clock::time_point& start) {
  const auto now = std::chrono::steady_clock::now();
  report.stageSeconds.emplace_back(name, std::chrono::duration<double>(now - start).count());
  start = now;
}

double sphereVolume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

double expectedParticles(const GranularBedParams& p) {
  const double fraction =
      p.packing == GranularBedParams::Packing::HCP ? kHcpFraction : p.packingFraction;
  return fraction * p.container.fillVolume() / (4.0 / 3.0 * M_PI * p.sizes.moment(3));
}

void checkCap(double n, std::int64_t cap) {
  if (n > static_cast<double>(cap)) {
    std::ostringstream msg;
    msg << "the bed needs about " << static_cast<long long>(n)
        << " particles, more than MaxParticles (" << cap
        << "): use larger particles, a smaller container, or raise MaxParticles";
    throw InputError(msg.str());
  }
}

ParticleSet hcpBed(const GranularBedParams& p, const ProgressCallback& progress) {
  const Container& c = p.container;
  const double r = p.sizes.radius;
  const double a = 2.0 * r;
  const double dy = a * std::sqrt(3.0) / 2.0;
  const double dz = a * std::sqrt(2.0 / 3.0);
  double lo[3], hi[3];
  c.bounds(r, lo, hi);
  // Box beds stand on the floor; bowl beds hang from the surface so it stays flat.
  const bool fromFloor = c.type == Container::Type::Box;
  const double z0 = fromFloor ? c.floorHeight() + r : c.surfaceHeight - r;
  const long layers = static_cast<long>(std::floor((hi[2] - lo[2]) / dz + 1e-9)) + 1;
  const long imax = static_cast<long>(std::ceil(std::max(-lo[0], hi[0]) / a)) + 1;
  const long jmax = static_cast<long>(std::ceil(std::max(-lo[1], hi[1]) / dy)) + 1;
  const double margin = r * (1.0 - kWallTolerance);

  ParticleSet out;
  out.reserve(static_cast<std::size_t>(expectedParticles(p) * 1.05) + 16);
  std::int64_t next = 0;
  for (long k = 0; k < layers; ++k) {
    reportProgress(progress, static_cast<double>(k) / layers);
    const double z = fromFloor ? z0 + k * dz : z0 - k * dz;
    const bool layerB = (k % 2) == 1;
    const double ox = layerB ? r : 0.0, oy = layerB ? r / std::sqrt(3.0) : 0.0;
    for (long j = -jmax; j <= jmax; ++j)
      for (long i = -imax; i <= imax; ++i) {
        const double x[3] = {i * a + ((j % 2) != 0 ? r : 0.0) + ox, j * dy + oy, z};
        if (!c.inside(x, margin))
          continue;
        if (next >= p.maxParticles)
          checkCap(static_cast<double>(next) + 1.0, p.maxParticles);
        out.add(x, r, p.particleDensity, p.material, next++);
      }
  }
  return out;
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
    double worst = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst) if (n >= 512)
    for (std::size_t i = 0; i < n; ++i) {
      double d[3] = {0.0, 0.0, 0.0};
      const double ri = scale * radius[i], vi = ri * ri * ri;
      cells.forEachCandidate(&x[3 * i], ri + rmax, [&](std::size_t j) {
        if (j == i)
          return;
        const double rj = scale * radius[j];
        double e[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1],
                       x[3 * i + 2] - x[3 * j + 2]};
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

ProgressCallback subRange(const ProgressCallback& progress, double lo, double hi) {
  if (!progress)
    return {};
  return [progress, lo, hi](double f) { return progress(lo + (hi - lo) * f); };
}

// Kinetic energy (translation and spin) of the particles whose centre lies below `keepBelow`,
// and their number.
double keptKineticEnergy(const ParticleSet& s, double keepBelow, std::size_t& kept) {
  double energy = 0.0;
  kept = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.position[3 * i + 2] > keepBelow)
      continue;
    ++kept;
    double v2 = 0.0, w2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      v2 += s.velocity[3 * i + k] * s.velocity[3 * i + k];
      w2 += s.angularVelocity[3 * i + k] * s.angularVelocity[3 * i + k];
    }
    energy += 0.5 * s.mass[i] * (v2 + 0.4 * s.radius[i] * s.radius[i] * w2);
  }
  return energy;
}

// The settling run's DEM: strong damping, the bed's friction, no rolling resistance, and a
// soft contact law (docs/physics.md §7). The stiffness carries the weight of the filled
// height at the overlap kSettleOverlap of the lithostatic estimate, not an impact: the step
// grows as 1/sqrt(k_N), and the overlaps it leaves are taken out by unloading (unloadBed).
DemParams settlingParams(const GranularBedParams& p, const Container& filled) {
  const double g = p.settlingGravity;
  const double rmin = p.sizes.smallest();
  DemParams dp;
  dp.walls = containerWalls(filled);
  dp.gravity = Gravity::downward(g);
  dp.contact.restitutionN = dp.contact.restitutionT = kSettleRestitution;
  dp.contact.muS = p.settlingFriction;
  dp.contact.muR = dp.contact.muT = 0.0;
  // The loose fill may overlap by kLooseOverlap; the soft law pushes that apart gently.
  dp.initialOverlapLimit = 2.0 * kLooseOverlap;
  dp.overlapWarning = kSettleOverlapWarning;
  dp.warnStepsPerCollision = kSettleStepsPerContact;
  const StiffnessChoice k =
      chooseStiffnessAndStep({rmin, p.particleDensity, 0.0, kSettleOverlap, g,
                              filled.surfaceHeight - filled.floorHeight(), kSettleStepsPerContact});
  dp.contact.kN = k.kN;
  dp.contact.kT = k.kT;
  dp.dt = k.dt;
  return dp;
}

// Unloads a settled bed: gravity falls exponentially to kUnloadGravity of its value over
// kUnloadStepsPerLayer steps per grain layer of the fill (a few crossings of the bed by a
// contact wave), so the contacts relax quasi-statically to a 64th of their overlap under the
// full weight, as a law 64 times stiffer would leave them, at the soft law's step.
void unloadBed(DemSolver& solver, double g, double height, double meanRadius,
               const ProgressCallback& progress) {
  const long steps =
      std::max(200L, std::lround(kUnloadStepsPerLayer * height / (2.0 * meanRadius)));
  for (long i = 0; i < steps; ++i) {
    if (i % 10 == 0) {
      reportProgress(progress, static_cast<double>(i) / steps);
      solver.setGravity(Gravity::downward(g * std::pow(kUnloadGravity, double(i) / steps)));
    }
    solver.step();
  }
}

// Settles a loose bed under gravity with the SSDEM solver until its kinetic energy has
// decayed, then unloads it (docs/physics.md §7).
ParticleSet settleBed(const ParticleSet& loose, const GranularBedParams& p, const Container& filled,
                      GranularBedReport& report, const ProgressCallback& progress) {
  const double g = p.settlingGravity;
  const double height = filled.surfaceHeight - filled.floorHeight();
  const DemParams dp = settlingParams(p, filled);
  const double fall = std::sqrt(2.0 * height / g);
  DemSolver solver(loose, dp);

  // Only the part of the bed that will be kept must come to rest: spheres in the extra fill
  // above the surface keep rolling on its free slope and are trimmed afterwards.
  const double keepBelow = p.container.surfaceHeight - 2.0 * p.sizes.largest();
  double meanMass = 0.0, meanRadius = 0.0;
  for (std::size_t i = 0; i < loose.size(); ++i) {
    meanMass += loose.mass[i] / loose.size();
    meanRadius += loose.radius[i] / loose.size();
  }
  const double chunk = std::max(0.05 * fall, 100.0 * dp.dt);
  const double limit = 40.0 * fall;
  // The loose fill compacts by falling a fraction of its height: half the free-fall time of
  // the whole fill passes before its energy can have peaked and decayed.
  while (solver.time() < limit) {
    solver.advanceTo(solver.time() + chunk);
    reportProgress(progress, std::min(0.9, solver.time() / (2.0 * fall)));
    std::size_t kept = 0;
    const double energy = keptKineticEnergy(solver.particles(), keepBelow, kept);
    if (solver.time() > kMinFall * fall &&
        energy < p.settledEnergy * kept * meanMass * g * meanRadius) {
      report.settled = true;
      break;
    }
  }
  unloadBed(solver, g, height, meanRadius, subRange(progress, 0.9, 1.0));
  report.settlingTime = solver.time();
  report.settlingSteps = solver.stepCount();
  ParticleSet out = solver.particles();
  std::fill(out.velocity.begin(), out.velocity.end(), 0.0);
  std::fill(out.angularVelocity.begin(), out.angularVelocity.end(), 0.0);
  return out;
}

// Keeps the particles whose top is at or below the surface, renumbering the ids.
ParticleSet trimToSurface(const ParticleSet& s, double surface) {
  ParticleSet out;
  out.reserve(s.size());
  std::int64_t next = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.position[3 * i + 2] + s.radius[i] <= surface + 1e-12 * s.radius[i]) {
      out.add(&s.position[3 * i], s.radius[i], s.density[i], s.material[i], next++);
      out.mass.back() = s.mass[i];
    }
  return out;
}

ParticleSet randomBed(const GranularBedParams& p, GranularBedReport& rep,
                      const ProgressCallback& progress) {
  auto clock = std::chrono::steady_clock::now();
  // A settled bed compacts from the loose fraction to ~0.62: fill higher so that it still
  // reaches the surface afterwards (the bowl's wall continues as a cylinder above its rim).
  Container c = p.container;
  if (p.settle) {
    const double depth = c.surfaceHeight - c.floorHeight();
    c.surfaceHeight +=
        (0.64 / std::min(p.packingFraction, 0.6) - 1.0) * depth + 2.0 * p.sizes.largest();
  }
  Random rng(p.seed);
  const double target = p.packingFraction * c.fillVolume(kWallDepletion * p.sizes.moment(1));
  std::vector<double> radii;
  double volume = 0.0;
  const std::int64_t cap = p.settle ? 2 * p.maxParticles : p.maxParticles;
  while (volume < target) {
    if (static_cast<std::int64_t>(radii.size()) >= cap)
      checkCap(static_cast<double>(radii.size()) + 1.0, cap);
    radii.push_back(p.sizes.sample(rng));
    volume += sphereVolume(radii.back());
  }
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
  endStage(rep, "placement", clock);
  const double placeShare = p.settle ? 0.2 : 1.0;
  // A fill that settles keeps small overlaps (the DEM removes them) and grows faster.
  rep.relaxationIterations =
      relaxOverlaps(out, p, c, p.sizes.largest(), true, subRange(progress, 0.0, placeShare),
                    p.settle ? kLooseOverlap : 0.0, p.settle ? kLooseGrowthSweeps : kGrowthSweeps);
  endStage(rep, "relaxation", clock);
  if (!p.settle)
    return out;
  ParticleSet settled = settleBed(out, p, c, rep, subRange(progress, 0.2, 0.95));
  endStage(rep, "settling", clock);
  ParticleSet trimmed = trimToSurface(settled, p.container.surfaceHeight);
  if (static_cast<std::int64_t>(trimmed.size()) > p.maxParticles)
    checkCap(static_cast<double>(trimmed.size()), p.maxParticles);
  endStage(rep, "trim", clock);
  // Unloading leaves contacts overlapping by well under 1 % of a radius; remove those so the
  // bed is stress-free under any gravity and stiffness it is used with later.
  rep.finalRelaxationIterations = relaxOverlaps(trimmed, p, p.container, p.sizes.largest(), false,
                                                subRange(progress, 0.95, 1.0));
  endStage(rep, "final relaxation", clock);
  return trimmed;
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
  if (packing == Packing::RCP &&
      (!(packingFraction > 0.0) || packingFraction > kMaxRandomFraction)) {
    msg << "PackingFraction must be in (0, " << kMaxRandomFraction << "] for random placement (got "
        << packingFraction << "); denser beds come from settling with the DEM";
    throw InputError(msg.str());
  }
  if (maxRelaxationIterations <= 0)
    throw InputError("the relaxation sweep limit must be positive");
  if (packing == Packing::RCP && settle) {
    if (!(settlingGravity > 0.0) || !std::isfinite(settlingGravity)) {
      msg << "SettlingGravity must be positive (got " << settlingGravity << " m/s^2)";
      throw InputError(msg.str());
    }
    if (!(settlingFriction >= 0.0) || !std::isfinite(settlingFriction)) {
      msg << "SettlingFriction must be non-negative (got " << settlingFriction << ")";
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
  ParticleSet bed = params.packing == GranularBedParams::Packing::HCP
                        ? hcpBed(params, progress)
                        : randomBed(params, rep, progress);
  if (bed.size() == 0)
    throw InputError("the container holds no particle of the requested size");
  rep.particles = bed.size();
  rep.topHeight = std::numeric_limits<double>::lowest();
  for (std::size_t i = 0; i < bed.size(); ++i)
    rep.topHeight = std::max(rep.topHeight, bed.position[3 * i + 2] + bed.radius[i]);
  rep.bulkPackingFraction =
      measurePackingFraction(bed, params.container, 3.0 * params.sizes.largest(), 200000);
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

#include "analysis/ColumnCollapse.h"

#include "bed/GranularBed.h"
#include "common/Error.h"
#include "dem/DemSolver.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace craterkit {

namespace {
constexpr double kR = 0.01, kRho = 2500.0, kG = 9.81;

// Runs until the mean kinetic energy per grain stays below 1e-4 m g r for 0.1 s (or tMax),
// removing nothing. Returns the time spent.
double runToRest(DemSolver& solver, double tMax) {
  const double start = solver.time(), chunk = 0.02;
  const double m = solver.particles().mass[0];
  double quiet = 0.0;
  while (solver.time() - start < tMax) {
    solver.advanceTo(solver.time() + chunk);
    const DemDiagnostics d = solver.diagnostics();
    const double perGrain = (d.kineticEnergy + d.rotationalEnergy) / solver.particles().size();
    quiet = perGrain < 1e-4 * m * kG * kR ? quiet + chunk : 0.0;
    if (quiet >= 0.1)
      break;
  }
  return solver.time() - start;
}

ParticleSet keep(const ParticleSet& s, const std::vector<char>& mask) {
  ParticleSet out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (mask[i]) {
      out.add(&s.position[3 * i], s.radius[i], s.density[i], s.material[i], s.id[i]);
    }
  return out;
}

double radialDistance(const ParticleSet& s, std::size_t i) {
  return std::hypot(s.position[3 * i], s.position[3 * i + 1]);
}
} // namespace

double lubeRunout(double a) { return a < 1.7 ? 1.24 * a : 1.6 * std::sqrt(a); }

double depositEdgeRadius(const std::vector<double>& positions, const std::vector<double>& radii) {
  const std::size_t n = radii.size();
  if (n == 0 || positions.size() != 3 * n)
    throw InputError("deposit edge: no grains, or positions and radii of different lengths");
  double sum = 0.0, outer = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += radii[i];
    outer = std::max(outer, std::hypot(positions[3 * i], positions[3 * i + 1]));
  }
  const double w = 2.0 * sum / static_cast<double>(n), half = 0.5 * M_PI / (2.0 * std::sqrt(3.0));
  std::vector<double> cover(static_cast<std::size_t>(outer / w) + 2, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(std::hypot(positions[3 * i], positions[3 * i + 1]) / w);
    cover[k] += M_PI * radii[i] * radii[i];
  }
  std::size_t last = 0;
  for (std::size_t k = 0; k < cover.size(); ++k) {
    cover[k] /= M_PI * w * w * static_cast<double>(2 * k + 1); // the ring's area
    if (cover[k] >= half)
      last = k;
  }
  // The last ring is always empty, so the crossing lies between `last` and the ring after it.
  const double c0 = cover[last], c1 = cover[last + 1];
  return (static_cast<double>(last) + 0.5 + (c0 - half) / (c0 - c1)) * w;
}

ColumnCollapseResult runColumnCollapse(const ContactParams& contact, double aspectRatio,
                                       double radiusInGrains) {
  if (!(aspectRatio > 0.05 && aspectRatio < 50.0))
    throw InputError("column collapse: aspect ratio must be in (0.05, 50)");
  if (!(radiusInGrains >= 4.0 && radiusInGrains <= 200.0))
    throw InputError("column collapse: the column radius must be 4 to 200 grain radii");
  const double r0 = radiusInGrains * kR, h0 = aspectRatio * r0;
  // Pour a loose column 1.3 times as high as wanted into the cylinder (the floor at z = 0).
  GranularBedParams bp;
  bp.container.type = Container::Type::Box;
  bp.container.boxSize = {2.0 * r0, 2.0 * r0, 1.3 * h0 + 4.0 * kR};
  bp.sizes.radius = kR;
  bp.particleDensity = kRho;
  bp.settle = false;
  ParticleSet loose = generateGranularBed(bp);
  std::vector<char> inside(loose.size());
  for (std::size_t i = 0; i < loose.size(); ++i) {
    loose.position[3 * i + 2] += bp.container.boxSize[2]; // box beds stand on z = -height
    inside[i] = radialDistance(loose, i) < r0 - kR;
  }
  ParticleSet column = keep(loose, inside);

  DemParams p;
  p.contact = contact;
  const double fall = std::sqrt(2.0 * kG * 1.3 * h0);
  const StiffnessProposal k = proposeStiffness(kR, kRho, fall, 0.02, kG, 1.3 * h0, 30.0);
  p.contact.kN = k.kN;
  p.dt = k.dt;
  p.gravity.vector = {0, 0, -kG};
  p.walls.push_back(Wall::plane({0, 0, 0}, {0, 0, 1}));
  p.walls.push_back(Wall::cylinder({0, 0, 0}, {0, 0, 1}, r0));
  // Settle, cut the column at h0 (centres above h0 - r go), settle again.
  {
    DemSolver settle(column, p);
    runToRest(settle, 5.0);
    const ParticleSet& s = settle.particles();
    std::vector<char> below(s.size());
    for (std::size_t i = 0; i < s.size(); ++i)
      below[i] = s.position[3 * i + 2] < h0 - kR;
    column = keep(s, below);
    DemSolver again(column, p);
    runToRest(again, 2.0);
    column = again.particles();
  }
  std::fill(column.velocity.begin(), column.velocity.end(), 0.0);
  std::fill(column.angularVelocity.begin(), column.angularVelocity.end(), 0.0);
  ColumnCollapseResult out;
  out.particles = column.size();
  out.columnRadius = r0;
  for (std::size_t i = 0; i < column.size(); ++i)
    out.columnHeight = std::max(out.columnHeight, column.position[3 * i + 2] + kR);
  out.aspectRatio = out.columnHeight / r0;

  // Release: the cylinder is gone.
  p.walls.pop_back();
  DemSolver collapse(column, p);
  out.time = runToRest(collapse, 20.0);
  const ParticleSet& s = collapse.particles();
  std::vector<double> radial(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    radial[i] = radialDistance(s, i);
    out.finalHeight = std::max(out.finalHeight, s.position[3 * i + 2] + kR);
  }
  const std::size_t q = static_cast<std::size_t>(0.99 * static_cast<double>(radial.size() - 1));
  std::nth_element(radial.begin(), radial.begin() + static_cast<std::ptrdiff_t>(q), radial.end());
  out.radius99 = radial[q] + kR;
  out.finalRadius = depositEdgeRadius(s.position, s.radius);
  out.runout = (out.finalRadius - r0) / r0;
  return out;
}

} // namespace craterkit

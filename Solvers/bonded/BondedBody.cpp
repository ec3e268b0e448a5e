#include "bonded/BondedBody.h"

#include "common/CellList.h"
#include "common/Error.h"
#include "common/Random.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace craterkit {
namespace {

[[noreturn]] void refuse(const std::string& property, const std::string& what, double value) {
  std::ostringstream s;
  s << "BondedImpact: " << property << ' ' << what << ", got " << value;
  throw InputError(s.str());
}

void requirePositive(const char* property, double value) {
  if (!(value > 0.0) || !std::isfinite(value))
    refuse(property, "must be positive and finite", value);
}

double projectileVolume(const BondedImpactParams& p) {
  const double d = p.diameter;
  if (p.shape == ProjectileShape::Sphere)
    return M_PI / 6.0 * d * d * d;
  return M_PI / 4.0 * d * d * p.cylinderLengthRatio * d;
}

double plateVolume(const BondedImpactParams& p) {
  const double w = p.plateWidthRatio * p.diameter;
  return p.thicknessRatio * p.diameter * w * w;
}

double latticeSpacing(const BondedImpactParams& p) {
  if (p.spacing > 0.0)
    return p.spacing;
  return std::cbrt((projectileVolume(p) + plateVolume(p)) / p.particleCount);
}

// Gaussian deviates from the reproducible generator (std::normal_distribution is not).
double gaussian(Random& random) {
  const double u = random.uniformOpen(), w = random.uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * w);
}

void addSite(BondedSystem& s, double x, double y, double z, std::uint8_t body) {
  s.positions.insert(s.positions.end(), {x, y, z});
  s.body.push_back(body);
}

} // namespace

void BondedImpactParams::validate() const {
  requirePositive("Diameter", diameter);
  requirePositive("ThicknessRatio (t/D)", thicknessRatio);
  requirePositive("PlateWidthRatio", plateWidthRatio);
  if (shape == ProjectileShape::Cylinder)
    requirePositive("CylinderLengthRatio", cylinderLengthRatio);
  requirePositive("ProjectileDensity", projectileDensity);
  requirePositive("PlateDensity", plateDensity);
  if (!(speed >= 0.0) || !std::isfinite(speed))
    refuse("ImpactSpeed", "must not be negative", speed);
  if (!(angle >= 0.0 && angle <= 80.0))
    refuse("ImpactAngle", "must lie in [0, 80] degrees", angle);
  if (!(spacing >= 0.0) || !std::isfinite(spacing))
    refuse("Spacing", "must not be negative", spacing);
  if (spacing == 0.0)
    requirePositive("ParticleCount", particleCount);
  requirePositive("Epsilon", epsilon);
  requirePositive("Kappa", kappa);
  if (!(rCutOverSigma > ws2017::kTwoToOneSixth) || !std::isfinite(rCutOverSigma))
    refuse("CutoffRatio (r_cut/sigma)", "must exceed the bond length r_eq/sigma = 2^(1/6) = 1.1225",
           rCutOverSigma);
  if (!(referenceSigma >= 0.0) || !std::isfinite(referenceSigma))
    refuse("ReferenceSigma", "must not be negative", referenceSigma);
  if (!(temperature >= 0.0) || !std::isfinite(temperature))
    refuse("Temperature", "must not be negative", temperature);
  if (!(memoryLimit >= 0.0))
    refuse("MemoryLimit", "must not be negative", memoryLimit);
  const double a = latticeSpacing(*this);
  if (thicknessRatio * diameter < 0.5 * a)
    refuse("ThicknessRatio (t/D)", "gives a plate thinner than half a lattice spacing",
           thicknessRatio);
  if (diameter < a)
    refuse(spacing > 0.0 ? "Spacing" : "ParticleCount",
           "leaves less than one particle across the projectile",
           spacing > 0.0 ? spacing : particleCount);
}

double estimateBondedBytes(double particles) {
  // Per particle: set-up arrays (57 B), solver state x, v, f, m, body and list reference
  // (105 B), bond adjacency (~30 B), three bonds with their flags (~55 B), the pair lists in
  // blocks of eight (~100 B) and their staging while they are rebuilt (~120 B), the sparse
  // cell list (~85 B: sort buffers, each point's cell, each occupied cell's nine rows). Measured
  // at the headline size: 523 B with the dense cell list (~50 B), the process's own ~10 MB
  // included; the sparse one added 37 B to the peak of a window (2026-12-05). The lists' rebuild
  // trigger (~80 B: the positions at the build, its regions' cell list and their bounds). The
  // second position buffer the force pass drifts into (24 B).
  return 704.0 * particles;
}

void checkBondedMemory(double particles, double limit, const char* property) {
  if (!(particles < 4.0e9))
    refuse(property, "asks for more than 2^32 particles", particles);
  if (limit <= 0.0) {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    limit = pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page)
                                  : std::numeric_limits<double>::max();
  }
  const double bytes = estimateBondedBytes(particles);
  if (bytes > limit) {
    std::ostringstream s;
    s << "BondedImpact: " << property << " needs about " << bytes / 1e9 << " GB for " << particles
      << " particles, more than the " << limit / 1e9 << " GB available";
    throw InputError(s.str());
  }
}

void formBonds(BondedSystem& system) {
  const std::size_t n = system.size();
  const double rc = system.law.rCut, rc2 = rc * rc;
  CellList cells;
  cells.build(system.positions.data(), n, rc);
  system.bonds.clear();
  std::vector<BondedBond> mine;
  for (std::size_t i = 0; i < n; ++i) {
    const double* xi = &system.positions[3 * i];
    mine.clear();
    cells.forEachCandidate(xi, rc, [&](std::size_t j) {
      if (j <= i || system.body[j] != system.body[i])
        return;
      const double* xj = &system.positions[3 * j];
      const double dx = xj[0] - xi[0], dy = xj[1] - xi[1], dz = xj[2] - xi[2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < rc2)
        mine.push_back(
            {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), std::sqrt(r2)});
    });
    std::sort(mine.begin(), mine.end(),
              [](const BondedBond& a, const BondedBond& b) { return a.j < b.j; });
    system.bonds.insert(system.bonds.end(), mine.begin(), mine.end());
  }
}

void addBoltzmannJitter(BondedSystem& system, double temperature, std::uint64_t seed) {
  const std::size_t n = system.size();
  if (temperature <= 0.0 || n == 0)
    return;
  Random random(seed);
  std::vector<double> jitter(3 * n);
  std::array<std::array<double, 4>, 256> sums{}; // per body: momentum, mass
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = std::sqrt(temperature * system.law.epsilon / system.masses[i]);
    auto& s = sums[system.body[i]];
    for (int k = 0; k < 3; ++k) {
      jitter[3 * i + k] = sd * gaussian(random);
      s[k] += system.masses[i] * jitter[3 * i + k];
    }
    s[3] += system.masses[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = sums[system.body[i]];
    for (int k = 0; k < 3; ++k)
      system.velocities[3 * i + k] += jitter[3 * i + k] - s[k] / s[3];
  }
}

BondedSystem buildBondedBox(std::size_t nx, std::size_t ny, std::size_t nz, double spacing,
                            double density, const ws2017::Sizing& sizing) {
  const double count = static_cast<double>(nx) * static_cast<double>(ny) * nz;
  if (!(count > 0.0))
    refuse("BoxSize", "must hold at least one site", count);
  requirePositive("Spacing", spacing);
  requirePositive("Density", density);
  checkBondedMemory(count, 0.0, "BoxSize");
  BondedSystem s;
  s.law = ws2017::sizedLaw(sizing, spacing / ws2017::kTwoToOneSixth);
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        addSite(s, i * spacing, j * spacing, k * spacing, 0);
  const double mass = density * count * spacing * spacing * spacing;
  s.masses.assign(s.body.size(), ws2017::particleMass(mass, s.body.size()));
  s.velocities.assign(s.positions.size(), 0.0);
  formBonds(s);
  return s;
}

BondedSystem buildBondedImpact(const BondedImpactParams& p) {
  p.validate();
  const double a = latticeSpacing(p);
  const double volume = projectileVolume(p) + plateVolume(p);
  checkBondedMemory(1.1 * volume / (a * a * a) + 64.0, p.memoryLimit,
                    p.spacing > 0.0 ? "Spacing" : "ParticleCount");
  BondedSystem s;
  const double sigmaRef = p.referenceSigma > 0.0 ? p.referenceSigma : ws2017::headlineSigma();
  ws2017::Law reference{sigmaRef, p.epsilon, p.kappa, p.rCutOverSigma * sigmaRef};
  s.law = ws2017::sizedLaw(ws2017::sizingOf(reference), a / ws2017::kTwoToOneSixth);

  // Projectile on its own lattice through its centre, standing off by two cut-off lengths.
  const double r = 0.5 * p.diameter;
  const bool sphere = p.shape == ProjectileShape::Sphere;
  const double halfLength = sphere ? r : 0.5 * p.cylinderLengthRatio * p.diameter;
  const double theta = p.angle * M_PI / 180.0;
  const double standoff = halfLength + std::max(2.0 * s.law.rCut, a);
  const double cx = -standoff, cy = -standoff * std::tan(theta);
  const long reach = static_cast<long>(std::ceil(std::max(r, halfLength) / a)) + 1;
  for (long k = -reach; k <= reach; ++k)
    for (long j = -reach; j <= reach; ++j)
      for (long i = -reach; i <= reach; ++i) {
        const double dx = i * a, dy = j * a, dz = k * a;
        const double rr = dy * dy + dz * dz;
        const bool inside =
            sphere ? rr + dx * dx <= r * r : rr <= r * r && std::abs(dx) <= halfLength;
        if (inside)
          addSite(s, cx + dx, cy + dy, dz, 0);
      }
  const std::size_t nProjectile = s.body.size();

  // Plate: 0 <= x <= t, centred on the axis.
  const double t = p.thicknessRatio * p.diameter, w = p.plateWidthRatio * p.diameter;
  const long nt = std::max(1L, std::lround(t / a)), nw = std::max(1L, std::lround(w / a));
  for (long k = 0; k < nw; ++k)
    for (long j = 0; j < nw; ++j)
      for (long i = 0; i < nt; ++i)
        addSite(s, (i + 0.5) * a, (j - 0.5 * (nw - 1)) * a, (k - 0.5 * (nw - 1)) * a, 1);
  const std::size_t nPlate = s.body.size() - nProjectile;

  s.masses.resize(s.body.size());
  const double mp = ws2017::particleMass(p.projectileDensity * projectileVolume(p), nProjectile);
  const double mt = ws2017::particleMass(p.plateDensity * plateVolume(p), nPlate);
  for (std::size_t i = 0; i < s.body.size(); ++i)
    s.masses[i] = i < nProjectile ? mp : mt;
  s.velocities.assign(s.positions.size(), 0.0);
  for (std::size_t i = 0; i < nProjectile; ++i) {
    s.velocities[3 * i] = p.speed * std::cos(theta);
    s.velocities[3 * i + 1] = p.speed * std::sin(theta);
  }
  s.rearFace = t;
  s.impactSpeed = p.speed;
  formBonds(s);
  addBoltzmannJitter(s, p.temperature, p.seed);
  return s;
}

} // namespace craterkit

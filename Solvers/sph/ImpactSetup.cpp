#include "sph/ImpactSetup.h"

#include "common/Error.h"

#include <cmath>
#include <string>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

namespace craterkit {

namespace {
double referenceDensity(const EquationOfState& e) {
  if (e.model != EquationOfState::Model::IdealGas)
    return e.referenceDensity();
  throw InputError("SPHImpact: an ideal gas has no reference density to build a solid body from");
}

std::size_t physicalMemory() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(size)
                               : 0;
}
} // namespace

std::size_t sphBytesPerParticle(double kappa) {
  // State (≈ 22 doubles) three times (current, predictor, checkpoint copy), rates (≈ 17 doubles)
  // twice, and the neighbour list: 4 bytes per neighbour within 1.1 κ spacings.
  const double neighbours = 4.0 / 3.0 * M_PI * std::pow(1.1 * kappa, 3.0);
  return static_cast<std::size_t>(8.0 * (3 * 22 + 2 * 17) + 4.0 * neighbours + 64.0);
}

void SphImpactSetup::validate() const {
  auto positive = [](double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(std::string("SPHImpact: ") + what + " must be positive (got " +
                       std::to_string(v) + ")");
  };
  if (impactorRadius > 0.0)
    positive(impactorRadius, "ImpactorRadius");
  else
    positive(impactorMass, "ImpactorMass");
  if (impactorRadius < 0.0 || !std::isfinite(impactorRadius))
    throw InputError("SPHImpact: ImpactorRadius must not be negative (0: from the mass)");
  positive(impactSpeed, "ImpactSpeed");
  if (!(impactAngle >= 0.0 && impactAngle < 90.0))
    throw InputError("SPHImpact: ImpactAngle must be in [0, 90) degrees from the vertical (got " +
                     std::to_string(impactAngle) + ")");
  positive(targetRadius, "TargetRadius");
  if (!(targetPorosity < 1.0) || !std::isfinite(targetPorosity))
    throw InputError("SPHImpact: TargetPorosity must be below 1 (negative: the material's)");
  if (!(frictionAngle < 90.0) || !std::isfinite(frictionAngle))
    throw InputError(
        "SPHImpact: FrictionAngle must be below 90 degrees (negative: the material's)");
  if (!std::isfinite(cohesion))
    throw InputError("SPHImpact: Cohesion must be finite");
  if (!(surfaceGravity >= 0.0) || !std::isfinite(surfaceGravity))
    throw InputError("SPHImpact: SurfaceGravity must not be negative");
  if (particlesAcrossImpactor < 2 || particlesAcrossImpactor > 1000)
    throw InputError("SPHImpact: ParticlesAcrossImpactor must be in [2, 1000]");
  if (!(coarsening >= 1.0 && coarsening <= 100.0))
    throw InputError("SPHImpact: TargetCoarsening must be in [1, 100] (1: a uniform lattice; got " +
                     std::to_string(coarsening) + ")");
  if (coarsening > 1.0 && targetShape != Shape::Hemisphere)
    throw InputError("SPHImpact: TargetCoarsening above 1 needs the hemispherical target");
}

namespace {
// The graded target's shells beyond the lattice core: mid-radius, thickness (= spacing) and
// particle count of each, out to `outer`.
struct Shell {
  double mid, thickness;
  std::size_t count;
};
// A shell of thickness t holds points t apart over its hemisphere of radius `mid`.
Shell shellAt(double mid, double t) {
  return Shell{mid, t,
               std::max<std::size_t>(
                   1, static_cast<std::size_t>(std::lround(2.0 * M_PI * mid * mid / (t * t))))};
}
std::vector<Shell> gradedShells(double core, double dx, double coarsening, double outer) {
  std::vector<Shell> out;
  for (double r = core; r < outer;) {
    const double t = std::min(coarsening * dx, dx * std::max(1.0, r / core));
    out.push_back(shellAt(r + 0.5 * t, t));
    r += t;
  }
  return out;
}
// Refuses what the machine cannot hold before anything is allocated.
void checkMemory(const SphImpactSetup& setup, double R, double dx, double core, bool graded,
                 const std::vector<Shell>& shells) {
  const double volume = setup.targetShape == SphImpactSetup::Shape::Hemisphere
                            ? 2.0 / 3.0 * M_PI * R * R * R
                            : 4.0 * R * R * R;
  double estimate =
      volume / (dx * dx * dx) + 4.0 / 3.0 * M_PI * std::pow(0.5 * setup.particlesAcrossImpactor, 3);
  if (graded) {
    estimate = 2.0 / 3.0 * M_PI * core * core * core / (dx * dx * dx) +
               4.0 / 3.0 * M_PI * std::pow(0.5 * setup.particlesAcrossImpactor, 3);
    for (const Shell& sh : shells)
      estimate += static_cast<double>(sh.count);
  }
  const double need = estimate * static_cast<double>(sphBytesPerParticle(2.5));
  const double have = static_cast<double>(physicalMemory());
  if (estimate > 1.2e8 || (have > 0.0 && need > setup.memoryLimitFraction * have))
    throw InputError("SPHImpact: about " + std::to_string(static_cast<long long>(estimate)) +
                     " particles would need " + std::to_string(static_cast<long long>(need / 1e9)) +
                     " GB of memory (" + std::to_string(static_cast<long long>(have / 1e9)) +
                     " GB here): lower ParticlesAcrossImpactor or TargetRadius");
}

// The impactor: the lattice points within its radius a, moving at the impact speed and angle,
// its lowest particles half a spacing above z = 0.
void addImpactor(SphImpactProblem& out, const SphImpactSetup& setup, double a, double dx,
                 double mass, double rhoImp) {
  const double th = setup.impactAngle * M_PI / 180.0;
  const double dir[3] = {std::sin(th), 0.0, -std::cos(th)};
  const double gap = 0.5 * dx; // the impactor's lowest particles sit half a spacing above z = 0
  const double centre[3] = {-dir[0] * (a + gap), 0.0, -dir[2] * (a + gap)};
  const double vel[3] = {setup.impactSpeed * dir[0], 0.0, setup.impactSpeed * dir[2]};
  const int n = static_cast<int>(std::ceil(a / dx)) + 1;
  std::vector<double> pts;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        const double p[3] = {(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= a * a)
          pts.insert(pts.end(), p, p + 3);
      }
  const std::size_t ni = pts.size() / 3;
  if (ni == 0)
    throw InputError("SPHImpact: the impactor has no particles");
  for (std::size_t q = 0; q < ni; ++q) {
    const double x[3] = {centre[0] + pts[3 * q], centre[1] + pts[3 * q + 1],
                         centre[2] + pts[3 * q + 2]};
    out.state.add(x, vel, mass / static_cast<double>(ni), rhoImp, 0.0, 0);
  }
  out.impactorParticles = ni;
}

// The graded target: the lattice core, then the shells (the container's last).
void addGradedTarget(SphImpactProblem& out, const Material& tgt, double core, double dx,
                     const std::vector<Shell>& shells, std::size_t targetShells) {
  const double mt = out.targetBulkDensity * dx * dx * dx, rest[3] = {0, 0, 0};
  // The lattice core, then the shells: points spread evenly over each lower hemisphere
  // (uniform in z is uniform in area), turned by the golden angle from point to point and by
  // a different angle on every shell so that neighbouring shells do not line up.
  const int mc = static_cast<int>(std::ceil(core / dx));
  for (int k = 0; k < mc; ++k)
    for (int j = -mc; j < mc; ++j)
      for (int i = -mc; i < mc; ++i) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, -(k + 0.5) * dx};
        if (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] > core * core)
          continue;
        out.state.add(x, rest, mt, out.targetBulkDensity, 0.0, 1);
        out.state.alpha.back() = tgt.distention;
      }
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  double inner = core;
  for (std::size_t k = 0; k < shells.size(); ++k) {
    const Shell& sh = shells[k];
    const double outer = inner + sh.thickness;
    const int mat = k < targetShells ? 1 : 2; // the container's shells last
    const double volumeShare = 2.0 / 3.0 * M_PI * (outer * outer * outer - inner * inner * inner) /
                               static_cast<double>(sh.count);
    const double turn = golden * 7.0 * static_cast<double>(k);
    for (std::size_t q = 0; q < sh.count; ++q) {
      const double z = -(static_cast<double>(q) + 0.5) / static_cast<double>(sh.count);
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z)),
                   phi = turn + golden * static_cast<double>(q);
      const double x[3] = {sh.mid * rho * std::cos(phi), sh.mid * rho * std::sin(phi), sh.mid * z};
      out.state.add(x, rest, out.targetBulkDensity * volumeShare, out.targetBulkDensity, 0.0, mat);
      out.state.alpha.back() = tgt.distention;
      out.containerParticles += mat == 2 ? 1 : 0;
    }
    inner = outer;
  }
}

// The uniform target on the lattice, then its container (material 2), if any.
void addLatticeTarget(SphImpactProblem& out, const SphImpactSetup& setup, const Material& tgt,
                      double R, double dx, bool graded) {
  const bool hemisphere = setup.targetShape == SphImpactSetup::Shape::Hemisphere;
  const double mt = out.targetBulkDensity * dx * dx * dx, rest[3] = {0, 0, 0};
  // Inside the target (0), in its container shell (1), or outside both (-1).
  const double wall = 3.0 * dx, Rw = R + wall;
  auto where = [&](const double* x) {
    if (hemisphere) {
      const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
      return r2 <= R * R ? 0 : (setup.container && r2 <= Rw * Rw ? 1 : -1);
    }
    if (std::fabs(x[0]) <= R && std::fabs(x[1]) <= R && x[2] >= -R)
      return 0;
    return setup.container && std::fabs(x[0]) <= Rw && std::fabs(x[1]) <= Rw && x[2] >= -Rw ? 1
                                                                                            : -1;
  };
  const int m = graded ? 0 : static_cast<int>(std::ceil((setup.container ? Rw : R) / dx));
  for (int pass = 0; pass < 2; ++pass) // the target first, then its container
    for (int k = 0; k < m; ++k)
      for (int j = -m; j < m; ++j)
        for (int i = -m; i < m; ++i) {
          const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, -(k + 0.5) * dx};
          if (where(x) != pass)
            continue;
          out.state.add(x, rest, mt, out.targetBulkDensity, 0.0, 1 + pass);
          out.state.alpha.back() = tgt.distention;
          out.containerParticles += static_cast<std::size_t>(pass);
        }
}
} // namespace

SphImpactProblem buildImpact(const SphImpactSetup& setup) {
  setup.validate();
  Material imp = findMaterial(setup.materialDirectory, setup.impactorMaterial);
  Material tgt = findMaterial(setup.materialDirectory, setup.targetMaterial);
  const double rhoImp = referenceDensity(imp.eos), rhoMatrix = referenceDensity(tgt.eos);
  if (setup.targetPorosity >= 0.0)
    tgt.distention = 1.0 / (1.0 - setup.targetPorosity);
  if (setup.frictionAngle >= 0.0)
    tgt.frictionAngle = setup.frictionAngle;
  if (setup.cohesion >= 0.0)
    tgt.cohesion = setup.cohesion;
  SphImpactProblem out;
  const double a = setup.impactorRadius > 0.0
                       ? setup.impactorRadius
                       : std::cbrt(3.0 * setup.impactorMass / (4.0 * M_PI * rhoImp));
  const double mass =
      setup.impactorRadius > 0.0 ? 4.0 / 3.0 * M_PI * a * a * a * rhoImp : setup.impactorMass;
  const double dx = 2.0 * a / setup.particlesAcrossImpactor, R = setup.targetRadius;
  if (R < 3.0 * a)
    throw InputError("SPHImpact: TargetRadius must be at least three impactor radii");
  out.spacing = dx;
  out.impactorRadius = a;
  out.targetBulkDensity = rhoMatrix / tgt.distention;

  // Graded: the lattice core within four impactor radii, shells beyond (to the container's
  // outer face when there is one).
  const bool graded = setup.coarsening > 1.0;
  const double core = std::min(R, 4.0 * a);
  std::vector<Shell> shells;
  std::size_t targetShells = 0; // the rest are the container's
  if (graded) {
    shells = gradedShells(core, dx, setup.coarsening, R);
    targetShells = shells.size();
    if (setup.container) {
      // Three spacings of container at the spacing the target ends with.
      const double t = shells.empty() ? dx : shells.back().thickness,
                   start = shells.empty() ? core : shells.back().mid + 0.5 * t;
      for (int k = 0; k < 3; ++k)
        shells.push_back(shellAt(start + (k + 0.5) * t, t));
    }
  }
  checkMemory(setup, R, dx, core, graded, shells);
  addImpactor(out, setup, a, dx, mass, rhoImp);
  if (graded)
    addGradedTarget(out, tgt, core, dx, shells, targetShells);
  addLatticeTarget(out, setup, tgt, R, dx, graded);
  out.params.materials = {imp, tgt};
  if (setup.container) {
    Material shell = tgt;
    shell.name = tgt.name + " (container)";
    shell.rigid = true;
    out.params.materials.push_back(shell);
    // The container must take up the shock that reaches it: with the artificial viscosity
    // between wall and target (as before 2026-12-05) the outer layer's downward momentum at
    // 0.3 ms is −0.06 of the impactor's in SphImpact.ContainerTakesUpTheMomentumThatReachesIt,
    // without it +0.14 (the free target: 0.38). The default 0 (SphParams::wallViscosity) is for
    // material sliding along a wall; a viscosity on the approach normal to the wall only would
    // serve both (not done).
    out.params.wallViscosity = 1.0;
  }
  out.params.gravity[2] = -setup.surfaceGravity;
  // The late-stage switch keeps the target's weight (sph/Overburden.h): surface at z = 0.
  out.params.overburdenDensity = tgt.eos.referenceDensity() / tgt.distention;
  out.params.overburdenSurface = 0.0;
  return out;
}

void checkImpactTimes(double endTime, double outputInterval, double minTimeStep) {
  if (!(endTime >= 0.0) || !std::isfinite(endTime))
    throw InputError("EndTime must be a non-negative time in s");
  if (!(outputInterval > 0.0))
    throw InputError("OutputInterval must be positive");
  if (!(minTimeStep >= 0.0))
    throw InputError("MinTimeStep must not be negative");
}

std::vector<NamedValue> impactFields(const SphSolver& solver, const SphImpactSetup& setup,
                                     double spacing, std::size_t containerParticles) {
  double P[3], L[3];
  solver.totalMomentum(P);
  solver.totalAngularMomentum(L);
  auto number = &NamedValue::number;
  auto text = &NamedValue::string;
  const bool halfSpace = setup.targetShape == SphImpactSetup::Shape::HalfSpace;
  return {number("Time", solver.time()),
          number("Step", static_cast<double>(solver.steps())),
          number("TimeStep", solver.stableStep()),
          NamedValue::vector("Gravity", {0.0, 0.0, -setup.surfaceGravity}),
          NamedValue::vector("TotalMomentum", {P[0], P[1], P[2]}),
          NamedValue::vector("TotalAngularMomentum", {L[0], L[1], L[2]}),
          number("KineticEnergy", solver.kineticEnergy()),
          number("InternalEnergyTotal", solver.internalEnergy()),
          number("GravitationalEnergy", solver.potentialEnergy()),
          number("TotalEnergy", solver.totalEnergy()),
          number("ParticleSpacing", spacing),
          number("SurfaceHeight", 0.0),
          number("TargetRadius", setup.targetRadius),
          number("TargetCoarsening", setup.coarsening),
          number("TargetContainer", setup.container ? 1.0 : 0.0),
          number("ContainerParticles", static_cast<double>(containerParticles)),
          text("TargetShape", halfSpace ? "HalfSpace" : "Hemisphere"),
          number("ImpactSpeed", setup.impactSpeed),
          number("ImpactAngle", setup.impactAngle),
          text("ImpactorMaterial", setup.impactorMaterial),
          number("ImpactorMass", setup.impactorMass),
          text("TargetMaterial", setup.targetMaterial),
          number("FrictionAngle", setup.frictionAngle),
          number("LateStageSoundSpeed", solver.lateStageSoundSpeed()),
          number("LateStagePoissonRatio", solver.params().lateStagePoissonRatio),
          number("StopImpactorAtLateStage",
                 solver.params().lateStageStopMaterial == kImpactorMaterial ? 1.0 : 0.0)};
}

std::vector<SphImpactArray> impactArrays(const SphSolver& solver, std::size_t count) {
  const SphState& s = solver.state();
  auto head = [count](const char* name, const std::vector<double>& v, int components) {
    const auto end = v.begin() + static_cast<std::ptrdiff_t>(count * components);
    return SphImpactArray{name, components, std::vector<double>(v.begin(), end)};
  };
  std::vector<double> stress(6 * count);
  for (std::size_t i = 0; i < count; ++i) {
    const double* S = &s.S[6 * i];
    double* o = &stress[6 * i];
    o[0] = S[0], o[1] = S[1], o[2] = S[2], o[3] = S[3], o[4] = S[5], o[5] = S[4];
  }
  return {head("Velocity", s.v, 3),
          head("Density", s.rho, 1),
          head("Mass", s.mass, 1),
          head("Pressure", solver.pressure(), 1),
          head("InternalEnergy", s.u, 1),
          head("Distention", s.alpha, 1),
          head("Damage", s.damage, 1),
          head("SmoothingLength", s.h, 1),
          head("SoundSpeed", solver.soundSpeed(), 1),
          SphImpactArray{"DeviatoricStress", 6, std::move(stress)}};
}

} // namespace craterkit

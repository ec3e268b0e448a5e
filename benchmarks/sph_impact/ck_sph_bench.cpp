// The SCI-like SPH impact without VTK: builds the default problem of the SPHImpact source,
// runs it to a given time and prints throughput (particle-steps per second) and the
// conservation figures.
//   ck_sph_bench [END_TIME [PARTICLES_ACROSS_IMPACTOR [TARGET_RADIUS]]]
//   ck_sph_bench pysph-impact3d [STEPS [KAPPA [wendland|cubic]]]
// Environment: CK_POROSITY (target porosity), CK_IMPACTOR (material name), CK_SKIN
// (neighbour-list skin in units of h), CK_GRAVITY (m/s²), CK_CONTAINER (1: the rigid
// container), CK_LATE_STAGE ("TIME SOUND_SPEED": the late-stage scheme). The SCI example's
// SPH stage at its ctest size: CK_GRAVITY=1000 CK_CONTAINER=1 CK_LATE_STAGE="1e-3 317"
// ck_sph_bench 0.02 2 0.8.
// The graded SCI target at Ryugu's gravity (the slow validation's SPH stage) adds
// CK_COARSENING (SPHImpact's TargetCoarsening) and CK_DOMAIN_RADIUS (m): CK_GRAVITY=1.5e-4
// CK_CONTAINER=1 CK_LATE_STAGE="1e-3 0.46637" CK_COARSENING=15 CK_DOMAIN_RADIUS=29
// ck_sph_bench 196 2 11.6. A window of it: CK_RESUME (a checkpoint of that set-up to start
// from), CK_STEPS (stop after this many steps), CK_SAVE (write a checkpoint there at the end
// and every CK_SAVE_EVERY steps), CK_TRACE (a file: one line per step with what set its size).
// CK_BLOCK_STEPS=L: individual power-of-two steps in the late stage, up to 2^L times the smallest
// (SphParams::blockStepLevels; a step is then a block cycle, and the smallest steps and particle
// updates are printed at the end). CK_COHESION (Pa, default 0): the target's Drucker–Prager
// cohesion (docs/validation_history.md, "Depth and the SPH resolution", point 9).
#include "sph/ImpactSetup.h"
#include "sph/SphRun.h"
#include "sph/SphSolver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <omp.h>
#include <string>

using namespace craterkit;

namespace {
// PySPH's solid_mech/impact3d.py: a steel sphere (r 5 mm) at 3.1 km/s into an aluminium plate
// 2 mm thick, 40 mm wide, on the same lattice (dx 0.5 mm, 36,962 particles), the same materials
// (stiffened gas, shear modulus and von Mises yield as given there), XSPH 0.5, artificial
// viscosity α 1, β 1.5, Δt 1 ns. PySPH's Gaussian kernel with h = 1.3 dx reaches 3h = 3.9 dx;
// CraterKit uses the Wendland C2 kernel with the same reach (κ = 3.9), so both codes sum over
// the same neighbours. Prints particle-steps per second.
int pysphImpact3d(int steps, double kappa, bool wendland) {
  const double dx = 0.0005, r = 0.005;
  auto material = [](const char* name, double rho0, double c0, double gamma, double G, double Y) {
    Material m;
    m.name = name;
    m.eos.model = EquationOfState::Model::StiffenedGas;
    m.eos.stiffRho0 = rho0, m.eos.stiffC0 = c0, m.eos.stiffGamma = gamma;
    m.shearModulus = G;
    m.strength = Material::Strength::VonMises;
    m.yieldStress = Y;
    return m;
  };
  SphParams par;
  par.materials = {material("aluminium", 2785.0, 5328.0, 2.0, 2.76e7, 0.3e6),
                   material("steel", 7900.0, 4600.0, 2.17, 8.53e7, 0.979e6)};
  par.kernel = wendland ? SphParams::Kernel::WendlandC2 : SphParams::Kernel::CubicSpline;
  par.kappa = kappa;
  par.alpha = 1.0, par.beta = 1.5, par.xsph = 0.5;
  SphState s;
  const double rest[3] = {0, 0, 0}, vs[3] = {3100.0, 0, 0};
  for (int i = 0; 0.0 + i * dx < 0.002 + dx - 1e-12; ++i)
    for (int j = 0; - 0.02 + j * dx < 0.02 + dx - 1e-12; ++j)
      for (int k = 0; - 0.02 + k * dx < 0.02 + dx - 1e-12; ++k) {
        const double x[3] = {i * dx, -0.02 + j * dx, -0.02 + k * dx};
        s.add(x, rest, dx * dx * dx * 2785.0, 2785.0, 0.0, 0);
      }
  const std::size_t plate = s.size();
  for (int i = 0; - r + i * dx < r + 1e-6; ++i)
    for (int j = 0; - r + j * dx < r + 1e-6; ++j)
      for (int k = 0; - r + k * dx < r + 1e-6; ++k) {
        const double x[3] = {-r + i * dx, -r + j * dx, -r + k * dx};
        if (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] > r * r)
          continue;
        const double y[3] = {x[0] - (r + 2 * dx), x[1], x[2]};
        s.add(y, vs, dx * dx * dx * 7900.0, 7900.0, 0.0, 1);
      }
  std::printf("PySPH impact3d problem: %zu plate + %zu projectile = %zu particles, %s kernel, "
              "reach %.2f dx, %d threads\n",
              plate, s.size() - plate, s.size(), wendland ? "WendlandC2" : "CubicSpline", kappa,
              omp_get_max_threads());
  const auto t0 = std::chrono::steady_clock::now();
  SphSolver solver(s, par);
  for (int i = 0; i < steps; ++i)
    solver.step(1e-9);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("CraterKit: %d steps of 1 ns in %.2f s: %.4g particle-steps/s\n", steps, wall,
              static_cast<double>(s.size()) * steps / wall);
  double P[3]; // the end state, to compare two builds' runs
  solver.totalMomentum(P);
  std::printf("%zu neighbour-list builds; end: E = %.12e J, P = (%.9e, %.9e, %.9e) kg m/s\n",
              solver.neighbourBuilds(), solver.totalEnergy(), P[0], P[1], P[2]);
  return 0;
}
} // namespace

// One line per step: step, t, dt, tries, list builds; the Euler–Heun error, its particle and
// whether the error control held the next step back; the Courant and force limits of the new
// state and their particles (each: index, material, h, speed, distance from the impact point).
void traceStep(std::FILE* f, const SphSolver& solver, double dt, std::size_t builds) {
  const SphState& s = solver.state();
  const SphSolver::StepRecord& r = solver.lastStep();
  const SphSolver::Limits l = solver.limits();
  auto who = [&](std::size_t i) {
    const double* v = &s.v[3 * i];
    const double* x = &s.x[3 * i];
    std::fprintf(f, " %zu %d %.4g %.4g %.4g", i, s.material[i], s.h[i],
                 std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]),
                 std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
  };
  std::fprintf(f, "%zu %.6e %.4e %d %zu %.3e %d", solver.steps(), solver.time(), dt, r.attempts,
               builds, r.error, r.errorCapped ? 1 : 0);
  who(r.worst);
  std::fprintf(f, " %.4e", l.courant);
  who(l.courantParticle);
  std::fprintf(f, " %.4e", l.force);
  who(l.forceParticle);
  std::fprintf(f, "\n");
}

// The particles' own stable steps in power-of-two bins of the smallest, by material, and the
// rate evaluations per unit time individual (block) steps would need against one step for all.
void stepBins(const SphSolver& solver) {
  const std::vector<double> dt = solver.particleSteps();
  const SphState& s = solver.state();
  double dmin = INFINITY;
  for (double d : dt)
    dmin = std::min(dmin, d);
  std::size_t count[3][40] = {};
  double work = 0.0;
  for (std::size_t i = 0; i < dt.size(); ++i) {
    const int b = std::isfinite(dt[i])
                      ? std::min(39, static_cast<int>(std::floor(std::log2(dt[i] / dmin))))
                      : 39;
    ++count[std::min(2, s.material[i])][b];
    work += std::ldexp(1.0, -b);
  }
  std::printf("smallest particle step %.4g s; bin k holds steps in [2^k, 2^(k+1)) of it\n", dmin);
  for (int b = 0; b < 40; ++b)
    if (count[0][b] + count[1][b] + count[2][b] > 0)
      std::printf("bin %2d: impactor %zu, target %zu, container %zu\n", b, count[0][b], count[1][b],
                  count[2][b]);
  std::printf("block steps: %.4f of the particle updates of one step for all\n",
              work / static_cast<double>(dt.size()));
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "pysph-impact3d")
    return pysphImpact3d(argc > 2 ? std::atoi(argv[2]) : 100, argc > 3 ? std::atof(argv[3]) : 3.9,
                         argc > 4 ? std::string(argv[4]) != "cubic" : true);
  SphImpactSetup setup;
  setup.materialDirectory = std::string(CRATERKIT_SOURCE_DIR) + "/data/materials";
  const double end = argc > 1 ? std::atof(argv[1]) : 2e-4;
  if (argc > 2)
    setup.particlesAcrossImpactor = std::atoi(argv[2]);
  if (argc > 3)
    setup.targetRadius = std::atof(argv[3]);
  if (const char* e = std::getenv("CK_POROSITY"))
    setup.targetPorosity = std::atof(e);
  if (const char* e = std::getenv("CK_IMPACTOR"))
    setup.impactorMaterial = e;
  if (const char* e = std::getenv("CK_GRAVITY"))
    setup.surfaceGravity = std::atof(e);
  if (const char* e = std::getenv("CK_CONTAINER"))
    setup.container = std::atoi(e) != 0;
  if (const char* e = std::getenv("CK_COARSENING"))
    setup.coarsening = std::atof(e);
  setup.frictionAngle = 30.0;
  setup.cohesion = 0.0;
  // The target's cohesion (Pa). A checkpoint holds no material constants: a resume takes it
  // from here. The regolith has no Grady–Kipp flaws, so its damage stays 0 and keeps it whole.
  if (const char* e = std::getenv("CK_COHESION")) {
    char* end = nullptr;
    setup.cohesion = std::strtod(e, &end);
    if (end == e || *end != '\0' || !(setup.cohesion >= 0.0) || !std::isfinite(setup.cohesion)) {
      std::fprintf(stderr, "CK_COHESION must be a finite cohesion in Pa, 0 or more (got '%s')\n",
                   e);
      return 1;
    }
  }
  SphImpactProblem prob = buildImpact(setup);
  if (const char* e = std::getenv("CK_SKIN"))
    prob.params.skin = std::atof(e);
  if (const char* e =
          std::getenv("CK_LATE_STAGE")) { // "TIME SOUND_SPEED", as SPHImpact's LateStage*
    prob.params.lateStageTime = std::atof(e);
    if (const char* c = std::strchr(e, ' '))
      prob.params.lateStageSoundSpeed = std::atof(c + 1);
  }
  if (const char* e = std::getenv("CK_DOMAIN_RADIUS"))
    prob.params.domainRadius = std::atof(e);
  if (const char* e = std::getenv("CK_BLOCK_STEPS"))
    prob.params.blockStepLevels = std::atoi(e);
  const char* resume = std::getenv("CK_RESUME");
  const char* save = std::getenv("CK_SAVE");
  const long long saveEvery =
      std::getenv("CK_SAVE_EVERY") ? std::atoll(std::getenv("CK_SAVE_EVERY")) : 0;
  const long long maxSteps = std::getenv("CK_STEPS") ? std::atoll(std::getenv("CK_STEPS")) : -1;
  std::FILE* trace = std::getenv("CK_TRACE") ? std::fopen(std::getenv("CK_TRACE"), "a") : nullptr;

  double t0Resume = 0.0, nextStep = 0.0;
  std::size_t steps0 = 0;
  if (resume)
    prob.state = readSphCheckpoint(resume, t0Resume, steps0, nextStep);
  SphSolver solver(prob.state, prob.params, SphClock{t0Resume, steps0, nextStep});
  const std::size_t n = prob.state.size();
  std::printf(
      "SCI-like SPH: %zu particles (%zu impactor), dx = %.4g m, %d threads, to t = %.3g s\n", n,
      prob.impactorParticles, prob.spacing, omp_get_max_threads(), end);
  if (setup.cohesion > 0.0)
    std::printf("target cohesion %.4g Pa\n", setup.cohesion);
  double P0[3];
  solver.totalMomentum(P0);
  const double E0 = solver.totalEnergy();
  const auto t0 = std::chrono::steady_clock::now();
  double nextReport = 0.0;
  if (std::getenv("CK_STEP_BINS")) // how individual power-of-two steps would share the work
    stepBins(solver);
  const std::size_t builds0 = solver.neighbourBuilds();
  while (solver.time() < end &&
         (maxSteps < 0 || solver.steps() - steps0 < static_cast<std::size_t>(maxSteps))) {
    const std::size_t before = solver.neighbourBuilds();
    const double dt = solver.step(std::min(solver.stableStep(), end - solver.time()));
    if (trace)
      traceStep(trace, solver, dt, solver.neighbourBuilds() - before);
    if (save && saveEvery > 0 && (solver.steps() - steps0) % saveEvery == 0)
      writeSphCheckpoint(save, solver.state(), solver.time(), solver.steps(), solver.stableStep());
    if (solver.time() >= nextReport || solver.time() >= end) {
      double P[3], vmax = 0.0, pmax = 0.0, amin = 10.0;
      solver.totalMomentum(P);
      const SphState& s = solver.state();
      for (std::size_t i = 0; i < n; ++i) {
        vmax = std::max(vmax, std::sqrt(s.v[3 * i] * s.v[3 * i] + s.v[3 * i + 1] * s.v[3 * i + 1] +
                                        s.v[3 * i + 2] * s.v[3 * i + 2]));
        pmax = std::max(pmax, solver.pressure()[i]);
        if (s.material[i] == 1)
          amin = std::min(amin, s.alpha[i]);
      }
      std::printf("t = %.3e s, %zu steps, dt %.2e, vmax %.0f m/s, pmax %.3g Pa, min distention "
                  "%.3f, dP/P0 = %.1e, dE/E0 = %.2e\n",
                  solver.time(), solver.steps(), solver.stableStep(), vmax, pmax, amin,
                  std::abs(P[2] - P0[2]) / std::abs(P0[2]), (solver.totalEnergy() - E0) / E0);
      // Where the impactor (the first prob.impactorParticles) is: what sets the crater's
      // depth in the graded Ryugu stage (docs/validation_history.md, "Depth and the SPH
      // resolution").
      double mi = 0.0, zc = 0.0, vc = 0.0;
      for (std::size_t i = 0; i < prob.impactorParticles; ++i)
        mi += s.mass[i], zc += s.mass[i] * s.x[3 * i + 2], vc += s.mass[i] * s.v[3 * i + 2];
      std::printf("  impactor's centre of mass at z = %.4g m, moving at %.3g m/s along z\n",
                  zc / mi, vc / mi);
      std::fflush(stdout);
      nextReport += end / 10.0;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t taken = solver.steps() - steps0;
  std::printf("%zu steps in %.2f s: %.3g particle-steps/s (%zu neighbour-list builds)\n", taken,
              wall, static_cast<double>(n) * taken / wall, solver.neighbourBuilds() - builds0);
  {
    double P[3];
    solver.totalMomentum(P);
    std::printf("end: t = %.9e s, %zu steps, E = %.12e J, P = (%.9e, %.9e, %.9e) kg m/s\n",
                solver.time(), solver.steps(), solver.totalEnergy(), P[0], P[1], P[2]);
  }
  if (prob.params.blockStepLevels > 0) {
    const SphSolver::BlockStats& b = solver.blockStats();
    std::printf("block steps: %zu smallest steps, %zu particle updates (%.4f of one step for all "
                "at each), %zu woken, %zu overruns, %zu partial list rebuilds\n",
                b.substeps, b.updates,
                b.substeps ? static_cast<double>(b.updates) / (static_cast<double>(n) * b.substeps)
                           : 0.0,
                b.wakes, b.overruns, solver.neighbourRefreshes());
  }
  if (save)
    writeSphCheckpoint(save, solver.state(), solver.time(), solver.steps(), solver.stableStep());
  if (trace)
    std::fclose(trace);
}

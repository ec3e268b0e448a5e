// The bonded model's shock heating beyond the paper (bonded/ShockViscosity.h): a planar
// aluminium plate-on-plate impact at 6.7 km/s against aluminium's Hugoniot and the waste heat
// left after release, each pulse's energy bookkeeping, total energy and momentum through an
// impact, the paper's model (Dissipation None) unchanged bit for bit, and bad parameters refused
// by name. Each test prints its figures. docs/physics.md §5.1 derives the reference figures.
#include "bonded/BondedBody.h"
#include "bonded/BondedReport.h"
#include "bonded/BondedSolver.h"
#include "bonded/ShockViscosity.h"
#include "bonded/WatsonSteinhauser2017.h"
#include "common/Error.h"
#include "common/Random.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace craterkit;

namespace {

// Aluminium 6061-T6: the linear U_s–u_p fit of Marsh (1980, LASL Shock Hugoniot Data) with the
// Grüneisen parameter of the Mie–Grüneisen form (docs/physics.md §5.1).
struct Hugoniot {
  double rho0 = 2703.0, c0 = 5350.0, s = 1.34, gamma0 = 2.0;
  double shockSpeed(double up) const { return c0 + s * up; }
  double pressure(double up) const { return rho0 * shockSpeed(up) * up; }
  // p_H(V) on the Hugoniot, η = 1 − V/V0 (valid for V < V0/(1 − 1/s); continued past V0).
  double pressureAt(double v) const {
    const double eta = 1.0 - v * rho0;
    return rho0 * c0 * c0 * eta / ((1.0 - s * eta) * (1.0 - s * eta));
  }
  // The specific internal energy (J/kg) left when the state shocked to particle velocity up is
  // released along its isentrope to zero pressure: e_H = ½ p_H (V0 − V_H) = up²/2 less the work
  // ∫ p dV of the release, with p = p_H(V) + (Γ0/V0)(e − e_H(V)) (ρΓ = ρ0Γ0), integrated by RK4
  // in V from V_H until p = 0.
  double wasteHeat(double up) const {
    const double v0 = 1.0 / rho0, us = shockSpeed(up), vH = v0 * (1.0 - up / us);
    auto eH = [&](double v) { return 0.5 * pressureAt(v) * (v0 - v); };
    auto p = [&](double v, double e) { return pressureAt(v) + gamma0 / v0 * (e - eH(v)); };
    const int steps = 20000;
    const double h = 2.0 * (v0 - vH) / steps;
    double v = vH, e = 0.5 * up * up;
    for (int k = 0; k < 2 * steps; ++k) {
      const double k1 = -p(v, e), k2 = -p(v + h / 2, e + h / 2 * k1);
      const double k3 = -p(v + h / 2, e + h / 2 * k2), k4 = -p(v + h, e + h * k3);
      const double eNext = e + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      const double pNow = p(v, e), pNext = p(v + h, eNext);
      if (pNext <= 0.0)
        return e + (eNext - e) * pNow / (pNow - pNext);
      v += h, e = eNext;
    }
    return NAN;
  }
};

// The paper's best fit (ε = 0.01 J, κ = 4.56e6 N/m, r_cut = 1.5σ) at the headline σ.
ws2017::Sizing headlineSizing() {
  const double s = ws2017::headlineSigma();
  return ws2017::sizingOf({s, ws2017::kHeadlineEpsilon, ws2017::kHeadlineKappa, 1.5 * s});
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

BondedSolverParams shockViscosity() {
  BondedSolverParams p;
  p.dissipation = BondedDissipation::ShockViscosity;
  return p;
}

// A flyer plate of `thick` × w × w lattice sites at v0 along x onto a target `targetThick` × w
// × w at rest (sites i + j n + k n w of each plate, the target first), the paper's law at its
// headline spacing, the jitter of BondedImpact's default.
struct PlateImpact {
  std::size_t thick, targetThick, width;
  double spacing;
  BondedSystem system;
};

PlateImpact plateImpact(std::size_t thick, std::size_t targetThick, std::size_t width, double v0) {
  const double a = ws2017::kTwoToOneSixth * ws2017::headlineSigma();
  const BondedSystem target =
      buildBondedBox(targetThick, width, width, a, 2700.0, headlineSizing());
  const BondedSystem flyer = buildBondedBox(thick, width, width, a, 2700.0, headlineSizing());
  BondedSystem s = target;
  std::fill(s.body.begin(), s.body.end(), 1);
  const std::uint32_t offset = static_cast<std::uint32_t>(s.size());
  for (std::size_t i = 0; i < flyer.size(); ++i) {
    s.positions.insert(s.positions.end(), {flyer.positions[3 * i] - thick * a,
                                           flyer.positions[3 * i + 1], flyer.positions[3 * i + 2]});
    s.velocities.insert(s.velocities.end(), {v0, 0.0, 0.0});
    s.masses.push_back(flyer.masses[i]);
    s.body.push_back(0);
  }
  for (BondedBond b : flyer.bonds) {
    b.i += offset, b.j += offset;
    s.bonds.push_back(b);
  }
  addBoltzmannJitter(s, 1e-3, 3);
  return {thick, targetThick, width, a, std::move(s)};
}

// Per lattice column along x (column c of the flyer is −thick + c, the target's c), over the
// central tube |j|, |k| ≤ width/6 of the cross-section: mean x velocity and specific internal
// energy.
struct Columns {
  std::vector<double> vx, heat; // index: column + thick
};

Columns columns(const PlateImpact& p, const BondedSolver& solver) {
  const std::size_t nf = p.thick, nt = p.targetThick, w = p.width, inTarget = nt * w * w;
  Columns c;
  c.vx.assign(nf + nt, 0.0), c.heat.assign(nf + nt, 0.0);
  std::vector<double> count(nf + nt, 0.0);
  const BondedSystem& s = solver.system();
  const double centre = 0.5 * (w - 1.0), half = w / 6.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const bool target = i < inTarget;
    const std::size_t n = target ? nt : nf, site = target ? i : i - inTarget;
    const double j = (site / n) % w, k = site / (n * w);
    if (std::abs(j - centre) > half || std::abs(k - centre) > half)
      continue;
    const std::size_t index = (target ? nf : 0) + site % n;
    c.vx[index] += s.velocities[3 * i];
    c.heat[index] += solver.internalEnergy()[i] / s.masses[i];
    count[index] += 1.0;
  }
  for (std::size_t k = 0; k < nf + nt; ++k)
    c.vx[k] /= count[k], c.heat[k] /= count[k];
  return c;
}

// Where the shocked region ends in the target (in columns, interpolated): the first column,
// walking from the impact face, at which the mean velocity drops below v0/4 (half the shocked
// state's) and stays there for the next column.
double shockFront(const Columns& c, std::size_t thick, double v0) {
  const double level = 0.25 * v0;
  for (std::size_t k = thick + 1; k + 1 < c.vx.size(); ++k)
    if (c.vx[k] < level && c.vx[k + 1] < level)
      return static_cast<double>(k - 1 - thick) + (c.vx[k - 1] - level) / (c.vx[k - 1] - c.vx[k]);
  return NAN;
}

// A planar impact's measures (PlanarImpactFollowsTheHugoniotAndLeavesTheWasteHeat, below).
struct Planar {
  double up, us, pressure, heat, energyError, momentumError;
  std::size_t particles, steps, interval;
};

Planar planarImpact(double v0, const BondedSolverParams& sp, bool print = false) {
  PlateImpact p = plateImpact(14, 22, 24, v0);
  const double rho0 = p.system.masses[0] / std::pow(p.spacing, 3);
  BondedSolver solver(p.system, sp);
  const BondedEnergies e0 = solver.energies();
  const std::array<double, 3> p0 = solver.momentum();
  std::vector<double> times, fronts;
  Planar r{};
  for (int k = 0; k <= 4; ++k) {
    solver.advanceTo(1.4e-7 + 4e-8 * k);
    const Columns c = columns(p, solver);
    const double front = shockFront(c, p.thick, v0);
    if (print)
      std::printf("[shock]   t = %.3e s: front at column %.2f, u = %.0f %.0f %.0f m/s\n",
                  solver.time(), front, c.vx[p.thick + 1], c.vx[p.thick + 2], c.vx[p.thick + 3]);
    times.push_back(solver.time());
    fronts.push_back(front * p.spacing);
    r.up += (c.vx[p.thick + 1] + c.vx[p.thick + 2] + c.vx[p.thick + 3]) / 15.0;
  }
  double tm = 0.0, xm = 0.0, txx = 0.0, tt = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k)
    tm += times[k] / times.size(), xm += fronts[k] / times.size();
  for (std::size_t k = 0; k < times.size(); ++k)
    txx += (times[k] - tm) * (fronts[k] - xm), tt += (times[k] - tm) * (times[k] - tm);
  r.us = txx / tt, r.pressure = rho0 * r.us * r.up;
  solver.advanceTo(8e-7);
  const Columns c = columns(p, solver);
  for (int col = 3; col <= 8; ++col)
    r.heat += (c.heat[p.thick + col] + c.heat[p.thick - col]) / 12.0;
  const std::array<double, 3> p1 = solver.momentum();
  r.energyError = solver.energies().total() / e0.total() - 1.0;
  r.momentumError = std::abs(p1[0] - p0[0]) / p0[0];
  r.particles = solver.system().size(), r.steps = solver.stepCount();
  r.interval = solver.dissipationInterval();
  return r;
}

} // namespace

// The reference itself: the waste heat of the Hugoniot and its release isentrope at the impact
// speeds of Table 1 of the paper against the heat that melts aluminium from 298.15 K
// (docs/physics.md §5.1: 0.666 MJ/kg to the melting point, 1.063 MJ/kg with the heat of fusion).
// The paper's thresholds (incipient melting at 5.6 km/s, complete at 7.0 km/s) are where the
// waste heat reaches these: within 10 %.
TEST(BondedShock, WasteHeatReachesTheMeltingHeatsAtThePapersThresholds) {
  const Hugoniot al;
  const double incipient = al.wasteHeat(2800.0), complete = al.wasteHeat(3500.0);
  const double headline = al.wasteHeat(3350.0);
  std::printf("[shock] Al Hugoniot: p at 5.6 / 6.7 / 7.0 km/s = %.1f / %.1f / %.1f GPa, U_s(3.35 "
              "km/s) = %.0f m/s; waste heat at 5.6 / 6.7 / 7.0 km/s: %.3f / %.3f / %.3f MJ/kg\n",
              al.pressure(2800.0) / 1e9, al.pressure(3350.0) / 1e9, al.pressure(3500.0) / 1e9,
              al.shockSpeed(3350.0), incipient / 1e6, headline / 1e6, complete / 1e6);
  // Steinberg's set for 6061-T6 (ρ0 2703 kg/m³, C0 5.24 km/s, S1 1.40, Γ0 1.97): the spread of
  // the reference between two fits.
  const Hugoniot steinberg{2703.0, 5240.0, 1.40, 1.97};
  std::printf("[shock] Steinberg's set: p(3.35 km/s) = %.1f GPa, waste heat at 5.6 / 6.7 / 7.0 "
              "km/s: %.3f / %.3f / %.3f MJ/kg\n",
              steinberg.pressure(3350.0) / 1e9, steinberg.wasteHeat(2800.0) / 1e6,
              steinberg.wasteHeat(3350.0) / 1e6, steinberg.wasteHeat(3500.0) / 1e6);
  EXPECT_NEAR(incipient / 0.666e6, 1.0, 0.10);
  EXPECT_NEAR(complete / 1.063e6, 1.0, 0.10);
  EXPECT_LT(headline, 0.5 * 3350.0 * 3350.0 / 4.0); // a fraction of the shock's up²/2
}

// A flyer plate 14 sites thick onto a target 22 thick, both 24 wide, at 6.7 km/s with
// ShockViscosity. Both are aluminium: the shocked state has u_p = v0/2 and p = ρ0 U_s u_p
// (Rankine–Hugoniot), U_s the speed of the main front into the target at rest, fitted over
// 1.4–3.0e-7 s (columns 6 to 12; before it, a fast precursor along the lattice's rows runs ahead
// and decays), u_p the mean velocity of target columns 1–3 over the same outputs, in the central
// tube. The internal energy left in the central tube, columns 3–8 on either side of the impact
// face (away from its wall heating), once both plates are released at 8e-7 s, against the
// waste heat. Δt is 2e-3 of the bond period (9× the paper's): the pulses follow the lattice's
// crossing time, and the heat does not depend on Δt (docs/physics.md §5.1).
// The pressure is asserted within 30 %: the paper's law makes the lattice softer than aluminium
// at this pressure (docs/physics.md §5.1), which the dissipative term does not change.
TEST(BondedShock, PlanarImpactFollowsTheHugoniotAndLeavesTheWasteHeat) {
  const double v0 = 6700.0;
  BondedSolverParams sp = shockViscosity();
  sp.timeStepFraction = 2e-3;
  const Planar r = planarImpact(v0, sp, true);
  const Hugoniot al;
  const double waste = al.wasteHeat(0.5 * v0);
  std::printf("[shock] planar 6.7 km/s, %zu particles, %zu steps (pulse every %zu): u_p = %.0f "
              "m/s (v0/2 = %.0f), U_s = %.0f m/s (Al %.0f), p = %.1f GPa (Al %.1f); internal "
              "energy left %.3f MJ/kg (waste heat %.3f); dE/E0 = %.2e, |dP|/(M v0) = %.1e\n",
              r.particles, r.steps, r.interval, r.up, 0.5 * v0, r.us, al.shockSpeed(0.5 * v0),
              r.pressure / 1e9, al.pressure(0.5 * v0) / 1e9, r.heat / 1e6, waste / 1e6,
              r.energyError, r.momentumError);
  EXPECT_NEAR(r.up / (0.5 * v0), 1.0, 0.10);
  EXPECT_NEAR(r.pressure / al.pressure(0.5 * v0), 1.0, 0.30);
  EXPECT_NEAR(r.heat / waste, 1.0, 0.25);
}

// The calibration of docs/physics.md §5.1 (about 3 minutes on one thread; run with
// --gtest_also_run_disabled_tests --gtest_filter=BondedShock.DISABLED_CalibrationTable): the
// planar impact above at 5.6, 6.7 and 7.0 km/s with the defaults, at 6.7 km/s with other
// thresholds and with the shock codes' usual coefficients, and the paper's model.
TEST(BondedShock, DISABLED_CalibrationTable) {
  const Hugoniot al;
  struct Row {
    const char* name;
    double v0, linear, quadratic, threshold;
    bool none;
  };
  const Row rows[] = {{"defaults", 5600.0, 0.0, 0.05, 500.0, false},
                      {"defaults", 6700.0, 0.0, 0.05, 500.0, false},
                      {"defaults", 7000.0, 0.0, 0.05, 500.0, false},
                      {"w_th 200 m/s", 6700.0, 0.0, 0.05, 200.0, false},
                      {"w_th 1000 m/s", 6700.0, 0.0, 0.05, 1000.0, false},
                      {"C_Q 0.1", 6700.0, 0.0, 0.1, 500.0, false},
                      {"C_L 0.25, C_Q 1, w_th 200 m/s", 6700.0, 0.25, 1.0, 200.0, false},
                      {"C_L 0.25, C_Q 1, w_th 3900 m/s", 5600.0, 0.25, 1.0, 3900.0, false},
                      {"C_L 0.25, C_Q 1, w_th 3900 m/s", 6700.0, 0.25, 1.0, 3900.0, false},
                      {"None (the paper's model)", 6700.0, 0.0, 0.05, 500.0, true}};
  std::printf("[shock] calibration | model | v0 (m/s) | u_p (m/s) | U_s (m/s) | p (GPa) | "
              "p / p_Al | internal energy left (MJ/kg) | waste heat (MJ/kg) | ratio |\n");
  for (const Row& row : rows) {
    BondedSolverParams sp = shockViscosity();
    sp.timeStepFraction = 2e-3;
    sp.shockViscosityLinear = row.linear, sp.shockViscosityQuadratic = row.quadratic;
    sp.shockViscosityThreshold = row.threshold;
    if (row.none)
      sp.dissipation = BondedDissipation::None;
    const Planar r = planarImpact(row.v0, sp);
    const double waste = al.wasteHeat(0.5 * row.v0);
    std::printf("[shock] calibration | %s | %.0f | %.0f | %.0f | %.1f | %.2f | %.3f | %.3f | "
                "%.2f |\n",
                row.name, row.v0, r.up, r.us, r.pressure / 1e9,
                r.pressure / al.pressure(0.5 * row.v0), r.heat / 1e6, waste / 1e6, r.heat / waste);
  }
}

// What a pulse costs on the bonded benchmark's problem (the headline impact at 1.5e5 particles,
// benchmarks/hvi_bonded/run.py's default size, 1500 steps into the impact; about 3 minutes):
// the median time of the steps that end with a pulse against the others, in one run, and that
// difference spread over the interval, as a share of a step. CK_PULSE_PARTICLES sets the size.
// Run with --gtest_also_run_disabled_tests --gtest_filter=BondedShock.DISABLED_PulseCost.
TEST(BondedShock, DISABLED_PulseCost) {
  BondedImpactParams p;
  p.particleCount =
      std::getenv("CK_PULSE_PARTICLES") ? std::atof(std::getenv("CK_PULSE_PARTICLES")) : 1.5e5;
  BondedSolver solver(buildBondedImpact(p), shockViscosity());
  solver.advance(1500);
  const std::uint64_t k = solver.dissipationInterval();
  std::vector<double> with, without;
  for (int s = 0; s < 20 * static_cast<int>(k); ++s) {
    const bool pulse = (solver.stepCount() + 1) % k == 0;
    const auto t0 = std::chrono::steady_clock::now();
    solver.step();
    (pulse ? with : without)
        .push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double a = median(with), b = median(without);
  std::printf("[shock] pulse cost: %zu particles, %d threads, a pulse every %llu steps: step "
              "%.2f ms, with the pulse %.2f ms; the pulse %.2f ms, %.1f %% of a step\n",
              solver.system().size(), omp_get_max_threads(), static_cast<unsigned long long>(k),
              1e3 * b, 1e3 * a, 1e3 * (a - b), 100.0 * (a - b) / static_cast<double>(k) / b);
  EXPECT_LT((a - b) / static_cast<double>(k) / b, 0.15);
}

// One pulse on a hand-made cloud (every pair listed, eight particles a block): the kinetic
// energy it takes equals the internal energy it gives, to rounding; momentum is unchanged to
// rounding; no pair approaching slower than the threshold, or apart, or farther than r_eq is
// touched; and every particle's share is its pairs' J w / 2 less ½ m |Δv|².
TEST(BondedShock, EachPulseKeepsTheEnergyItTakes) {
  const ws2017::Law law = ws2017::sizedLaw(headlineSizing(), 1e-3 / ws2017::kTwoToOneSixth);
  const std::size_t n = 27;
  Random random(5);
  std::vector<double> x(3 * n), v(3 * n), m(n), internal(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      x[3 * i + k] = 1e-3 *
                         ((i / (k == 0   ? 1
                                : k == 1 ? 3
                                         : 9)) %
                          3) *
                         0.95 +
                     2e-5 * random.uniform();
      v[3 * i + k] = 3000.0 * (random.uniform() - 0.5);
    }
    m[i] = 2.7e-6 * (0.8 + 0.4 * random.uniform());
  }
  const std::size_t blocks = (n + 7) / 8;
  std::vector<std::size_t> blockStart(blocks + 1);
  std::vector<std::uint32_t> partner;
  for (std::size_t b = 0; b < blocks; ++b) {
    blockStart[b] = partner.size();
    for (std::size_t k = 0; k < n; ++k) // entry k of lane l: particle k (itself: padding)
      for (std::size_t l = 0; l < 8; ++l)
        partner.push_back(static_cast<std::uint32_t>(k));
  }
  blockStart[blocks] = partner.size();
  ShockViscosityParams params{0.0, 0.05, 500.0};
  const ShockViscosity viscosity(params, law, 2.7e-6, 1e-6);
  auto kinetic = [&](const std::vector<double>& vel) {
    double k = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      k += 0.5 * m[i] *
           (vel[3 * i] * vel[3 * i] + vel[3 * i + 1] * vel[3 * i + 1] +
            vel[3 * i + 2] * vel[3 * i + 2]);
    return k;
  };
  auto momentum = [&](const std::vector<double>& vel, int k) {
    double p = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      p += m[i] * vel[3 * i + k];
    return p;
  };
  const std::vector<double> before = v;
  std::vector<double> scratch(4 * n);
  double taken = 0.0, given = 0.0, scale = kinetic(before), pScale = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    pScale += m[i] * std::sqrt(v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] +
                               v[3 * i + 2] * v[3 * i + 2]);
  for (int pulse = 0; pulse < 20; ++pulse) {
    const std::vector<double> vb = v, ub = internal;
    viscosity.pulse({n, blockStart.data(), partner.data()}, x.data(), v.data(), m.data(),
                    internal.data(), scratch.data());
    const double dk = kinetic(vb) - kinetic(v);
    double du = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      du += internal[i] - ub[i];
    taken += dk, given += du;
    EXPECT_NEAR(dk, du, 1e-13 * scale) << pulse;
  }
  // The impulses: pairs in contact (r < r_eq) approaching faster than 500 m/s only.
  std::size_t active = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      double r2 = 0.0, dot = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double d = x[3 * i + k] - x[3 * j + k];
        r2 += d * d, dot += d * (before[3 * i + k] - before[3 * j + k]);
      }
      active += r2 < law.rEq() * law.rEq() && -dot / std::sqrt(r2) > 500.0;
    }
  std::printf(
      "[shock] pulse: %zu particles, %zu pairs active at first, kinetic energy taken "
      "%.6e J, internal energy given %.6e J (of %.3e J), momentum change %.1e, %.1e, %.1e\n",
      n, active, taken, given, scale, momentum(v, 0) - momentum(before, 0),
      momentum(v, 1) - momentum(before, 1), momentum(v, 2) - momentum(before, 2));
  EXPECT_GT(active, 3u);
  EXPECT_GT(taken, 1e-3 * scale);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(momentum(v, k), momentum(before, k), 1e-14 * pScale);
  EXPECT_EQ(viscosity.impulse(499.0, 1e-6, 1e-6), 0.0);
  EXPECT_GT(viscosity.impulse(600.0, 1e-6, 1e-6), 0.0);
  // Two particles alone, head on: the pulse never reverses an approach.
  const ShockViscosity strong({1e3, 1e3, 1.0}, law, 2.7e-6, 1e-6);
  EXPECT_LE(strong.impulse(5000.0, 1e-6, 1e-6), 0.5e-6 * (5000.0 - 1.0));
  EXPECT_GT(strong.impulse(5000.0, 1e-6, 1e-6), 0.99 * 0.5e-6 * (5000.0 - 1.0));
}

// A sphere on a plate at 6.7 km/s with ShockViscosity to 4 µs: kinetic + repulsive + bond +
// broken-bond + internal energy stays within the integrator's own error, measured by the
// paper's model on the same set-up (the term adds no error of its own: each pulse keeps what it
// takes, above), while the internal energy is a sizeable share; momentum is kept to rounding.
TEST(BondedShock, TotalEnergyAndMomentumKeptThroughAnImpact) {
  BondedImpactParams p;
  p.particleCount = 2500;
  p.plateWidthRatio = 2.5;
  p.seed = 7;
  const BondedSystem start = buildBondedImpact(p);
  double error[2] = {0.0, 0.0}, internalShare = 0.0, dp = 0.0;
  for (int model = 0; model < 2; ++model) {
    BondedSolver solver(start, model ? shockViscosity() : BondedSolverParams{});
    const double e0 = solver.energies().total();
    const std::array<double, 3> p0 = solver.momentum();
    for (int k = 1; k <= 8; ++k) {
      solver.advanceTo(0.5e-6 * k);
      error[model] = std::max(error[model], std::abs(solver.energies().total() / e0 - 1.0));
    }
    if (model == 1) {
      internalShare = solver.energies().internal / e0;
      const std::array<double, 3> p1 = solver.momentum();
      dp = std::sqrt(std::pow(p1[0] - p0[0], 2) + std::pow(p1[1] - p0[1], 2) +
                     std::pow(p1[2] - p0[2], 2)) /
           std::abs(p0[0]);
    }
  }
  std::printf("[shock] sphere on plate, 2500 particles, 4 us: max |E/E0 - 1| = %.2e (paper's "
              "model %.2e), internal energy %.3f of E0, |dP|/P = %.1e\n",
              error[1], error[0], internalShare, dp);
  EXPECT_GT(internalShare, 0.01);
  EXPECT_LT(error[1], 2.0 * error[0] + 1e-6);
  EXPECT_LT(dp, 1e-11);
}

// Dissipation None is the paper's model: no pulse, no internal energy, and the same bits as the
// code path with a threshold no pair reaches (every pulse then changes nothing), through bond
// breaking and list rebuilds; and ShockViscosity itself gives the same bits on one and two
// threads. The existing BondedImpact.* and BondedRun.* tests, unchanged,
// pin the paper's model's figures.
TEST(BondedShock, NoneIsThePapersModelBitForBit) {
  BondedImpactParams p;
  p.particleCount = 800;
  p.plateWidthRatio = 2.5;
  p.seed = 7;
  const BondedSystem start = buildBondedImpact(p);
  const int threadsBefore = omp_get_max_threads();
  BondedSolver none(start);
  none.advanceTo(1e-6);
  BondedSolverParams idle = shockViscosity();
  idle.shockViscosityThreshold = 1e30;
  BondedSolver untouched(start, idle);
  untouched.advanceTo(1e-6);
  omp_set_num_threads(2);
  BondedSolver two(start, shockViscosity());
  two.advanceTo(1e-6);
  omp_set_num_threads(1);
  BondedSolver one(start, shockViscosity());
  one.advanceTo(1e-6);
  omp_set_num_threads(threadsBefore);
  const BondedEnergies e = none.energies();
  std::printf("[shock] None against an idle ShockViscosity: %llu steps, %zu broken, pulse every "
              "%llu steps; ShockViscosity internal energy %.3e J, broken %zu\n",
              static_cast<unsigned long long>(none.stepCount()), none.brokenBonds(),
              static_cast<unsigned long long>(untouched.dissipationInterval()),
              one.energies().internal, one.brokenBonds());
  EXPECT_EQ(none.dissipationInterval(), 0u);
  EXPECT_GT(none.brokenBonds(), 0u);
  EXPECT_EQ(e.internal, 0.0);
  EXPECT_EQ(e.total(), e.kinetic + e.repulsive + e.bond + e.dissipated);
  EXPECT_TRUE(std::all_of(none.internalEnergy().begin(), none.internalEnergy().end(),
                          [](double u) { return u == 0.0; }));
  EXPECT_TRUE(sameBits(untouched.system().positions, none.system().positions));
  EXPECT_TRUE(sameBits(untouched.system().velocities, none.system().velocities));
  EXPECT_TRUE(sameBits(untouched.forces(), none.forces()));
  EXPECT_TRUE(sameBits(untouched.bondBroken(), none.bondBroken()));
  EXPECT_GT(one.energies().internal, 0.0);
  EXPECT_FALSE(sameBits(one.system().velocities, none.system().velocities));
  EXPECT_TRUE(sameBits(one.system().positions, two.system().positions));
  EXPECT_TRUE(sameBits(one.system().velocities, two.system().velocities));
  EXPECT_TRUE(sameBits(one.internalEnergy(), two.internalEnergy()));
  // The report: InternalEnergy per particle (J/kg) and the field data.
  const BondedFragmentResult f = analyseDebrisCloud(one);
  const BondedArrays a = bondedArrays(one, f, 2700.0, 2700.0);
  double sum = 0.0;
  for (std::size_t i = 0; i < one.system().size(); ++i)
    sum += a.internalEnergy[i] * one.system().masses[i];
  EXPECT_NEAR(sum, one.energies().internal, 1e-12 * one.energies().total());
  bool named = false;
  for (const NamedValue& v : bondedFields(one, f))
    named |= v.name == "Dissipation" && v.text == "ShockViscosity";
  EXPECT_TRUE(named);
}

// Every refusal names the parameter: negative coefficients, both zero, a threshold that is not a
// positive speed (0 would damp every contact), an unknown model; refused by the solver's
// parameters even with Dissipation None.
TEST(BondedShock, BadParametersRefusedByName) {
  auto refused = [](const std::function<void(BondedSolverParams&)>& change,
                    const std::string& name) {
    for (BondedDissipation d : {BondedDissipation::None, BondedDissipation::ShockViscosity}) {
      BondedSolverParams p;
      p.dissipation = d;
      change(p);
      try {
        p.validate();
        ADD_FAILURE() << "accepted bad " << name;
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
      }
    }
  };
  refused([](auto& p) { p.shockViscosityLinear = -0.1; }, "ShockViscosityLinear");
  refused([](auto& p) { p.shockViscosityQuadratic = -1.0; }, "ShockViscosityQuadratic");
  refused(
      [](auto& p) {
        p.shockViscosityLinear = 0.0;
        p.shockViscosityQuadratic = 0.0;
      },
      "ShockViscosityQuadratic");
  refused([](auto& p) { p.shockViscosityThreshold = 0.0; }, "ShockViscosityThreshold");
  refused([](auto& p) { p.shockViscosityThreshold = -5.0; }, "ShockViscosityThreshold");
  refused([](auto& p) { p.shockViscosityThreshold = NAN; }, "ShockViscosityThreshold");
  refused([](auto& p) { p.dissipation = static_cast<BondedDissipation>(7); }, "Dissipation");
  EXPECT_EQ(dissipationByName("ShockViscosity"), BondedDissipation::ShockViscosity);
  EXPECT_EQ(dissipationByName("None"), BondedDissipation::None);
  EXPECT_THROW(dissipationByName("Viscous"), InputError);
  const BondedSystem box = buildBondedBox(4, 4, 4, 1e-3, 2700.0, headlineSizing());
  BondedSolverParams bad = shockViscosity();
  bad.shockViscosityThreshold = 0.0;
  EXPECT_THROW(BondedSolver(box, bad), InputError);
}

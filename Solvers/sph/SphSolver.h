// The SPH solver for the shock stage (PHYSICS.md §2): first piece, the hydrodynamic core.
//
// Continuity (integrated density), momentum and energy in the symmetric forms of §2.2 with
// Monaghan artificial viscosity (§2.3), a choice of kernel, smoothing length following the
// density (h = κ (m/ρ)^{1/3}, support h), equations of state by material, periodic or open
// boundaries, uniform gravity, and Heun's predictor–corrector (RK2) with a Courant time step.
// Neighbours come from a cell list rebuilt at every force evaluation; periodic axes use ghost
// copies of the particles within one support radius of a face. OpenMP over particles, the
// same bits for any thread count.
//
// Not yet here (issue 4 continues): deviatoric stress and strength, porosity, damage, variable
// h with ∇h terms, checkpoints.
#pragma once

#include "sph/Eos.h"

#include <cstddef>
#include <string>
#include <vector>

namespace craterkit {

struct SphState {
  std::vector<double> x, v;           // 3 per particle
  std::vector<double> mass, rho, u, h; // kg, kg/m³, J/kg, m (support radius)
  std::vector<int> material;
  std::size_t size() const { return mass.size(); }
  void add(const double pos[3], const double vel[3], double m, double density, double energy, int mat);
};

struct SphParams {
  enum class Kernel { CubicSpline, WendlandC2 } kernel = Kernel::CubicSpline;
  std::vector<EquationOfState> eos; // one per material index
  double alpha = 1.0, beta = 2.0;  // artificial viscosity
  double kappa = 2.5;               // h = κ (m/ρ)^{1/3}
  double courant = 0.3;
  bool summationDensity = false;    // ρ = Σ m W (gases) instead of the integrated continuity equation
  double gravity[3] = {0, 0, 0};
  bool periodic[3] = {false, false, false};
  double boxLo[3] = {0, 0, 0}, boxHi[3] = {1, 1, 1}; // the periodic cell
  void validate() const;
};

class SphSolver {
public:
  SphSolver(const SphState& initial, const SphParams& params);
  // One Heun step of size dt (0: the Courant step).
  double step(double dt = 0.0);
  void advanceTo(double t);
  double time() const { return time_; }
  const SphState& state() const { return s_; }
  const std::vector<double>& pressure() const { return p_; }
  double courantStep() const;
  double totalEnergy() const; // kinetic + internal
  void totalMomentum(double p[3]) const;

private:
  struct Rates {
    std::vector<double> dv, drho, du; // dx/dt is the state's own velocity
  };
  // Rates of state s; fills pressure and sound speed of s into p, c; returns the largest
  // signal speed over h (for the time step).
  double computeRates(const SphState& s, Rates& r, std::vector<double>& p, std::vector<double>& c) const;
  void updateSmoothing(SphState& s) const;
  void densityBySummation(SphState& s) const;
  void wrap(SphState& s) const;
  // After a position update: positions into the periodic box, h from ρ, and ρ by summation
  // when asked.
  void settle(SphState& s) const;
  SphState s_;
  SphParams par_;
  std::vector<double> p_, cs_; // pressure and sound speed of the current state
  double time_ = 0.0, lastMaxSignal_ = 0.0;
};

} // namespace craterkit

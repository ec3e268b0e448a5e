// Grady–Kipp fracture for the SPH solver, as in Benz & Asphaug (1995) and miluphcuda
// (docs/physics.md §2.7). Weibull flaws n(ε) = k ε^m: N ln N flaws for the N particles of a brittle
// material, flaw j activating at ε_j = (j / (k V))^{1/m} (V the material's volume), each given
// to a random particle. A particle's local strain is ε = σ_max / ((1 − D) E), E = 9KG/(3K + G);
// with n_act of its n_tot flaws active, its damage grows as d(D^⅓)/dt = n_act c_g / R_s,
// c_g = 0.4 √((K + 4G/3)/ρ), R_s its radius, up to D ≤ n_act / n_tot. Damage never heals; it
// weakens tension and shear (sph/Strength.h).
#pragma once

#include "sph/Material.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct SphState;

// Per particle: d(D^⅓)/dt and the cap n_act/n_tot (empty when no particle has flaws).
struct DamageRates {
  std::vector<double> rate, cap;
};

class GradyKippFracture {
public:
  // Draws the flaws of every material with a Weibull k > 0 (a particle left without one gets
  // the next); each particle's thresholds are ascending.
  void assignFlaws(const SphState& s, const std::vector<Material>& materials, std::uint64_t seed);
  bool empty() const { return eps_.empty(); }
  bool hasFlaws(std::size_t i) const { return start_[i + 1] > start_[i]; }
  // Particle i's rate and cap from its deviatoric stress S (6 components) and pressure p.
  void damageRate(std::size_t i, const Material& mat, const double* S, double p, double D,
                  double rho, double mass, double& rate, double& cap) const;
  // damage = the damage `from` integrated over dt with the rates a (or the mean of a and b,
  // and the larger cap); damage and from may be the same array.
  static void integrate(std::vector<double>& damage, const std::vector<double>& from, double dt,
                        const DamageRates& a, const DamageRates* b);

private:
  std::vector<std::uint32_t> start_; // activation strains per particle (CSR, ascending)
  std::vector<double> eps_;
};

} // namespace craterkit

// Shock heating for the bonded-particle model: an optional dissipative term beyond Watson &
// Steinhauser 2017 (Materials 10:379), chosen by name (BondedSolverParams::dissipation).
//
//   None            the paper's model exactly: no term, the same bits as before the term existed.
//   ShockViscosity  a pair viscosity in fast compression, the bonded analogue of the artificial
//                   viscosity of shock codes (von Neumann & Richtmyer 1950, J. Appl. Phys.
//                   21:232, quadratic term; Landshoff 1955, LA-1930, linear term).
//
// ShockViscosity acts on every pair closer than r_eq (in repulsive contact) whose particles
// approach each other faster than the threshold w_th along their line of centres: with w the
// approach speed and q = w − w_th > 0 its excess, the pair is pushed apart by the force
//
//     F = (m̄ / r_eq) (C_Q q² + C_L c0 q),      m̄ = 2 m_i m_j / (m_i + m_j),
//
// the pressure ρ0 (C_Q Δu² + C_L c0 Δu) of the shock codes' viscosity on the face r_eq² between
// two lattice cells (ρ0 r_eq³ = m), with c0 = r_eq √(φ''(r_eq) / m̄) the long-wave speed of the
// lattice in compression (φ'' = 72 ε / (2^{1/3} σ²), Eq. 3). The force is equal and opposite on
// the two particles and along their line of centres: momentum and angular momentum are kept.
// Every quantity is invariant under the paper's sizing (ε ∝ σ³, m ∝ σ³): c0 does not depend on σ,
// and F r_eq / m̄ neither.
//
// The term is applied as an operator split: every `interval` steps, after a whole Verlet step,
// each pair receives the impulse of its force over interval·Δt, integrated exactly for a pair on
// its own (the excess approach speed decays as dq/dt = −γ(q) q, γ = F / (μ q), μ = m̄/2; with the
// rate frozen over the pulse, J = μ q (1 − e^{−γ τ}), τ = interval·Δt, which never reverses an
// approach). The interval is the largest whole number of steps within 1/kPulsesPerCrossing of
// the time r_eq / c0 a compression wave takes to cross one lattice spacing (at least 1): the
// viscosity's own time scale r_eq / (2 (C_Q q + C_L c0)) is resolved by several pulses for
// approach speeds up to the impact speed. All impulses of a pulse are computed from the same
// velocities (each particle sums its own pairs, in its list's order: the same bits for any
// number of threads).
//
// The energy the pulse takes out of the motion is kept, exactly, as internal energy: a particle's
// kinetic energy changes by m_i v_i·Δv_i + ½ m_i |Δv_i|², and Σ_i m_i v_i·Δv_i = −Σ_pairs J w,
// so giving each particle of a pair J w / 2 and each particle −½ m_i |Δv_i|² makes the internal
// energy gained equal to the kinetic energy lost, to rounding. The internal energy is inert: it
// exerts no pressure (the model's pressure is its potential alone), it is what a shock leaves as
// heat. docs/physics.md §5.1 calibrates the coefficients against aluminium's waste heat.
#pragma once

#include "bonded/WatsonSteinhauser2017.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace craterkit {

// The dissipative terms by name; entry 0 is the paper's model.
enum class BondedDissipation : std::uint32_t { None = 0, ShockViscosity = 1 };
// "None", "ShockViscosity".
const char* dissipationName(BondedDissipation d);
// The term of that name; throws InputError naming the choices otherwise.
BondedDissipation dissipationByName(const std::string& name);

struct ShockViscosityParams {
  double linear = 0.0;    // C_L (dimensionless)
  double quadratic = 0.0; // C_Q (dimensionless)
  double threshold = 0.0; // w_th, m/s
  // Throws InputError naming the parameter: negative coefficients, both zero, a threshold that
  // is not positive (0 would damp every approaching contact, the lattice's jitter included).
  void validate() const;
};

class ShockViscosity {
public:
  static constexpr double kPulsesPerCrossing = 16.0;

  // The constants for a law, the lightest particle's mass (which sets the interval) and Δt.
  ShockViscosity(const ShockViscosityParams& params, const ws2017::Law& law, double lightestMass,
                 double timeStep);

  // Steps between pulses.
  std::uint64_t interval() const { return interval_; }
  // c0 = r_eq √(φ''(r_eq) / m) for particles of mass m.
  double soundSpeed(double mass) const;

  // The pair lists of the solver (BondedSolver.h: blocks of eight particles, entry k of lane l
  // at blockStart[b] + k kLanes + l; padding entries name the particle itself).
  struct Lists {
    std::size_t n;
    const std::size_t* blockStart;
    const std::uint32_t* partner;
  };
  // One pulse: the impulses of every pair from the current positions and velocities, added to
  // the velocities; the kinetic energy taken out added to `internal` (J per particle).
  // `scratch` holds 4 n doubles.
  void pulse(const Lists& lists, const double* x, double* v, const double* m, double* internal,
             double* scratch) const;

  // The impulse J (N s) along the line of centres for a pair of masses mi, mj approaching at
  // speed w (m/s, > 0 approaching): 0 at or below the threshold.
  double impulse(double w, double mi, double mj) const;

private:
  ShockViscosityParams p_;
  double rEq_ = 0.0, rEq2_ = 0.0;
  double stiffness_ = 0.0; // φ''(r_eq)
  double tau_ = 0.0;       // interval · Δt
  std::uint64_t interval_ = 1;
};

} // namespace craterkit

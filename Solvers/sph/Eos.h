// Equations of state for the SPH solver, chosen by name at run time (docs/physics.md §2.4):
// Tillotson (Tillotson 1962; as in miluphcuda's pressure.cu), Murnaghan, ideal gas, stiffened gas.
// Pressure p(ρ, u) in Pa for density ρ (kg/m³) and specific internal energy u (J/kg); the
// sound speed comes from c² = ∂p/∂ρ|_u + (p/ρ²) ∂p/∂u|_ρ, floored at `soundSpeedFloor`.
// Late stage (after Raducan & Jutzi 2022; docs/physics.md §2.8): a Tillotson or Murnaghan law is
// replaced by the linear p = K (ρ/ρ0 − 1), K = ρ0 c², with a low sound speed c, so that the
// Courant step grows and a run can follow the slow, gravity-driven crater growth.
#pragma once

#include <string>

namespace craterkit {

struct TillotsonParams {
  double rho0 = 2700.0; // kg/m³
  double A = 26.7e9;    // Pa
  double B = 26.7e9;    // Pa
  double E0 = 487e6;    // J/kg
  double Eiv = 4.72e6;  // J/kg, incipient vaporisation
  double Ecv = 18.2e6;  // J/kg, complete vaporisation
  double a = 0.5, b = 1.5, alpha = 5.0, beta = 5.0;
  double rhoLimit = 0.9; // below η = ρ/ρ0 < rhoLimit and u < Ecv: p = 0 (no cold tension)
};

struct EquationOfState {
  enum class Model { Tillotson, Murnaghan, IdealGas, StiffenedGas } model = Model::Tillotson;
  TillotsonParams tillotson;
  // Murnaghan: p = (K0 / n) ((ρ/ρ0)^n − 1).
  double murnaghanRho0 = 2700.0, murnaghanK0 = 50e9, murnaghanN = 4.0;
  // Ideal gas: p = (γ − 1) ρ u.
  double gamma = 1.4;
  // Stiffened gas (Howell & Ball 2002, as PySPH's StiffenedGasEOS): p = c0² (ρ − ρ0) + (Γ − 1) ρ u,
  // c² = c0² + (Γ − 1)(u + p/ρ).
  double stiffRho0 = 2700.0, stiffC0 = 5000.0, stiffGamma = 2.0;
  double soundSpeedFloor = 0.0; // m/s; Tillotson default: 1 % of sqrt(A/ρ0) (set by validate)

  double pressure(double rho, double u) const;
  // ρ0 of the law (Tillotson, Murnaghan, stiffened gas); 0 for the ideal gas, which has none.
  double referenceDensity() const;
  // Whether the law has a late-stage form (Tillotson, Murnaghan; the gases keep theirs).
  bool hasLateStage() const { return model == Model::Tillotson || model == Model::Murnaghan; }
  // The bulk modulus the law states at ρ0: Tillotson's A, Murnaghan's K0 (late-stage laws).
  double referenceBulkModulus() const;
  // Switches a law with a late-stage form to the linear Murnaghan law (n = 1) of sound speed
  // c, with the sound-speed floor at 1 % of c; returns its K = ρ0 c².
  double switchToLateStage(double c);
  double soundSpeed(double rho, double u) const;
  // Throws InputError naming the bad parameter.
  void validate();
  static Model modelFromName(const std::string& name);
  static const char* nameOf(Model m);
};

} // namespace craterkit

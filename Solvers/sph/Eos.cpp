#include "sph/Eos.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

namespace {
double tillotsonCompressed(const TillotsonParams& t, double rho, double u) {
  const double eta = rho / t.rho0, chi = eta - 1.0;
  return (t.a + t.b / (1.0 + u / (t.E0 * eta * eta))) * rho * u + t.A * chi + t.B * chi * chi;
}
double tillotsonExpanded(const TillotsonParams& t, double rho, double u) {
  const double eta = rho / t.rho0, chi = eta - 1.0, z = t.rho0 / rho - 1.0;
  return t.a * rho * u +
         (t.b * rho * u / (1.0 + u / (t.E0 * eta * eta)) + t.A * chi * std::exp(-t.beta * z)) *
             std::exp(-t.alpha * z * z);
}
bool inColdCut(const TillotsonParams& t, double rho, double u) {
  return rho / t.rho0 < t.rhoLimit && u < t.Ecv;
}

double tillotsonPressure(const TillotsonParams& t, double rho, double u, bool cut = true) {
  const double eta = rho / t.rho0;
  double p;
  if (rho >= t.rho0 || u <= t.Eiv) {
    p = tillotsonCompressed(t, rho, u);
  } else if (u >= t.Ecv) {
    p = tillotsonExpanded(t, rho, u);
  } else {
    p = (tillotsonCompressed(t, rho, u) * (t.Ecv - u) +
         tillotsonExpanded(t, rho, u) * (u - t.Eiv)) /
        (t.Ecv - t.Eiv);
  }
  if (cut && eta < t.rhoLimit && u < t.Ecv)
    p = 0.0;
  return p;
}
} // namespace

double EquationOfState::pressure(double rho, double u) const {
  switch (model) {
  case Model::Tillotson:
    return tillotsonPressure(tillotson, rho, u);
  case Model::Murnaghan:
    // n = 1 (the late stage's linear law) without pow, which gives x¹ exactly anyway: the same
    // bits at a tenth of the cost, evaluated for every particle twice a step.
    return murnaghanK0 / murnaghanN *
           ((murnaghanN == 1.0 ? rho / murnaghanRho0 : std::pow(rho / murnaghanRho0, murnaghanN)) -
            1.0);
  case Model::IdealGas:
    return (gamma - 1.0) * rho * u;
  case Model::StiffenedGas:
    return stiffC0 * stiffC0 * (rho - stiffRho0) + (stiffGamma - 1.0) * rho * u;
  }
  return 0.0;
}

double EquationOfState::referenceDensity() const {
  switch (model) {
  case Model::Tillotson:
    return tillotson.rho0;
  case Model::Murnaghan:
    return murnaghanRho0;
  case Model::StiffenedGas:
    return stiffRho0;
  case Model::IdealGas:
    break;
  }
  return 0.0;
}

double EquationOfState::referenceBulkModulus() const {
  return model == Model::Tillotson ? tillotson.A : murnaghanK0;
}

double EquationOfState::switchToLateStage(double c) {
  const double rho0 = referenceDensity(), K = rho0 * c * c;
  model = Model::Murnaghan;
  murnaghanRho0 = rho0;
  murnaghanK0 = K;
  murnaghanN = 1.0;
  soundSpeedFloor = 0.01 * c;
  return K;
}

double EquationOfState::soundSpeed(double rho, double u) const {
  double c2 = 0.0;
  switch (model) {
  case Model::IdealGas:
    c2 = gamma * (gamma - 1.0) * u;
    break;
  case Model::Murnaghan:
    c2 = murnaghanK0 / murnaghanRho0 *
         (murnaghanN == 1.0 ? 1.0 : std::pow(rho / murnaghanRho0, murnaghanN - 1.0)); // x⁰ = 1
    break;
  case Model::StiffenedGas:
    c2 = stiffC0 * stiffC0 + (stiffGamma - 1.0) * (u + pressure(rho, u) / rho);
    break;
  case Model::Tillotson: {
    // In the cold expanded region the pressure is held at 0: no stiffness (the floor applies).
    if (inColdCut(tillotson, rho, u))
      break;
    // Central differences of the formula without that cut, so that a state next to the cut's
    // edge (where p jumps) does not see the jump as an enormous stiffness.
    const TillotsonParams& t = tillotson;
    const double dr = 1e-6 * rho, du = 1e-6 * std::max(u, t.E0 * 1e-3);
    const double p = tillotsonPressure(t, rho, u, false);
    const double dpdr =
        (tillotsonPressure(t, rho + dr, u, false) - tillotsonPressure(t, rho - dr, u, false)) /
        (2.0 * dr);
    const double dpdu = (tillotsonPressure(t, rho, u + du, false) -
                         tillotsonPressure(t, rho, std::max(0.0, u - du), false)) /
                        (u > du ? 2.0 * du : du + u);
    c2 = dpdr + p / (rho * rho) * dpdu;
    break;
  }
  }
  return std::max(std::sqrt(std::max(c2, 0.0)), soundSpeedFloor);
}

void EquationOfState::validate() {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(std::string("equation of state: ") + name + " must be positive (got " +
                       std::to_string(v) + ")");
  };
  switch (model) {
  case Model::Tillotson: {
    const TillotsonParams& t = tillotson;
    positive(t.rho0, "rho0");
    positive(t.A, "A");
    positive(t.E0, "E0");
    positive(t.Ecv, "Ecv");
    if (!(t.B >= 0.0) || !(t.Eiv >= 0.0) || !(t.Ecv > t.Eiv))
      throw InputError("equation of state: Tillotson needs B >= 0 and 0 <= Eiv < Ecv");
    if (soundSpeedFloor <= 0.0)
      soundSpeedFloor = 0.01 * std::sqrt(t.A / t.rho0);
    break;
  }
  case Model::Murnaghan:
    positive(murnaghanRho0, "rho0");
    positive(murnaghanK0, "K0");
    positive(murnaghanN, "n");
    break;
  case Model::StiffenedGas:
    positive(stiffRho0, "rho0");
    positive(stiffC0, "c0");
    if (!(stiffGamma >= 1.0) || !std::isfinite(stiffGamma))
      throw InputError("equation of state: the stiffened-gas Gruneisen gamma must be at least 1");
    break;
  case Model::IdealGas:
    if (!(gamma > 1.0) || !std::isfinite(gamma))
      throw InputError("equation of state: gamma must be above 1 (got " + std::to_string(gamma) +
                       ")");
    break;
  }
}

EquationOfState::Model EquationOfState::modelFromName(const std::string& name) {
  if (name == "Tillotson")
    return Model::Tillotson;
  if (name == "Murnaghan")
    return Model::Murnaghan;
  if (name == "IdealGas")
    return Model::IdealGas;
  if (name == "StiffenedGas")
    return Model::StiffenedGas;
  throw InputError("unknown equation of state '" + name +
                   "' (Tillotson, Murnaghan, IdealGas, StiffenedGas)");
}

const char* EquationOfState::nameOf(Model m) {
  switch (m) {
  case Model::Tillotson:
    return "Tillotson";
  case Model::Murnaghan:
    return "Murnaghan";
  case Model::IdealGas:
    return "IdealGas";
  case Model::StiffenedGas:
    return "StiffenedGas";
  }
  return "?";
}

} // namespace craterkit

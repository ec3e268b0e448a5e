// Material data for the SPH solver, read from files under data/materials/ (one material per
// file, "key = value" lines, '#' comments), not from code. Each names its equation of state
// and strength model; see data/materials/README.md for the keys and the sources of the values.
#pragma once

#include "sph/Eos.h"

#include <string>
#include <vector>

namespace craterkit {

struct Material {
  std::string name;
  EquationOfState eos;
  double shearModulus = 0.0; // Pa (0: fluid)
  double bulkModulus = 0.0;  // Pa
  enum class Strength { None, VonMises, DruckerPrager } strength = Strength::None;
  double yieldStress = 0.0;    // Pa (von Mises)
  double frictionAngle = 30.0; // degrees (Drucker–Prager)
  double cohesion = 0.0;       // Pa (Drucker–Prager)
  double distention = 1.0;     // initial α = ρ_matrix / ρ_bulk (P–α porosity; 1: none)
  double crushPe = 1e6;        // Pa, elastic limit of the quadratic P–α crush curve
  double crushPs = 1e9;        // Pa, pressure at which the pores are closed (α = 1)
  double weibullK = 0.0;       // m⁻³, Grady–Kipp flaw density n(ε) = k ε^m (0: no fracture)
  double weibullM = 9.0;       // Weibull exponent m
  bool rigid = false;          // boundary particles: fixed in place, their pressure and stress
                               // taken from the adjacent material (SphParams::walls)
  std::string source;          // where the values come from

  // The bulk modulus the pressure follows now: bulkModulus if set, else the law's reference.
  double lawBulkModulus() const {
    return bulkModulus > 0.0 ? bulkModulus : eos.referenceBulkModulus();
  }
  // The late stage (sph/Eos.h): a material whose law has a late-stage form takes the linear law
  // of sound speed c and keeps its Poisson ratio, so G falls with K, or takes the Poisson ratio
  // poissonRatio if that is not negative. Returns the factor by which G changed (1: unchanged),
  // by which each particle's deviatoric stress is scaled: the elastic strain is unchanged.
  double switchToLateStage(double c, double poissonRatio = -1.0);
};

// A material with this equation of state and no strength or porosity (a fluid).
Material fluidMaterial(const EquationOfState& eos, const std::string& name = "fluid");

// Reads one material file; throws InputError naming the file and line.
Material readMaterial(const std::string& path);
// The materials of a directory (every *.cfg), sorted by name.
std::vector<Material> readMaterialLibrary(const std::string& directory);
// The material folder: `chosen`, else the environment's CRATERKIT_MATERIALS, else `builtIn`.
std::string materialDirectory(const std::string& chosen, const std::string& builtIn);
// The material called `name`; the error lists the names that exist.
Material findMaterial(const std::string& directory, const std::string& name);

} // namespace craterkit

// What a BondedImpact run reports at an output time: the debris-cloud analysis of the current
// state (BondedFragments, the paper's Section 3 measures), the per-particle arrays the data
// model names (Radius, Density, Material, Id, BondCount, FragmentId) with the shock heating's
// InternalEnergy, and the field data list (clock, broken bonds, energies, F, the cloud's edges,
// L_a, L_r, R, v_a / v0, set-up figures).
#pragma once

#include "bonded/BondedFragments.h"
#include "bonded/BondedSolver.h"
#include "common/NamedValue.h"

#include <cstdint>
#include <vector>

namespace craterkit {

// The fragments and debris cloud of the solver's current state, behind the plate's rear face;
// massFraction: the cloud's mass inside the measured extents (BondedFragments.h).
BondedFragmentResult analyseDebrisCloud(const BondedSolver& solver, double massFraction = 0.95);

struct BondedArrays {
  std::vector<double> radius;  // half the equilibrium spacing: neighbours touch at r_eq
  std::vector<double> density; // kg/m^3 of the particle's body
  std::vector<int> material;   // 0 projectile, 1 plate
  std::vector<std::int64_t> id;
  std::vector<int> bondCount; // intact bonds
  std::vector<int> fragmentId;
  std::vector<double> internalEnergy; // J/kg: the shock heating's (0 without it)
};
BondedArrays bondedArrays(const BondedSolver& solver, const BondedFragmentResult& fragments,
                          double projectileDensity, double plateDensity);

std::vector<NamedValue> bondedFields(const BondedSolver& solver,
                                     const BondedFragmentResult& fragments,
                                     double massFraction = 0.95);

} // namespace craterkit

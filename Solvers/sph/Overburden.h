// The target's weight carried through the late-stage switch (docs/physics.md §2.8).
//
// The switch lowers each material's bulk modulus from K to K' = ρ0 c² at the same density, so a
// target at rest under gravity keeps only K'/K of the pressure that carries its weight: it sags
// by about g H² / 2c² and then rings at the period 4H/c with speeds of order g H / c, hardly
// damped. In the SCI stage at Ryugu's gravity (H ≈ 11.6 m, c = 0.47 m/s) that scale is of order
// 3 mm/s with a period of order 100 s, as fast as the late crater flow itself; what it changed
// there is docs/validation_history.md, "Depth and the SPH resolution", point 11.
//
// With SphParams::overburdenDensity ρ_o > 0 the switch scales only each particle's departure
// from the lithostatic pressure p_L = ρ_o |g| d (d: its depth below the surface plane, along g)
// by K'/K, as it scales the deviatoric stress: p' = p_L + (K'/K)(p − p_L). The late law is
// linear in ρ (dp'/dρ = K'/ρ0), so this raises the particle's density by (1 − K'/K) p_L ρ0 / K'
// (at Ryugu's gravity 0.8 % at 11.6 m). The lithostatic stress is taken isotropic (no K0
// anisotropy), as in iSALE's lithostatic initial state; rigid particles and materials without a
// late-stage law are left alone. With SphParams::summationDensity the next settle recomputes ρ
// from the positions and the raise is lost (the impact set-up integrates the density).
#pragma once

#include "sph/SphParams.h"
#include "sph/SphState.h"

#include <vector>

namespace craterkit {

// Each material's Material::lawBulkModulus, taken before the switch.
std::vector<double> earlyBulkModuli(const std::vector<Material>& materials);

// After Material::switchToLateStage: raises the density of every particle below the surface by
// its share of the lithostatic load (above). earlyK: earlyBulkModuli before the switch. Does
// nothing when par.overburdenDensity is 0 or there is no uniform gravity.
void keepOverburden(SphState& s, const SphParams& par, const std::vector<double>& earlyK);

} // namespace craterkit

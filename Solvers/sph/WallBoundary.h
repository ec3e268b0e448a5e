// Rigid-particle walls of the SPH solver with the pressure extrapolated from the adjacent
// material (Adami, Hu & Adams 2012, J. Comput. Phys. 231:7057, Eqs. 27–28).
//
// For each rigid particle w, over its non-rigid neighbours f inside the pair support
// (h̄ = ½(h_w + h_f), W_wf = W(|r_wf|, h̄), r_wf = x_w − x_f):
//   p_w = (Σ_f p_f W_wf + (g_w − a_w) · Σ_f ρ_f r_wf W_wf) / Σ_f W_wf      (Adami Eq. 27)
// g_w the body force at the wall (uniform gravity plus the point mass), a_w = 0 (rigid
// particles are at rest). The extrapolation is exact for a hydrostatic (linear) pressure
// field; a wall with no such neighbour inside the support keeps what its own state gives (no
// one reads it). p_w is not taken below the most tensile pressure of its neighbours, nor below 0
// when they hold none, so the wall never pulls a cohesionless material (as PySPH's
// ClampWallPressure, which clamps at 0).
//   Density (Adami Eq. 28): ρ_w from the inverse of the wall material's equation of state,
// p(α ρ_w, u_w)/α = p_w, so that the wall's p/ρ² and volume m/ρ match its pressure instead of
// drifting with the continuity equation; ρ_w = ρ0/α where p_w is at or below the law's
// pressure there; unchanged for a law without a reference density (ideal gas).
//   Deviatoric stress: the wall's own (Hooke's law with its velocity gradient against the
// adjacent flow, as for dynamic boundary particles), limited by its material's yield at p_w.
// Not the Shepard average Σ S_f W / Σ W with the body force on the diagonal only (the form of
// PySPH's AdamiBoundaryConditionExtrapolate for solids): that wall carries the soil's S with a
// pressure raised by the weight term, so its S_xz/p falls below the soil's friction (0.51–0.59
// against 3B = 0.693 measured), the wall is smoother than the soil and a stiff layer at 35°
// slides on it 11 times faster than the yield law allows (docs/validation.md, "The infinite
// slope, analysed"). A wall of the material's own yield holds the adjacent soil by the soil's
// friction.
//   Artificial viscosity: none between a wall and the material by default
// (SphParams::wallViscosity = 0, applied in the pair terms; Adami et al. 2012 keep no viscous
// interaction with a free-slip wall either). Monaghan's term acts only on approaching pairs, so
// a particle sliding at speed v over the wall's particle lattice is pushed up and back by the
// wall particles ahead of it and not held by those behind: a net lift whose scale, α (c_a +
// c_b) v ρ, is 30 kPa at 1 m/s for the test soil (α = 0.5, K = 0.4 MPa), against 2.3 kPa of
// weight on the floor of its 0.2 m layer. On the 40° slope it lifted the lowest soil row
// off the floor after about 1 s, and the layer slid on it as a block at 2.02 m/s² against the
// yield law's 1.10 (1.20 without it; docs/validation_history.md, "The infinite slope, analysed").
// The wall holds the material by its extrapolated pressure and, in shear, by its deviatoric stress,
// whose rate takes the wall's own velocity (zero: no slip in the strain rate). The impact
// set-up's container keeps the viscosity (factor 1) to absorb the shock; with the bilateral
// form (receding pairs too) the lowest row stays down but a 40° layer still gains 1.81 m/s²
// (a trial, not kept), so the lift is not the viscosity's only effect on the floor's friction.
//   Why: with dynamic boundary particles (Crespo et al. 2007: the wall's density by continuity
// and its pressure from its own state) a column at rest keeps a row-to-row alternation of its
// pressure (±17–25 % in the test), the floor's rows carry 0.96 and 0.07 of the hydrostatic
// load, and a dilating layer lowers the floor's density and pressure to zero.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct SphState;
struct SphParams;
class NeighbourList;

class WallBoundary {
public:
  // Sets p, the density and the signal speed c of every rigid particle of s with a non-rigid
  // neighbour, and limits its deviatoric stress S, as above (nb: the current list). Reads only
  // non-rigid particles, so the order of the walls does not matter. Walls without such
  // neighbours keep what their own state gives: no one reads them.
  // With `need`, only the walls i with need[i] != 0 (block steps: those an updated particle
  // reads); the others keep what their own state gives.
  void apply(SphState& s, std::vector<double>& p, std::vector<double>& c, const SphParams& par,
             const NeighbourList& nb, const std::vector<char>* need = nullptr);

private:
  // The walls with non-rigid neighbours and those neighbours' list entries (index * 32 + image
  // code), compacted once per list: most of a container's particles lie deeper than one support
  // from its face, and most entries of a wall near it are walls.
  void compact(const SphState& s, const std::vector<char>& rigid, const NeighbourList& nb);
  std::size_t builds_ = 0, size_ = 0; // the list (its version) and state compacted
  std::vector<std::uint32_t> wall_, start_, entry_;
};

} // namespace craterkit

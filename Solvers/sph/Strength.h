// Strength and porosity of solids for the SPH solver.
//   Elasticity: Hooke's law for the deviatoric stress with the Jaumann rate,
//     dS/dt = 2G (ε̇ − ⅓ tr ε̇ I) + R S − S R (docs/physics.md §2.2).
//   Yield (docs/physics.md §2.5; Collins, Melosh & Ivanov 2004): S → f S with
//     von Mises (metals): f = min(Y0/√(3 J2), 1), J2 = ½ S:S;
//     Drucker–Prager (granular material), matched to the Mohr–Coulomb compression cone:
//     √J2 ≤ k + 3B p, k = 6c cos φ/(√3 (3 − sin φ)), B = 2 sin φ/(√3 (3 − sin φ)),
//     tension cut at the cone's apex. Damage D (Grady–Kipp, §2.7) scales Y0 and c by (1 − D)
//     and a tension p < 0 by (1 − D).
//   Porosity, P–α (Jutzi et al. 2008; docs/physics.md §2.6): p = p_s(α ρ, u)/α with the quadratic
//     crush curve α(p) = 1 + (α0 − 1)((p_s − p)/(p_s − p_e))² for p_e < p < p_s; α only falls.
#pragma once

#include "sph/Eos.h"
#include "sph/Material.h"

#include <cmath>

namespace craterkit {

// Derived constants of a material's strength and porosity model.
struct Rheology {
  enum Kind { Fluid, VonMises, DruckerPrager } kind = Fluid;
  double G = 0.0;
  double yield = 0.0;           // von Mises: uniaxial yield stress Y0 (√(3 J2) ≤ Y0)
  double dpK = 0.0, dpB3 = 0.0; // Drucker–Prager: √J2 ≤ k + 3B p
  double alpha0 = 1.0, pe = 0.0, ps = 1.0;
  explicit Rheology(const Material& m);
  // α on the quadratic crush curve at bulk pressure p.
  double crushAlpha(double p) const {
    if (p <= pe)
      return alpha0;
    if (p >= ps)
      return 1.0;
    const double t = (ps - p) / (ps - pe);
    return 1.0 + (alpha0 - 1.0) * t * t;
  }
};

// A:B for symmetric tensors stored xx yy zz xy xz yz.
inline double dot6(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

// P–α compaction of a particle of bulk density rho and energy u whose distention alpha gives
// the bulk pressure P: when alpha lies above the crush curve, it falls to the curve (the
// largest value in [1, alpha] on or below it). Returns the bulk pressure at the new alpha.
double compactDistention(const Rheology& r, const EquationOfState& eos, double rho, double u,
                         double& alpha, double P);

// The yield limit on the deviatoric stress S (6 components, scaled in place) at bulk pressure
// P and damage D; returns the pressure after damage and the Drucker–Prager tension cut.
double limitStress(const Rheology& r, double D, double P, double* S);

// The signal speed of a material with bulk sound speed cs at density rho: solids carry shear
// waves too, so theirs is the longitudinal one, c² = c_s² + 4G/(3ρ), or the time step is too
// long for a stiff solid (and much too long for a porous one).
inline double signalSpeed(const Rheology& r, double cs, double rho) {
  return r.kind == Rheology::Fluid ? cs : std::sqrt(cs * cs + 4.0 * r.G / (3.0 * rho));
}

// Hooke's law with the Jaumann rate: dS (6 components) from the shear modulus G, the velocity
// gradient grad[3α + β] = ∂_β v^α and the deviatoric stress S.
inline void deviatoricStressRate(double G, const double* grad, const double* S, double* dS) {
  // Strain rate ε̇ = sym(∇v), rotation rate R^{αβ} = ½(∂_β v^α − ∂_α v^β).
  const double exx = grad[0], eyy = grad[4], ezz = grad[8];
  const double exy = 0.5 * (grad[1] + grad[3]), exz = 0.5 * (grad[2] + grad[6]);
  const double eyz = 0.5 * (grad[5] + grad[7]);
  const double wxy = 0.5 * (grad[1] - grad[3]), wxz = 0.5 * (grad[2] - grad[6]);
  const double wyz = 0.5 * (grad[5] - grad[7]);
  const double tr = (exx + eyy + ezz) / 3.0;
  // Full tensors for R S − S R (R antisymmetric, S symmetric: the result is symmetric).
  const double Sm[3][3] = {{S[0], S[3], S[4]}, {S[3], S[1], S[5]}, {S[4], S[5], S[2]}};
  const double R[3][3] = {{0.0, wxy, wxz}, {-wxy, 0.0, wyz}, {-wxz, -wyz, 0.0}};
  auto rot = [&](int i, int j) {
    double v = 0.0;
    for (int k = 0; k < 3; ++k)
      v += R[i][k] * Sm[k][j] - Sm[i][k] * R[k][j];
    return v;
  };
  dS[0] = 2.0 * G * (exx - tr) + rot(0, 0);
  dS[1] = 2.0 * G * (eyy - tr) + rot(1, 1);
  dS[2] = 2.0 * G * (ezz - tr) + rot(2, 2);
  dS[3] = 2.0 * G * exy + rot(0, 1);
  dS[4] = 2.0 * G * exz + rot(0, 2);
  dS[5] = 2.0 * G * eyz + rot(1, 2);
}

} // namespace craterkit

// Bonded-particle interaction law of Watson & Steinhauser 2017, "Discrete Particle Method for
// Simulating Hypervelocity Impact Phenomena", Materials 10:379 (seed 003), Sections 2.2–2.3.
//
// Every pair closer than r_eq = 2^{1/6} σ repels with the Lennard-Jones potential cut at its
// minimum and shifted up by ε (Eq. 3); pairs bonded at set-up also pull back with a quadratic
// spring of stiffness κ when stretched beyond their rest length (Eq. 4); a bond stretched beyond
// r_cut is removed for good. No friction, no damping, no tangential force.
//
// Where the printed equations disagree with each other we follow the text and the derivation:
// - Eqs. 2–3 are printed without the factor 4 of the Lennard-Jones potential, which makes the
//   printed Eq. 3 jump by 0.75 ε at r_eq. The text asks for a potential "shifted upwards by ε to
//   ensure smooth continuity": that is φ = 4ε[(σ/r)^12 − (σ/r)^6] + ε, of depth ε before the
//   shift (also LAMMPS' lj/cut shifted at 2^{1/6} σ). The printed form would only rescale ε by 4.
// - Eq. 5 is printed γ = ε/σ, but Eqs. 12–14 carry σ³γ in the repulsion, and only ε ∝ σ³ makes
//   Φ_tot independent of N (Eq. 19: N ∝ σ^-3 pairs of energy ε each). We use γ = ε/σ³.
// - Eq. 12 writes the bond energy σλ(r − r_eq)² without the ½ of Eq. 4; the factor does not
//   change the scaling. We use Eq. 4.
// Parameters given at one σ (the paper's ε = 0.01 J, κ = 4.56e6 N/m at the headline size) are
// resized to any other σ through γ, λ and r_cut/σ (Eqs. 5–11); masses come from Eq. 20.
#pragma once

#include <cmath>
#include <cstddef>

namespace craterkit {
namespace ws2017 {

constexpr double kTwoToOneSixth = 1.122462048309373; // r_eq / σ (minimum of Eq. 2)

// The three material parameters at one particle diameter σ (SI: m, J, N/m, m).
struct Law {
  double sigma = 0.0;
  double epsilon = 0.0;
  double kappa = 0.0;
  double rCut = 0.0;
  double rEq() const { return kTwoToOneSixth * sigma; }
};

// Length-invariant parameters: γ = ε/σ³ (Eq. 5 as used in Eqs. 12–14), λ = κ/σ (Eq. 6),
// and r_cut/σ (Eq. 11).
struct Sizing {
  double gamma = 0.0;
  double lambda = 0.0;
  double rCutOverSigma = 1.5;
};

// Eqs. 5, 6, 11: the invariants of a law given at its σ.
Sizing sizingOf(const Law& law);
// Eqs. 8–11 solved for the parameters at a new σ: ε = γσ³, κ = λσ, r_cut = (r_cut/σ) σ.
Law sizedLaw(const Sizing& sizing, double sigma);
// Eq. 20: m = M / N.
double particleMass(double bodyMass, std::size_t count);
// Period 2π √(m/κ) of one bond spring between a particle and a fixed wall; Δt is a fraction
// of it, so that Δt ∝ σ like every other time scale of the sized model.
double bondPeriod(double mass, double kappa);

// The paper's headline body: Al sphere D = 9.53 mm on an Al plate t/D = 0.425, here 4D × 4D
// wide, on a cubic lattice of spacing r_eq holding N = 7.4e5 particles (Section 2.3.2); its σ
// is where ε = 0.01 J and κ = 4.56e6 N/m apply, and its Δt = 1e-10 s (Figure 12).
constexpr double kHeadlineDiameter = 9.53e-3;
constexpr double kHeadlineThicknessRatio = 0.425;
constexpr double kHeadlinePlateWidthRatio = 4.0;
constexpr double kHeadlineParticles = 7.4e5;
constexpr double kHeadlineDensity = 2700.0;
constexpr double kHeadlineEpsilon = 0.01;
constexpr double kHeadlineKappa = 4.56e6;
constexpr double kHeadlineTimeStep = 1e-10;
double headlineSigma();
// Δt / bondPeriod at the headline size (about 2.2e-4): the same fraction at any σ.
double referenceTimeStepFraction();

// Eq. 3 (with the factor 4, see above), for r² < r_eq² only: returns the pair energy and sets
// forceOverR = −(dφ/dr)/r, so that the force on i is forceOverR · (x_i − x_j).
inline double repulsion(double r2, double sigma2, double epsilon, double& forceOverR) {
  const double s2 = sigma2 / r2;
  const double s6 = s2 * s2 * s2;
  forceOverR = 24.0 * epsilon * s6 * (2.0 * s6 - 1.0) / r2;
  return 4.0 * epsilon * s6 * (s6 - 1.0) + epsilon;
}

// Eq. 4 with the bond's rest length r0 (r_eq on the paper's lattice): energy ½κ(r − r0)² for
// r > r0, else 0; sets forceOverR so that the force on i is forceOverR · (x_j − x_i).
inline double bondSpring(double r, double r0, double kappa, double& forceOverR) {
  if (!(r > r0)) {
    forceOverR = 0.0;
    return 0.0;
  }
  const double stretch = r - r0;
  forceOverR = kappa * stretch / r;
  return 0.5 * kappa * stretch * stretch;
}

// Constants of pairForceOverR: σ², ε, κ and r_eq².
struct PairTerms {
  double sigma2 = 0.0, epsilon = 0.0, kappa = 0.0, rEq2 = 0.0;
};

// Eqs. 3 and 4 of one pair at once, for the solver's pair loop: returns forceOverR so that the
// force on i is forceOverR · (x_i − x_j), the repulsion (as repulsion() above, for 0 < r² <
// r_eq²) minus the pull of an intact bond of rest length r0 (as bondSpring() above, for r > r0;
// r0 = +∞ where the pair has no intact bond). Branch-free (both terms are computed and the
// unused one is dropped by a select), with one division and one square root, so that a loop over
// pairs vectorises; it differs from the two functions above only by rounding. r² = 0 gives 0.
inline double pairForceOverR(double r2, double r0, const PairTerms& p) {
  const double inv = 1.0 / r2;
  const double s2 = p.sigma2 * inv, s6 = s2 * s2 * s2;
  const bool near = (r2 < p.rEq2) & (r2 > 0.0);
  const double repel = near ? 24.0 * p.epsilon * s6 * (2.0 * s6 - 1.0) * inv : 0.0;
  const double r = std::sqrt(r2);
  const double pull = r > r0 ? p.kappa * (r - r0) * (r * inv) : 0.0; // κ (r − r0) / r
  return repel - pull;
}

} // namespace ws2017
} // namespace craterkit

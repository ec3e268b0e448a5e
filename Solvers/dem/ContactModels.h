// Soft-sphere contact laws of pkdgrav's SSDEM.
//
// Normal laws (chosen at run time by name):
//   LinearSpringDashpot  F_N = -k_N x n + C_N u_n, C_N from the normal restitution
//                        (Schwartz, Richardson & Michel 2012, Granular Matter 14:363, Eqs. 3,
//                        15-16).
//   Hertz                F_N = -(4/3) E* sqrt(r x) x n + C u_n with C from the restitution as in
//                        Tsuji et al. 1992 (the form LIGGGHTS' hertz model uses).
// Friction (Schwartz et al. 2012 Eqs. 6-7, 17-19; rolling and twisting spring-dashpot-slider
// with shape parameter beta, pkdgrav's DEM_ROTATION_DASHPOT after Jiang, Shen & Wang 2015
// and Zhang et al. 2017, Icarus 294:98): see docs/physics.md §1.3-1.4 for every equation used here.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace craterkit {

struct ContactParams {
  std::string normalModel = "LinearSpringDashpot"; // or "Hertz"
  double kN = 1.0e6;                               // normal stiffness, N/m (linear law)
  double kT = -1.0;           // tangential stiffness, N/m; < 0 means 2/7 k_N (pkdgrav default)
  double restitutionN = 0.55; // normal coefficient of restitution ε_n
  double restitutionT = 0.55; // tangential ε_t (sets C_T)
  double muS = 0.6;           // static (sliding) friction
  // μ_r and μ_t are calibrated so that, with μ_s = 0.6 and β = 0.5, a heap's angle of repose
  // is 30° (the friction angle of the SCI study's regolith; benchmarks/README.md).
  double muR = 0.35;            // rolling friction
  double muT = 0.4375;          // twisting friction
  double beta = 0.5;            // shape parameter (contact size relative to the reduced radius)
  double cohesion = 0.0;        // Pa; attractive normal force c 4 (beta r)^2 per contact
  double youngsModulus = 1.0e8; // Pa (Hertz)
  double poissonRatio = 0.25;   // (Hertz)

  double tangentialStiffness() const { return kT < 0.0 ? 2.0 / 7.0 * kN : kT; }
  void validate() const; // throws InputError naming the bad coefficient
};

// Damping coefficient C = 2 sqrt(k mu) (-ln e) / sqrt(pi^2 + ln^2 e) (Schwartz 2012 Eq. 15),
// split into the restitution factor (computed once per run) and sqrt(k mu).
inline double dashpotFactor(double restitution) {
  if (restitution >= 1.0)
    return 0.0;
  const double l = std::log(std::max(restitution, 1e-12));
  return 2.0 * (-l) / std::sqrt(M_PI * M_PI + l * l);
}
inline double dashpotCoefficient(double k, double restitution, double reducedMass) {
  return dashpotFactor(restitution) * std::sqrt(k * reducedMass);
}

// History of one contact, carried in the contact frame between steps.
struct ContactHistory {
  double spring[3] = {0, 0, 0};  // tangential spring S
  double rolling[3] = {0, 0, 0}; // rolling displacement ξ_R
  double twisting = 0.0;         // twisting angle ξ_Q
  double normal[3] = {0, 0, 0};  // contact normal at the previous step (0 = new contact)
  void clear() { *this = ContactHistory{}; }
  bool fresh() const { return normal[0] == 0.0 && normal[1] == 0.0 && normal[2] == 0.0; }
};

// Geometry and kinematics of a contact seen from particle p (n is the partner or a wall).
struct ContactState {
  Eigen::Vector3d n;     // unit normal from p towards n
  double overlap;        // x > 0
  double leverP, leverN; // distances from the centres to the contact point (leverN = inf: wall)
  // Velocity of n's surface relative to p's at the contact point:
  // u = v_n - v_p + l_n (n x w_n) + l_p (n x w_p). (docs/physics.md §1.1 prints "- l_p"; p's
  // contact point is at +l_p n, whose velocity is v_p + w_p x l_p n = v_p - l_p n x w_p.)
  Eigen::Vector3d u;
  Eigen::Vector3d omegaRel; // ω_n - ω_p
  Eigen::Vector3d omegaSum; // ω_p + ω_n (frame spin)
  double reducedMass;
  double reducedRadius;
};

struct ContactResult {
  Eigen::Vector3d force;   // on p (n gets minus this)
  Eigen::Vector3d torqueP; // on p
  Eigen::Vector3d torqueN; // on n
};

// Constants of the friction part, computed once per force evaluation.
struct FrictionConstants {
  explicit FrictionConstants(const ContactParams& p)
      : kT(p.tangentialStiffness()), dampingT(dashpotFactor(p.restitutionT)), sqrtKT(std::sqrt(kT)),
        muS(p.muS), muR(p.muR), muT(p.muT), beta(p.beta), cohesion(p.cohesion) {}
  double kT, dampingT, sqrtKT;
  double muS, muR, muT, beta, cohesion; // copies of ContactParams', for the contact loops
};

// The normal laws act without tension: a cohesionless contact's normal force is clipped at
// zero when the dashpot would pull the grains together as they separate (as LAMMPS's
// `limit_damping`); the contact then ends before the overlap closes. So that ε_n keeps its
// meaning (the ratio of rebound to impact speed in a head-on collision), the damping factor is
// the one for which the clipped law rebounds with ε_n (Schwäger & Pöschel 2007, Granular
// Matter 9:465, for the linear law), found once per run by clippedDampingFactor.
enum class NormalLawKind { LinearSpringDashpot, Hertz };

// The dimensionless damping factor f (C = f sqrt(k_eff m)) for which a head-on collision
// under the clipped law of KIND rebounds with RESTITUTION. Without clipping, the linear law
// has f = dashpotFactor(ε) (Schwartz 2012 Eq. 15); with it f is larger, and the linear law
// cannot rebound slower than ε = e^-2 while underdamped. Solved by bisection on a numerical
// collision (an RK4 integration of the one-dimensional contact in units where m = 1 and the
// elastic force at unit overlap is 1; ε does not depend on the impact speed for either law).
double clippedDampingFactor(NormalLawKind kind, double restitution);
// Restitution of the clipped law of KIND with damping factor F, and the contact's duration in
// the dimensionless units above (impact speed 1); for tests and for clippedDampingFactor.
double clippedRestitution(NormalLawKind kind, double factor, double* duration = nullptr);

// A normal law: elastic force magnitude, the stiffness used for rolling and twisting
// springs, the dashpot coefficient, and the stored elastic energy. FACTOR is the damping
// factor of clippedDampingFactor.
struct LinearSpringDashpot {
  LinearSpringDashpot(double k, double factor) : kN(k), factor(factor * std::sqrt(k)) {}
  double kN, factor; // factor includes sqrt(k_N)
  double elastic(double x, double) const { return kN * x; }
  double stiffness(double, double) const { return kN; }
  double damping(double, double, double mu) const { return factor * std::sqrt(mu); }
  double energy(double x, double) const { return 0.5 * kN * x * x; }
  // The tangential spring: TangentialStiffness (2/7 k_N unless set; Schwartz 2012 Eq. 17).
  double tangentialStiffness(double, double, const FrictionConstants& fc) const { return fc.kT; }
  double tangentialRoot(double, double, const FrictionConstants& fc) const { return fc.sqrtKT; }
};

struct Hertz {
  // E* = E / (2 (1 - ν^2)) between two particles of one material, E / (1 - ν^2) against a
  // rigid wall. Damping C = f sqrt(k(x) m) with k(x) = 2 E* sqrt(r x) (Tsuji et al. 1992's
  // form, so that ε does not depend on the impact speed).
  // The tangential spring follows Mindlin's no-slip stiffness 8 G* sqrt(r x), which is
  // 2 (1 - ν) / (2 - ν) of the normal tangent stiffness for one material (and against a rigid
  // wall): TangentialStiffness does not apply.
  Hertz(double modulus, double factor, double poisson)
      : effectiveModulus(modulus), factor(factor),
        tangentialRatio(2.0 * (1.0 - poisson) / (2.0 - poisson)) {}
  double effectiveModulus, factor, tangentialRatio;
  double elastic(double x, double r) const {
    return 4.0 / 3.0 * effectiveModulus * std::sqrt(r * x) * x;
  }
  double stiffness(double x, double r) const { return 2.0 * effectiveModulus * std::sqrt(r * x); }
  double damping(double x, double r, double mu) const {
    return factor * std::sqrt(stiffness(x, r) * mu);
  }
  double energy(double x, double r) const {
    return 8.0 / 15.0 * effectiveModulus * std::sqrt(r) * std::pow(x, 2.5);
  }
  double tangentialStiffness(double x, double r, const FrictionConstants&) const {
    return tangentialRatio * stiffness(x, r);
  }
  double tangentialRoot(double x, double r, const FrictionConstants& fc) const {
    return std::sqrt(tangentialStiffness(x, r, fc));
  }
};

// Plain-number helpers of the lane kernel below. Each keeps the operation order of Eigen's
// fixed-size 3-vectors (a dot product is (a0 b0 + a1 b1) + a2 b2), so that the kernel gives
// the same bits as the vector form it replaced.
#if defined(__GNUC__)
#define CK_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define CK_ALWAYS_INLINE inline
#endif
CK_ALWAYS_INLINE double dot3(const double a[3], const double b[3]) {
  return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2];
}
CK_ALWAYS_INLINE void cross3(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// One contact as plain numbers (see ContactState, ContactHistory and ContactResult for the
// meaning of each field): what ssdemContactLane reads and writes. Loops over a table of
// contacts fill one per contact and run several contacts at once, one per SIMD lane.
struct ContactLane {
  double n[3], overlap, leverP, leverN, u[3], omegaRel[3], omegaSum[3], reducedMass, reducedRadius;
  double spring[3], rolling[3], twisting, normal[3]; // the history, updated in place
  double force[3], torqueP[3], torqueN[3];           // the result
};

// Rotates history vectors with the contact frame (docs/physics.md §1.3 (a)-(b)). Written
// without branches (both ways computed, one kept) so that a loop over contacts vectorises;
// the kept value is the one the branch would give, bit for bit.
// n is the new normal, nOld the last one, S and xi the tangential spring and the rolling
// displacement.
CK_ALWAYS_INLINE void carryContactFrame(const double n[3], const double nOld[3],
                                        const double omegaSum[3], double S[3], double xi[3],
                                        double dt) {
  // (a) spin about the mean normal by φ = dt/2 (ω_p + ω_n)·n_mean. Cayley form with
  // q = (φ/2) a: exactly orthogonal, no trigonometry, angle error O(φ³) for the tiny
  // per-step angles of a resolved contact.
  double mean[3] = {nOld[0] + n[0], nOld[1] + n[1], nOld[2] + n[2]};
  const double len2 = dot3(mean, mean);
  const double len = std::sqrt(len2);
  for (int k = 0; k < 3; ++k)
    mean[k] = mean[k] / len;
  const double phi = 0.25 * dt * dot3(omegaSum, mean);
  const double q[3] = {phi * mean[0], phi * mean[1], phi * mean[2]};
  const double q2 = dot3(q, q);
  const bool spin = (len2 > 0.0) & (q2 > 0.0);
  const double f = 2.0 / (1.0 + q2);
  double qS[3], qX[3], qqS[3], qqX[3];
  cross3(q, S, qS);
  cross3(q, xi, qX);
  cross3(q, qS, qqS);
  cross3(q, qX, qqX);
  for (int k = 0; k < 3; ++k) {
    S[k] = spin ? S[k] + f * (qS[k] + qqS[k]) : S[k];
    xi[k] = spin ? xi[k] + f * (qX[k] + qqX[k]) : xi[k];
  }
  // (b) the rotation taking n_old to n (Rodrigues with k = n_old x n, c = n_old·n):
  // R v = c v + k x v + (k·v) k / (1 + c).
  double kv[3];
  cross3(nOld, n, kv);
  const double cosine = dot3(nOld, n);
  const bool turn = (dot3(kv, kv) > 0.0) & (cosine > -1.0);
  const double g = 1.0 / (1.0 + cosine);
  double kS[3], kX[3];
  cross3(kv, S, kS);
  cross3(kv, xi, kX);
  const double gS = g * dot3(kv, S), gX = g * dot3(kv, xi);
  for (int k = 0; k < 3; ++k) {
    S[k] = turn ? (cosine * S[k] + kS[k]) + gS * kv[k] : S[k];
    xi[k] = turn ? (cosine * xi[k] + kX[k]) + gX * kv[k] : xi[k];
  }
  // Keep the histories in the tangent plane against round-off drift.
  const double sn = dot3(S, n), xn = dot3(xi, n);
  for (int k = 0; k < 3; ++k) {
    S[k] = S[k] - sn * n[k];
    xi[k] = xi[k] - xn * n[k];
  }
}

// Objective rolling rate of Kuhn & Bagi (2004, Int. J. Solids Struct. 41:5793): the mean
// travel of the contact point over the two surfaces, as an angular rate about the tangent
// plane. With c = x_p + l_p n, the contact point crosses p's surface at a_p = c' - v_p -
// w_p x l_p n and n's at a_n = c' - v_n + w_n x l_n n; their mean, (a_p + a_n)/2, is
// R* (w_n - w_p) x n + (l_p - l_n)/(2 (l_p + l_n)) u_T with R* = l_p l_n / (l_p + l_n) and u the
// sliding velocity of ContactState. Divided by R* and turned into a rate about the tangent
// plane (n x): w_R = (w_n - w_p)_T + (1/l_n - 1/l_p)/2 (n x u) (docs/physics.md §1.4). For a
// wall (l_n = inf) the second term is -(n x u)/(2 l_p): a sphere that slides without turning
// still rolls at half the rate of its travel; one that slides with back-spin v/l_p does not.
inline Eigen::Vector3d rollingRate(const ContactState& c) {
  const Eigen::Vector3d& n = c.n;
  const double invN = std::isfinite(c.leverN) ? 1.0 / c.leverN : 0.0;
  return c.omegaRel - c.omegaRel.dot(n) * n + 0.5 * (invN - 1.0 / c.leverP) * n.cross(c.u);
}

// One contact: normal law + SSDEM tangential, rolling and twisting resistance, on plain
// numbers and without branches (both ways computed, one kept; every division done whatever
// the case, so that the compiler need not fear a trap in a lane that would not have run it),
// so that a loop over a table of contacts runs several at once.
template <class Normal> CK_ALWAYS_INLINE void
ssdemContactLane(const Normal& law, const FrictionConstants& fc, ContactLane& c, double dt) {
  const double x = c.overlap, rr = c.reducedRadius;
  const double kT = law.tangentialStiffness(x, rr, fc);
  const double* n = c.n;
  const double un = dot3(c.u, n);
  double uT[3];
  for (int k = 0; k < 3; ++k)
    uT[k] = c.u[k] - un * n[k];
  const double cN = law.damping(x, rr, c.reducedMass);
  // F_N is along n: keep its signed magnitude (spring, dashpot, cohesion).
  double fNsigned = -law.elastic(x, rr) + cN * un;
  const double a = fc.beta * rr;
  fNsigned = fc.cohesion > 0.0 ? fNsigned + fc.cohesion * 4.0 * a * a : fNsigned;
  // No tension: a cohesionless contact's force is clipped at zero (see NormalLawKind), and
  // friction, rolling and twisting are limited by the compressive load alone, so a sliding
  // contact's tangential impulse is μ_s times its normal impulse.
  fNsigned = fc.cohesion == 0.0 ? std::min(fNsigned, 0.0) : fNsigned;
  const double fNmag = std::max(-fNsigned, 0.0);

  // A fresh contact (no normal yet) has no history to carry.
  const bool fresh = (c.normal[0] == 0.0) & (c.normal[1] == 0.0) & (c.normal[2] == 0.0);
  double S[3], xiR[3];
  for (int k = 0; k < 3; ++k) {
    S[k] = c.spring[k];
    xiR[k] = c.rolling[k];
  }
  carryContactFrame(n, c.normal, c.omegaSum, S, xiR, dt);
  for (int k = 0; k < 3; ++k) {
    S[k] = fresh ? c.spring[k] : S[k];
    xiR[k] = fresh ? c.rolling[k] : xiR[k];
  }
  // Tangential spring and Coulomb slider; pkdgrav zeroes the spring when it slips.
  const double cT = fc.dampingT * law.tangentialRoot(x, rr, fc) * std::sqrt(c.reducedMass);
  double fT[3];
  for (int k = 0; k < 3; ++k) {
    S[k] = S[k] + uT[k] * dt;
    fT[k] = kT * S[k] + cT * uT[k];
  }
  const double fTmax = fc.muS * fNmag;
  const bool slip = dot3(fT, fT) > fTmax * fTmax;
  const double ut = std::sqrt(dot3(uT, uT));
  const double slideAny = std::min(fTmax, cT * ut) / ut;
  const double slide = ut > 0.0 ? slideAny : 0.0;
  for (int k = 0; k < 3; ++k) {
    S[k] = slip ? 0.0 : S[k];
    fT[k] = slip ? slide * uT[k] : fT[k];
  }

  // Rolling and twisting (computed even when off, then dropped: no branch in the loop).
  const bool rolling = fc.muR > 0.0, twisting = fc.muT > 0.0;
  const double br = fc.beta * rr;
  const double kN = law.stiffness(x, rr);
  const double twistRate = dot3(c.omegaRel, n);
  // rollingRate above, component by component.
  const double invAny = 1.0 / c.leverN;
  const double invN = std::isfinite(c.leverN) ? invAny : 0.0;
  const double half = 0.5 * (invN - 1.0 / c.leverP);
  double nxu[3], omegaR[3];
  cross3(n, c.u, nxu);
  for (int k = 0; k < 3; ++k)
    omegaR[k] = (c.omegaRel[k] - twistRate * n[k]) + half * nxu[k];
  const double kR = kN * br * br, cR = cN * br * br, mRmax = fc.muR * br * fNmag;
  double mR[3], xiNew[3];
  for (int k = 0; k < 3; ++k) {
    xiNew[k] = xiR[k] + omegaR[k] * dt;
    mR[k] = kR * xiNew[k];
  }
  const double m2 = dot3(mR, mR);
  // Slipping: the spring stays at the limit (not at its last length, which would keep
  // more than the limit when the load drops and drive the grain once the rolling turns
  // back; docs/physics.md §1.4).
  const bool rollSlip = m2 > mRmax * mRmax;
  const double scale = mRmax / std::sqrt(m2);
  for (int k = 0; k < 3; ++k) {
    const double limited = mR[k] * scale, back = limited / kR;
    xiNew[k] = rollSlip ? back : xiNew[k];
    mR[k] = rollSlip ? limited : mR[k] + cR * omegaR[k];
    xiR[k] = rolling ? xiNew[k] : xiR[k];
    mR[k] = rolling ? mR[k] : 0.0;
  }
  const double kQ = 2.0 * kT * br * br, cQ = 2.0 * cT * br * br;
  const double mQmax = fc.muT * br * fc.muS * fNmag;
  const double turned = c.twisting + twistRate * dt;
  const double trial = kQ * turned;
  const bool twistSlip = std::abs(trial) > mQmax;
  const double limit = std::copysign(mQmax, trial), held = limit / kQ;
  const double mQn = twistSlip ? limit : trial + cQ * twistRate;
  c.twisting = twisting ? (twistSlip ? held : turned) : c.twisting;
  double mQ[3];
  for (int k = 0; k < 3; ++k)
    mQ[k] = twisting ? mQn * n[k] : 0.0; // +0 when off, as the vector form had
  for (int k = 0; k < 3; ++k) {
    c.spring[k] = S[k];
    c.rolling[k] = xiR[k];
    c.normal[k] = n[k];
  }
  double nxT[3];
  cross3(n, fT, nxT);
  const double leverN = std::isfinite(c.leverN) ? c.leverN : 0.0;
  for (int k = 0; k < 3; ++k) {
    c.force[k] = fNsigned * n[k] + fT[k];
    c.torqueP[k] = (c.leverP * nxT[k] + mR[k]) + mQ[k];
    c.torqueN[k] = (leverN * nxT[k] - mR[k]) - mQ[k];
  }
}

// The same on the vector types: one contact seen from p (fc must be FrictionConstants(p)).
template <class Normal> inline ContactResult ssdemContact(const Normal& law, const ContactParams& p,
                                                          const FrictionConstants& fc,
                                                          const ContactState& c, ContactHistory& h,
                                                          double dt) {
  (void)p; // its coefficients are in fc
  ContactLane lane;
  for (int k = 0; k < 3; ++k) {
    lane.n[k] = c.n[k];
    lane.u[k] = c.u[k];
    lane.omegaRel[k] = c.omegaRel[k];
    lane.omegaSum[k] = c.omegaSum[k];
    lane.spring[k] = h.spring[k];
    lane.rolling[k] = h.rolling[k];
    lane.normal[k] = h.normal[k];
  }
  lane.overlap = c.overlap;
  lane.leverP = c.leverP;
  lane.leverN = c.leverN;
  lane.reducedMass = c.reducedMass;
  lane.reducedRadius = c.reducedRadius;
  lane.twisting = h.twisting;
  ssdemContactLane(law, fc, lane, dt);
  ContactResult out;
  for (int k = 0; k < 3; ++k) {
    h.spring[k] = lane.spring[k];
    h.rolling[k] = lane.rolling[k];
    h.normal[k] = lane.normal[k];
    out.force[k] = lane.force[k];
    out.torqueP[k] = lane.torqueP[k];
    out.torqueN[k] = lane.torqueN[k];
  }
  h.twisting = lane.twisting;
  return out;
}

// Undamped duration of a contact between two particles of mass m (reduced mass m/2) on a
// spring k: τ = π sqrt(m / (2k)) (Schwartz 2012 Eq. 4). The DEM's stability check, the
// proposed stiffness and chooseStiffnessAndStep (dem/DemSetup.h) all use this one formula.
inline double pairCollisionTime(double mass, double k) { return M_PI * std::sqrt(0.5 * mass / k); }
// Duration of an undamped Hertz contact of a sphere (mass m, radius r) with a rigid wall of
// effective modulus E* = E/(1 - ν²) at impact speed v: 2.868 (m² / (r E*² v))^(1/5) (Hertz 1882;
// Johnson 1985, Contact Mechanics §11.4). The wall contact is the shortest of a bed (a pair of
// equal spheres lasts 2^(1/5) times longer).
inline double hertzCollisionTime(double m, double r, double effectiveModulus, double v) {
  return 2.868 * std::pow(m * m / (r * effectiveModulus * effectiveModulus * v), 0.2);
}
// The Hertz contact's stability time that DemSolver checks the step against: the linear
// collision time of the wall contact's tangent stiffness at 1 % overlap.
inline double hertzStabilityTime(double m, double r, double effectiveModulus) {
  return pairCollisionTime(m, 2.0 * effectiveModulus * std::sqrt(r * 0.01 * r));
}

// Proposed k_N and time step (Schwartz 2012 Eqs. 4-5, 36-39; docs/physics.md §1.6).
struct StiffnessProposal {
  double kN;            // N/m
  double collisionTime; // s, undamped, smallest pair
  double dt;            // s
};
StiffnessProposal proposeStiffness(double smallestRadius, double density, double maxSpeed,
                                   double overlapFraction, double gravity, double bedHeight,
                                   double stepsPerCollision = 30.0);

} // namespace craterkit

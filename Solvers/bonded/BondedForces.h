// The force pass of the bonded-particle model (Watson & Steinhauser 2017, Eqs. 3–4, see
// WatsonSteinhauser2017.h) over the solver's pair lists in blocks of eight particles, in two
// versions: the generic pass (BondedForces.cpp, cloned for AVX-512 by common/SimdClones.h) and the
// same pass written with AVX-512 intrinsics (BondedForcesAvx512.cpp): the eight lanes of a block
// are the eight doubles of one 512-bit register (GCC 12's AVX-512 clone of the generic pass runs
// them as two 256-bit halves), and bond breaks are masked stores.
//
// Each lane of the intrinsics pass does the operations of the compiled AVX-512 clone of the
// generic pass in the same order, including its fused multiply-adds (r² = dz² + (dx² + dy²),
// the spring's pull subtracted from the repulsion, each force component accumulated, the half
// kick), and its file is compiled with -ffp-contract=off so that no other operation is fused: on
// a processor with AVX-512 both give the same bits (asserted by
// BondedForces.Avx512PassEqualsTheGenericPassBitForBit), so runs do not depend on which ran. The
// AVX-512 pass with the next step's kick-drift block by block (blockForcesDriftAvx512) gives the
// bits of the pass followed by driftAvx512 (asserted by
// BondedForces.KickDriftBlockByBlockEqualsThePassThenTheKickDrift).
#pragma once

#include "bonded/WatsonSteinhauser2017.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace craterkit {
namespace bondedpass {

// List entries' rest lengths: no intact bond; a bond the current pass found beyond r_cut.
constexpr double kNoBond = std::numeric_limits<double>::infinity();
constexpr double kBreaking = -1.0;
// The same in the compact lists' 4-byte offsets (BlockPass::offset): +∞ decodes to kNoBond; −∞
// marks a break (never decoded: the solver books and clears the marks after each pass).
constexpr float kNoBondOffset = std::numeric_limits<float>::infinity();
constexpr float kBreakingOffset = -std::numeric_limits<float>::infinity();
constexpr std::size_t kLanes = 8;

// One force pass over blocks of kLanes particles: block b's entries are [blockStart[b],
// blockStart[b + 1]), entry k of its lane l at blockStart[b] + k kLanes + l. Each entry's rest
// length is either the double rest[e] (the wide lists) or, where rest is null, restRef +
// offset[e] (the compact lists, 8 bytes an entry in place of 12), one rounded addition in both
// passes; the solver uses the compact lists where that sum is every bond's rest length exactly.
struct BlockPass {
  const double* x;
  std::size_t n;
  const std::size_t* blockStart;
  const std::uint32_t* partner;
  double* rest;   // null: the compact lists
  float* offset;  // the compact lists' rest lengths less restRef
  double restRef; // the compact lists' reference rest length
  std::uint32_t* breaks;
  double* force;
  double* v; // null: forces only; else the second half kick too
  const double* m;
  double halfStep;
  ws2017::PairTerms terms;
  double rCut2;
};

// The forces on the particles of blocks [b0, b1): eight particles side by side, each lane
// summing its particle's entries in list order. An intact bond beyond r_cut is marked
// kBreaking (kBreakingOffset in the compact lists), contributes its repulsion only, and is counted
// in its block (p.breaks); the half kick too if p.v. Returns the number of bonds found beyond
// r_cut. Runs anywhere; its AVX-512 clone differs from the plain code by rounding.
long blockForces(const BlockPass& p, std::size_t b0, std::size_t b1);
// Whether this processor runs blockForcesAvx512 (the x86-64-v4 level: AVX-512 F, CD, BW, DQ, VL).
bool avx512Available();
// The forces on the particles of blocks [b0, b1) (and the half kick if p.v): returns the number
// of bonds found beyond r_cut, marked kBreaking (kBreakingOffset in the compact lists) and
// counted per block in p.breaks. Only where
// avx512Available().
long blockForcesAvx512(const BlockPass& p, std::size_t b0, std::size_t b1);

// The velocities after a kick-drift, for the lists' rebuild trigger (BondedListTrigger): the
// largest squared speed and each axis's extremes.
struct VelocitySpread {
  double speed2 = 0.0;
  double lo[3] = {kNoBond, kNoBond, kNoBond}, hi[3] = {-kNoBond, -kNoBond, -kNoBond};
  void add(double vx, double vy, double vz) {
    speed2 = std::max(speed2, vx * vx + vy * vy + vz * vz);
    lo[0] = std::min(lo[0], vx), lo[1] = std::min(lo[1], vy), lo[2] = std::min(lo[2], vz);
    hi[0] = std::max(hi[0], vx), hi[1] = std::max(hi[1], vy), hi[2] = std::max(hi[2], vz);
  }
  void merge(const VelocitySpread& o) {
    speed2 = std::max(speed2, o.speed2);
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], o.lo[k]), hi[k] = std::max(hi[k], o.hi[k]);
  }
  // A bound on any two particles' relative speed: |v_i − v_j| is at most 2 max|v|, and along each
  // axis at most max v_k − min v_k (the bound a common velocity does not change).
  double relativeSpeed() const {
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return std::min(2.0 * std::sqrt(speed2), std::sqrt(dx * dx + dy * dy + dz * dz));
  }
};

// The kick-drift of velocity Verlet over particles [i0, i1) where the force pass ran without its
// half kick (where avx512Available()): first that deferred second half kick of the previous step
// (if `pending`), v = fma(h, f, v), the operation blockForcesAvx512 does; then this step's first
// half kick v += h f and the drift x += Δt v, each product and sum rounded on its own as in the
// solver's generic kick-drift, eight particles at a time. The bits are those of the force pass's
// kick followed by the generic kick-drift, and the force pass no longer streams v and m. Adds the
// velocities after the kicks to `spread`. The drifted positions x + Δt v go to `xOut`: `x` itself,
// or the second position buffer where the kick-drift runs inside the force pass
// (BondedSolver::computeForces).
struct DriftPass {
  const double* x;
  double* xOut;
  double* v;
  const double* f;
  const double* m;
  double dt, halfStep;
  bool pending;
};
void driftAvx512(const DriftPass& p, std::size_t i0, std::size_t i1, VelocitySpread& spread);
// blockForcesAvx512 over blocks [b0, b1) (p.v null) with the kick-drift of driftAvx512 over their
// particles done block by block, on the block's forces and positions still in registers, into
// d.xOut, which must not be p.x (d.f is p.force, d.x is p.x, p.v null: the half kick is the
// drift's pending one): the bits of the pass followed by driftAvx512, and the
// velocities and masses are streamed once, block by block. Only where avx512Available().
long blockForcesDriftAvx512(const BlockPass& p, const DriftPass& d, std::size_t b0, std::size_t b1,
                            VelocitySpread& spread);
// The rebuild's candidate test over a copy of the positions in the cell list's order (x, y, z
// apart, with the particles' indices): which of entries [begin, end) lie closer than the reach to
// `xi`, other than the particle `self`. Their indices are written to `out` (which must have room
// for end - begin + kLanes entries); returns how many. The generic version runs anywhere, the
// AVX-512 one eight candidates at a time where avx512Available(); both give the same list.
struct NearScan {
  const double *x, *y, *z;
  const std::uint32_t* id;
  double reach2;
};
std::size_t nearCandidates(const NearScan& s, std::size_t begin, std::size_t end,
                           const double xi[3], std::uint32_t self, std::uint32_t* out);
std::size_t nearCandidatesAvx512(const NearScan& s, std::size_t begin, std::size_t end,
                                 const double xi[3], std::uint32_t self, std::uint32_t* out);
// The deferred second half kick alone, v = fma(h, f, v), over particles [i0, i1).
void halfKickAvx512(const DriftPass& p, std::size_t i0, std::size_t i1);

} // namespace bondedpass
} // namespace craterkit

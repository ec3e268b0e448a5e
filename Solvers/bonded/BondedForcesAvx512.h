// The force pass of the bonded-particle model (Watson & Steinhauser 2017, Eqs. 3–4, see
// WatsonSteinhauser2017.h) over the solver's pair lists in blocks of eight particles, written
// with AVX-512 intrinsics: the eight lanes of a block are the eight doubles of one 512-bit
// register (GCC 12's AVX-512 clone of the generic pass runs them as two 256-bit halves), and
// bond breaks are masked stores.
//
// Each lane does the operations of the compiled AVX-512 clone of the generic pass (BondedSolver,
// sph/SimdClones.h) in the same order, including its fused multiply-adds (r² = dz² + (dx² +
// dy²), the spring's pull subtracted from the repulsion, each force component accumulated, the
// half kick), and the file is compiled with -ffp-contract=off so that no other operation is
// fused: on a processor with AVX-512 both give the same bits, so runs do not depend on which
// of the two ran.
#pragma once

#include "bonded/WatsonSteinhauser2017.h"

#include <cstddef>
#include <cstdint>
#include <limits>

namespace craterkit {
namespace bondedpass {

// List entries' rest lengths: no intact bond; a bond the current pass found beyond r_cut.
constexpr double kNoBond = std::numeric_limits<double>::infinity();
constexpr double kBreaking = -1.0;
constexpr std::size_t kLanes = 8;

// One force pass over blocks of kLanes particles: block b's entries are [blockStart[b],
// blockStart[b + 1]), entry k of its lane l at blockStart[b] + k kLanes + l.
struct BlockPass {
  const double* x;
  std::size_t n;
  const std::size_t* blockStart;
  const std::uint32_t* partner;
  double* rest;
  std::uint32_t* breaks;
  double* force;
  double* v; // null: forces only; else the second half kick too
  const double* m;
  double halfStep;
  ws2017::PairTerms terms;
  double rCut2;
};

// Whether this processor runs blockForcesAvx512 (AVX-512 F, DQ, BW and VL, as x86-64-v4).
bool avx512Available();
// The forces on the particles of blocks [b0, b1) (and the half kick if p.v): returns the number
// of bonds found beyond r_cut, marked kBreaking and counted per block in p.breaks. Only where
// avx512Available().
long blockForcesAvx512(const BlockPass& p, std::size_t b0, std::size_t b1);

} // namespace bondedpass
} // namespace craterkit

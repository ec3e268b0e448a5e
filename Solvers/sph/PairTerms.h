// The SPH pair terms' data (docs/physics.md §2.2, §2.3: momentum with Monaghan's artificial
// viscosity and the deviatoric stress, continuity, energy with the stress power, velocity
// gradient, XSPH): what a particle's neighbours read of it, packed in one 128-byte record, and
// the per-particle stream of neighbours inside the support that the pair loop runs over.
//
// The pair loop (SphSolver.cpp) reads fifteen fields of each neighbour through its index. As
// plain C++ the compiler loads them lane by lane (354 instructions per eight pairs, most of
// them loads and inserts). `pairSumsWide` (PairTermsWide.cpp) is the same loop written for
// AVX-512: it loads the records of eight neighbours with two 64-byte loads each and transposes
// them in registers (48 shuffles for sixteen fields), then evaluates the same terms in the same
// order. It runs where the processor has AVX-512 (`wideKernelAvailable`); the two differ only
// by rounding (fused multiply-adds, the order of the final lane sum). Both accumulate only
// the particle's own sums, so the result does not depend on the thread count. Its reciprocals
// and square roots start from the processor's 14-bit estimates (vrcp14pd, vrsqrt14pd) refined
// by two Newton steps; the instruction set bounds those estimates but does not fix their bits,
// so a checkpoint continues bit for bit on processors of the same kind (exact division measured
// only 2 % slower, benchmarks/JOURNAL.md, if that ever matters).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

// A particle's position and smoothing length, for the support test.
struct alignas(32) PairPosition {
  double x[3], h;
};

// What the pair terms read of a particle (one 128-byte, cache-line-aligned record: the wide
// loop loads it with two vector loads).
struct alignas(64) PairRecord {
  double v[3];
  double h, rho, m, vol; // vol = m/ρ
  double pr;             // p/ρ²
  double c;
  double s[6];  // S/ρ²
  double rigid; // 1 for a rigid (wall) particle, else 0
};
static_assert(sizeof(PairRecord) == 128, "two 64-byte vector loads per record");

// Per-thread buffers of one particle's interacting neighbours.
struct PairScratch {
  // 64-bit like the doubles: with 32-bit indices the compiler runs the pair loop sixteen wide,
  // two vectors per sum, which spills the sums to memory and leaves up to 15 pairs to scalar code.
  std::vector<std::uint64_t> idx;
  std::vector<double> rx, ry, rz, r2;
  void resize(std::size_t n) {
    idx.resize(n), rx.resize(n), ry.resize(n), rz.resize(n), r2.resize(n);
  }
};

// The pair stream is padded to a multiple of the AVX-512 vector's eight doubles.
constexpr std::size_t kPairLanes = 8;

// What one particle's neighbours add up to (§2.2, §2.3).
struct PairSums {
  double acc[3], dr, de, grad[9], xs[3], sig;
};

struct PairConstants {
  double av, bv, xsph, stressOn, gradOn;
  double
      wallViscosity; // the artificial viscosity's factor between a rigid and a non-rigid particle
  bool periodic;
  double period[3]; // box lengths of the periodic axes
};

// Whether this processor runs pairSumsWide (AVX-512 and a build that has it).
bool wideKernelAvailable();

// The entries of a non-periodic list (index * 32 + image code, sph/NeighbourList.h) inside the
// support of their pair with particle `self`, with their separations, packed into w in list
// order and padded to a multiple of kPairLanes with `self` at separation zero; returns their
// number with the padding (SphSolver.cpp's supportStream, eight entries at a time).
std::size_t supportStreamWide(const PairPosition* positions, std::uint32_t self,
                              const std::uint32_t* entries, std::uint32_t count, PairScratch& w);

// The pair terms of particle A (record A) over the m (a multiple of kPairLanes) pairs of the
// stream w, eight at a time. K: the kernel (sph/Kernels.h); Xsph: with the XSPH term.
template <class K, bool Xsph> PairSums pairSumsWide(const PairRecord* records, const PairRecord& A,
                                                    std::size_t m, const PairScratch& w,
                                                    const PairConstants& pc);

} // namespace craterkit

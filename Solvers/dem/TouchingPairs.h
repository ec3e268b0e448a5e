// The DEM's contact detection over the half Verlet list (pkdgrav SSDEM; Schwartz, Richardson &
// Michel 2012, §2.1): which listed pairs overlap now, |x_j - x_i| < r_i + r_j.
//
// Most listed pairs of a bed are apart, and which are not follows no pattern a branch
// predictor can learn: the loop has no branch on the outcome (each slot is written to the
// output and kept by counting it). An AVX-512 version (gathers of eight pairs' positions, a
// compressed block of slots) was slower on the AMD EPYC of the benchmarks: its gathers cost
// more than the scalar loads (benchmarks/JOURNAL.md, 2026-12-05).
#pragma once

#include <cstddef>
#include <cstdint>

namespace craterkit {

// Tests the listed pairs [begin, end) (particles first[k] < second[k], positions x, radii r):
// writes each touching slot k to `touching` (room for end - begin + 1 entries) and returns how
// many there are. A slot that was in contact (active[k]) and is apart now loses its flag. Two
// particles at the same point count as apart, as they have no normal; a non-finite distance
// counts as touching, so that the overlap check reports it.
std::size_t findTouchingPairs(const double* x, const double* r, const std::uint32_t* first,
                              const std::uint32_t* second, char* active, std::size_t begin,
                              std::size_t end, std::uint32_t* touching);

} // namespace craterkit

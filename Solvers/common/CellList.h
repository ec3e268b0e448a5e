// Uniform-grid cell list for fixed-radius neighbour queries.
//
// Points are binned into cubic cells of at least the requested size with a counting
// sort (O(N), no per-cell allocation). A query visits every cell overlapping the cube
// of half-width `reach` around a point, so it returns a superset of the neighbours
// within `reach`; callers test the distance themselves. The grid never has more than
// a few cells per point, so a tiny cell size on a wide domain cannot exhaust memory.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

class CellList {
public:
  // points: 3*n contiguous coordinates; cellSize > 0.
  void build(const double* points, std::size_t n, double cellSize);

  // Calls visit(j) for every point j in the cells overlapping [x - reach, x + reach].
  template <class Visit>
  void forEachCandidate(const double x[3], double reach, Visit&& visit) const {
    forEachCandidateRange(x, reach, [&](std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s)
        visit(sorted_[s]);
    });
  }

  // The same points as ranges [begin, end) of sorted(), one per row of cells along x: for callers
  // that scan a copy of their coordinates laid out in cell order.
  template <class Visit>
  void forEachCandidateRange(const double x[3], double reach, Visit&& visit) const {
    if (count_ == 0)
      return;
    std::array<long, 3> lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max(0L, cellCoord(x[k] - reach, k));
      hi[k] = std::min(static_cast<long>(dims_[k]) - 1, cellCoord(x[k] + reach, k));
      if (lo[k] > hi[k])
        return;
    }
    for (long cz = lo[2]; cz <= hi[2]; ++cz)
      for (long cy = lo[1]; cy <= hi[1]; ++cy) {
        const std::size_t row = (static_cast<std::size_t>(cz) * dims_[1] + cy) * dims_[0];
        visit(cellStart_[row + lo[0]], cellStart_[row + hi[0] + 1]);
      }
  }

  // The points' indices in cell order.
  const std::vector<std::size_t>& sorted() const { return sorted_; }
  double cellSize() const { return cellSize_; }

private:
  long cellCoord(double v, int k) const {
    const double c = std::floor((v - origin_[k]) / cellSize_);
    // Clamp in double first so that far-away query points cannot overflow a long.
    return static_cast<long>(std::clamp(c, -1.0, static_cast<double>(dims_[k])));
  }

  std::array<double, 3> origin_{};
  std::array<std::size_t, 3> dims_{};
  double cellSize_ = 1.0;
  std::size_t count_ = 0;
  std::vector<std::size_t> cellStart_; // size cells+1
  std::vector<std::size_t> sorted_;    // point indices ordered by cell
};

} // namespace craterkit

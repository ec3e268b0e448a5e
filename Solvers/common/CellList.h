// Uniform-grid cell list for fixed-radius neighbour queries.
//
// Points are binned into cubic cells of at least the requested size with a counting
// sort (O(N), no per-cell allocation). A query visits every cell overlapping the cube
// of half-width `reach` around a point, so it returns a superset of the neighbours
// within `reach`; callers test the distance themselves. The grid never has more than
// a few cells per point, so a tiny cell size on a wide domain cannot exhaust memory.
//
// Two layouts answer the same queries. build(): a dense grid over the points' box, whose cells
// grow (by 1.25 at a time) until there are at most ~4 cells per point; on a wide, thinly filled
// domain (a debris cloud) each query then scans far more points than lie within its reach.
// buildSparse(): cells that keep the requested size however wide the box, only the occupied ones
// stored: the points are sorted by the linear index of their cell (z, then y, then x, a radix
// sort: in each cell by point index), so that a row of cells along x is still one stretch of
// sorted(), found by binary search in the occupied cells' indices; and for each occupied cell the
// nine rows of the 3 x 3 x 3 cells around it are found once per build (forEachNeighbourRange), by
// one merge over the sorted indices per row offset, for callers whose queries are the points
// themselves.
//
// One large body among small ones (an impactor among grains) must not set the cell size: cells
// that fit it make every query of a small particle scan cells of its size (at a size ratio of
// 6.7, some 300 times the candidates). The searches size their cells by the ordinary particles
// (sizeClasses below) and search the few large ones with their own larger reach.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

// Sizes (radii, support radii) split into ordinary and large: large is above kLargeBodyFactor
// times the mean. A set of equal sizes, or one whose sizes stay within that factor of their
// mean, has no large member; cells sized by `ordinaryMax` then are cells sized by the largest.
struct SizeClasses {
  static constexpr double kLargeBodyFactor = 2.0;
  double cut = 0.0;         // sizes above this are large
  double ordinaryMax = 0.0; // the largest size not above the cut
  double largest = 0.0;
  std::size_t large = 0; // how many are above the cut
  bool isLarge(double size) const { return size > cut; }
};
SizeClasses sizeClasses(const double* size, std::size_t n);

class CellList {
public:
  // Where build() puts the points of a set (its origin, the cells grown as it grows them, their
  // number per axis) without building: for a caller that reproduces the order in which a search
  // on such cells would visit them (by cell, then by index).
  struct DenseGeometry {
    std::array<double, 3> origin{};
    std::array<std::size_t, 3> dims{};
    double cellSize = 1.0;
    // The linear index (x fastest) of the cell build() puts point p in.
    std::size_t cellOf(const double* p) const {
      std::size_t c[3];
      for (int k = 0; k < 3; ++k)
        c[k] = std::min(dims[k] - 1, static_cast<std::size_t>((p[k] - origin[k]) / cellSize));
      return (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    }
    // The cells a query (x, reach) visits, per axis lo[k] .. hi[k]; false if none.
    bool visited(const double x[3], double reach, std::array<long, 3>& lo,
                 std::array<long, 3>& hi) const {
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::max(0L, coord(x[k] - reach, k));
        hi[k] = std::min(static_cast<long>(dims[k]) - 1, coord(x[k] + reach, k));
        if (lo[k] > hi[k])
          return false;
      }
      return true;
    }
    long coord(double v, int k) const {
      const double c = std::floor((v - origin[k]) / cellSize);
      // Clamp in double first so that far-away query points cannot overflow a long.
      return static_cast<long>(std::clamp(c, -1.0, static_cast<double>(dims[k])));
    }
  };
  static DenseGeometry denseGeometry(const double* points, std::size_t n, double cellSize);

  // points: 3*n contiguous coordinates; cellSize > 0.
  void build(const double* points, std::size_t n, double cellSize);
  // The sparse layout (see above): cells of cellSize (times 1 + 1e-8, see forEachNeighbourRange)
  // however far the points spread, unless that makes more than 2^21 cells along an axis (then
  // the cells grow as build()'s do). At most 2^32 - 1 points. The build's work is split over
  // the OpenMP threads; its result does not depend on their number.
  void buildSparse(const double* points, std::size_t n, double cellSize);

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
    if (!grid_.visited(x, reach, lo, hi))
      return;
    const std::array<std::size_t, 3>& dims = grid_.dims;
    for (long cz = lo[2]; cz <= hi[2]; ++cz)
      for (long cy = lo[1]; cy <= hi[1]; ++cy) {
        const std::size_t row = (static_cast<std::size_t>(cz) * dims[1] + cy) * dims[0];
        if (!sparse_) {
          visit(cellStart_[row + lo[0]], cellStart_[row + hi[0] + 1]);
          continue;
        }
        const auto first = std::lower_bound(cellKey_.begin(), cellKey_.end(), row + lo[0]);
        const auto last = std::upper_bound(first, cellKey_.end(), row + hi[0]);
        if (first != last)
          visit(cellStart_[first - cellKey_.begin()], cellStart_[last - cellKey_.begin()]);
      }
  }

  // After buildSparse only: the points of the 27 cells around the cell of point i of the build
  // as ranges of sorted(), one per row of three cells along x (z, then y, ascending; empty rows
  // left out). They hold every point closer to point i than the requested cell size on each
  // axis: cells 1 + 1e-8 times that size keep a rounding of the divisions that place the points
  // in cells (relative 2^-52 of up to 2^21 cells) from putting such a point two cells away.
  template <class Visit> void forEachNeighbourRange(std::size_t i, Visit&& visit) const {
    const std::uint32_t* r = rows_.data() + kRowEnds * pointCell_[i];
    for (std::size_t k = 0; k < kRowEnds; k += 2)
      if (r[k] != r[k + 1])
        visit(std::size_t(r[k]), std::size_t(r[k + 1]));
  }

  // After buildSparse only: the occupied cells (numbered in the order of their points in
  // sorted()), each point's cell, and the occupied cells among the 27 around cell c as ranges
  // [first, last) of those numbers, one per row of three cells along x: for callers that keep a
  // value per cell. Two points whose cells are not neighbours lie at least the requested cell
  // size apart on some axis (see above).
  std::size_t occupiedCells() const { return sparse_ ? cellKey_.size() - 1 : 0; }
  std::size_t cellOf(std::size_t i) const { return pointCell_[i]; } // point i's occupied cell
  template <class Visit> void forEachNeighbourCellRange(std::size_t c, Visit&& visit) const {
    const std::uint32_t* r = rows_.data() + kRowEnds * c;
    for (std::size_t k = 0; k < kRowEnds; k += 2)
      if (r[k] != r[k + 1])
        visit(std::size_t(pointCell_[sorted_[r[k]]]),
              std::size_t(pointCell_[sorted_[r[k + 1] - 1]]) + 1);
  }

  // The points' indices in cell order.
  const std::vector<std::size_t>& sorted() const { return sorted_; }
  double cellSize() const { return grid_.cellSize; }

private:
  static constexpr std::size_t kRowEnds = 18; // begin and end of the nine rows around a cell
  static constexpr int kRadixBits = 11;       // the sort's digits
  void sortByCell(const double* points, std::size_t n);
  void radixPass(std::size_t n, int shift);
  void findRows();

  DenseGeometry grid_; // the cells' origin, number and size (of either layout)
  std::size_t count_ = 0;
  std::vector<std::size_t> cellStart_; // size cells+1
  std::vector<std::size_t> sorted_;    // point indices ordered by cell
  // The sparse layout: the occupied cells' linear indices (ascending; cellStart_ then holds
  // their first points), each point's occupied cell and each cell's rows (kRowEnds entries).
  bool sparse_ = false;
  std::vector<std::uint64_t> cellKey_;
  std::vector<std::uint32_t> pointCell_;
  std::vector<std::uint32_t> rows_;
  std::vector<std::uint64_t> keyOf_, keyTmp_; // the sort's buffers, kept from build to build
  std::vector<std::uint32_t> idOf_, idTmp_;
  std::vector<std::size_t> radixCount_;
};

} // namespace craterkit

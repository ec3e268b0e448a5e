#include "common/CellList.h"

#include "common/Error.h"
#include "common/OpenMP.h"

#include <limits>

namespace craterkit {
namespace {

// The points' box; refuses non-finite coordinates. An empty set gets the box of the origin.
void boundsOf(const double* points, std::size_t n, std::array<double, 3>& lo,
              std::array<double, 3>& hi) {
  lo.fill(std::numeric_limits<double>::max());
  hi.fill(std::numeric_limits<double>::lowest());
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = points[3 * i + k];
      if (!std::isfinite(v))
        throw InputError("cell list: particle " + std::to_string(i) +
                         " has a non-finite coordinate");
      lo[k] = std::min(lo[k], v);
      hi[k] = std::max(hi[k], v);
    }
  if (n == 0) {
    lo.fill(0.0);
    hi.fill(0.0);
  }
}

} // namespace

SizeClasses sizeClasses(const double* size, std::size_t n) {
  SizeClasses c;
  if (n == 0)
    return c;
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum += size[i];
  c.cut = SizeClasses::kLargeBodyFactor * (sum / static_cast<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    c.largest = std::max(c.largest, size[i]);
    if (c.isLarge(size[i]))
      ++c.large;
    else
      c.ordinaryMax = std::max(c.ordinaryMax, size[i]);
  }
  return c;
}

CellList::DenseGeometry CellList::denseGeometry(const double* points, std::size_t n,
                                                double cellSize) {
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
    throw InputError("cell list: cell size must be positive and finite");
  std::array<double, 3> lo{}, hi{};
  boundsOf(points, n, lo, hi);
  // Grow the cells until the grid holds at most ~4 cells per point (and at least 1 cell).
  const double maxCells = std::max<double>(64.0, 4.0 * static_cast<double>(n));
  DenseGeometry g;
  g.cellSize = cellSize;
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < 3; ++k)
      cells *= std::floor((hi[k] - lo[k]) / g.cellSize) + 1.0;
    if (cells <= maxCells)
      break;
    g.cellSize *= 1.25;
  }
  for (int k = 0; k < 3; ++k) {
    g.origin[k] = lo[k];
    g.dims[k] = static_cast<std::size_t>(std::floor((hi[k] - lo[k]) / g.cellSize)) + 1;
  }
  return g;
}

void CellList::build(const double* points, std::size_t n, double cellSize) {
  grid_ = denseGeometry(points, n, cellSize);
  count_ = n;
  sparse_ = false;
  const std::size_t total = grid_.dims[0] * grid_.dims[1] * grid_.dims[2];
  std::vector<std::size_t> cellOf(n);
  cellStart_.assign(total + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    cellOf[i] = grid_.cellOf(&points[3 * i]);
    ++cellStart_[cellOf[i] + 1];
  }
  for (std::size_t c = 0; c < total; ++c)
    cellStart_[c + 1] += cellStart_[c];
  sorted_.resize(n);
  std::vector<std::size_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    sorted_[fill[cellOf[i]]++] = i;
}

void CellList::buildSparse(const double* points, std::size_t n, double cellSize) {
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
    throw InputError("cell list: cell size must be positive and finite");
  if (n >= (std::size_t(1) << 32))
    throw InputError("cell list: the sparse layout takes at most 2^32 - 1 points");
  count_ = n;
  sparse_ = true;
  std::array<double, 3> lo{}, hi{};
  boundsOf(points, n, lo, hi);
  // One empty cell of padding on every side: the 27 cells around an occupied cell all have
  // linear indices, at fixed offsets from its own.
  constexpr double kAxisCells = double(1 << 21); // three axes' indices in 63 bits
  double& size = grid_.cellSize;
  size = cellSize * (1.0 + 1e-8);
  while (std::floor((std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]})) / size) + 3.0 >
         kAxisCells)
    size *= 1.25;
  for (int k = 0; k < 3; ++k) {
    grid_.origin[k] = lo[k] - size;
    grid_.dims[k] = static_cast<std::size_t>(std::floor((hi[k] - lo[k]) / size)) + 3;
  }
  sortByCell(points, n);
  findRows();
}

// Each point's linear cell index, then a stable radix sort of the points by it (11 bits a
// pass, only as many passes as the largest index needs): in each cell by point index, as
// build()'s counting sort. Then the occupied cells, their first points and each point's cell.
void CellList::sortByCell(const double* points, std::size_t n) {
  keyOf_.resize(n), keyTmp_.resize(n), idOf_.resize(n), idTmp_.resize(n);
  const std::array<std::size_t, 3> dims = grid_.dims;
  const std::array<double, 3> origin = grid_.origin;
  const double size = grid_.cellSize;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < static_cast<long>(n); ++i) {
    std::uint64_t c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<std::uint64_t>(
          static_cast<std::uint64_t>((points[3 * i + k] - origin[k]) / size), 1, dims[k] - 2);
    keyOf_[i] = (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    idOf_[i] = static_cast<std::uint32_t>(i);
  }
  const std::uint64_t largest = std::uint64_t(dims[2]) * dims[1] * dims[0] - 1;
  for (int shift = 0; shift < 64 && (largest >> shift) != 0; shift += kRadixBits) {
    radixPass(n, shift);
    keyOf_.swap(keyTmp_);
    idOf_.swap(idTmp_);
  }
  // The occupied cells, with a sentinel above every index so that searches need no bounds.
  cellKey_.clear();
  cellStart_.clear();
  for (std::size_t s = 0; s < n; ++s)
    if (s == 0 || keyOf_[s] != keyOf_[s - 1]) {
      cellKey_.push_back(keyOf_[s]);
      cellStart_.push_back(s);
    }
  cellKey_.push_back(std::numeric_limits<std::uint64_t>::max());
  cellStart_.push_back(n);
  sorted_.resize(n);
  pointCell_.resize(n);
  const long cells = static_cast<long>(cellKey_.size()) - 1;
#pragma omp parallel for schedule(static)
  for (long c = 0; c < cells; ++c)
    for (std::size_t s = cellStart_[c]; s < cellStart_[c + 1]; ++s) {
      sorted_[s] = idOf_[s];
      pointCell_[idOf_[s]] = static_cast<std::uint32_t>(c);
    }
}

// One stable pass of the radix sort on the digit at `shift`, keyOf_ and idOf_ into keyTmp_ and
// idTmp_: each thread counts the digits of its fixed share of the points, and places them after
// those of the threads before it (the order of a serial pass for any number of threads).
void CellList::radixPass(std::size_t n, int shift) {
  constexpr std::size_t kDigits = std::size_t(1) << kRadixBits;
  const std::uint64_t mask = kDigits - 1;
  std::vector<std::size_t>& count = radixCount_;
#pragma omp parallel
  {
    const std::size_t teams = static_cast<std::size_t>(threadCount());
    const std::size_t me = static_cast<std::size_t>(threadNumber());
#pragma omp single
    count.assign(teams * kDigits, 0);
    const std::size_t i0 = n * me / teams, i1 = n * (me + 1) / teams;
    std::size_t* mine = count.data() + me * kDigits;
    for (std::size_t i = i0; i < i1; ++i)
      ++mine[(keyOf_[i] >> shift) & mask];
#pragma omp barrier
#pragma omp single
    {
      std::size_t total = 0;
      for (std::size_t d = 0; d < kDigits; ++d)
        for (std::size_t t = 0; t < teams; ++t) {
          const std::size_t c = count[t * kDigits + d];
          count[t * kDigits + d] = total;
          total += c;
        }
    }
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t to = mine[(keyOf_[i] >> shift) & mask]++;
      keyTmp_[to] = keyOf_[i];
      idTmp_[to] = idOf_[i];
    }
  }
}

// For each occupied cell, the nine rows (dz, dy in -1, 0, 1) of three cells around it as
// ranges of sorted(). Row r's first cell has the index key + offset[r] - 1 and its last
// key + offset[r] + 1: both grow with the cell's own index, so one pass over the occupied cells
// in order moves a cursor per row forward only (a binary search places them at the start
// of each chunk of cells).
void CellList::findRows() {
  const std::size_t cells = cellKey_.size() - 1;
  rows_.resize(kRowEnds * cells);
  std::uint64_t offset[9];
  for (int dz = -1, r = 0; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy, ++r) // unsigned wrap-around: the sum is the neighbour's
      offset[r] = static_cast<std::uint64_t>((dz * static_cast<long long>(grid_.dims[1]) + dy) *
                                             static_cast<long long>(grid_.dims[0]));
  constexpr std::size_t kChunk = 4096;
  const long chunks = static_cast<long>((cells + kChunk - 1) / kChunk);
  const std::uint64_t* key = cellKey_.data();
#pragma omp parallel for schedule(static)
  for (long ch = 0; ch < chunks; ++ch) {
    const std::size_t c0 = static_cast<std::size_t>(ch) * kChunk;
    const std::size_t c1 = std::min(cells, c0 + kChunk);
    std::size_t first[9];
    for (int r = 0; r < 9; ++r)
      first[r] = static_cast<std::size_t>(
          std::lower_bound(key, key + cells, key[c0] + offset[r] - 1) - key);
    for (std::size_t c = c0; c < c1; ++c) {
      std::uint32_t* out = rows_.data() + kRowEnds * c;
      for (int r = 0; r < 9; ++r) {
        const std::uint64_t middle = key[c] + offset[r];
        while (key[first[r]] < middle - 1)
          ++first[r];
        // The row's (at most three, distinct, sorted) cells are those from first[r] on that
        // lie within middle + 1: counted without branches (the sentinel ends the array).
        const std::size_t f = first[r];
        const std::size_t last = f + (key[f] <= middle + 1) +
                                 (key[std::min(f + 1, cells)] <= middle + 1) +
                                 (key[std::min(f + 2, cells)] <= middle + 1);
        out[2 * r] = static_cast<std::uint32_t>(cellStart_[f]);
        out[2 * r + 1] = static_cast<std::uint32_t>(cellStart_[last]);
      }
    }
  }
}

} // namespace craterkit

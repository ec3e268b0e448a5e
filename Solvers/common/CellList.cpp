#include "common/CellList.h"

#include "common/Error.h"

#include <limits>

namespace craterkit {

void CellList::build(const double* points, std::size_t n, double cellSize) {
  if (!(cellSize > 0.0) || !std::isfinite(cellSize))
    throw InputError("cell list: cell size must be positive and finite");
  count_ = n;
  std::array<double, 3> lo{}, hi{};
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
  // Grow the cells until the grid holds at most ~4 cells per point (and at least 1 cell).
  const double maxCells = std::max<double>(64.0, 4.0 * static_cast<double>(n));
  cellSize_ = cellSize;
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < 3; ++k)
      cells *= std::floor((hi[k] - lo[k]) / cellSize_) + 1.0;
    if (cells <= maxCells)
      break;
    cellSize_ *= 1.25;
  }
  std::size_t total = 1;
  for (int k = 0; k < 3; ++k) {
    origin_[k] = lo[k];
    dims_[k] = static_cast<std::size_t>(std::floor((hi[k] - lo[k]) / cellSize_)) + 1;
    total *= dims_[k];
  }
  std::vector<std::size_t> cellOf(n);
  cellStart_.assign(total + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::min(dims_[k] - 1,
                      static_cast<std::size_t>((points[3 * i + k] - origin_[k]) / cellSize_));
    cellOf[i] = (c[2] * dims_[1] + c[1]) * dims_[0] + c[0];
    ++cellStart_[cellOf[i] + 1];
  }
  for (std::size_t c = 0; c < total; ++c)
    cellStart_[c + 1] += cellStart_[c];
  sorted_.resize(n);
  std::vector<std::size_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    sorted_[fill[cellOf[i]]++] = i;
}

} // namespace craterkit

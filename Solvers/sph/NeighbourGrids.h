// The SPH neighbour search's grids (sph/NeighbourList.h): one sparse grid of cells per level
// of smoothing length, the candidates' positions, h and margins copied in (level, cell) order,
// and, where a level's occupied cells fill their box densely enough, a dense index of its cells.
// Internal to the neighbour list (NeighbourList.cpp, NeighbourGrids.cpp).
#pragma once

#include "sph/NeighbourList.h"
#include "sph/SphState.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace craterkit {

constexpr int kMaxGridLevels = 16; // levels of h in the neighbour grids (√2 apart)

// Sparse grids: cells of half the level's reach, keyed (z, y, x) in 64 bits and sorted, so
// memory and cost do not depend on how far ejecta have flown (a dense grid over a spray
// kilometres wide would have to coarsen its cells for everyone). Candidate positions are
// copied in (level, cell) order, so a scan reads memory sequentially.
struct NeighbourList::Grids {
  static constexpr std::int64_t kAxis = (std::int64_t(1) << 21) - 1;
  int levels = 1;
  double grow = 1.0;
  std::vector<double> levelH, levelMu; // each level's largest h and largest margin
  std::vector<std::size_t> levelSize;  // each level's range in the sorted arrays
  std::vector<double> cellSize;
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  std::vector<double> spx, spy, spz, sh, smu; // positions, h and margins in (level, cell) order
  std::vector<std::uint32_t> sid;
  std::vector<std::int64_t> cellKey;    // distinct cells, ascending per level
  std::vector<std::uint32_t> cellStart; // their first entry in the sorted arrays, plus the end
  std::vector<std::size_t> levelCells;  // each level's range in cellKey

  // h: each particle's smoothing length (by index, not by entry).
  Grids(const std::vector<double>& h, const std::vector<double>& pos,
        const std::vector<std::uint32_t>& id, const std::vector<std::uint8_t>& particleLevel,
        int levelCount, const std::vector<double>& mu, double growth);
  std::int64_t coord(double v, int k, int l) const {
    return static_cast<std::int64_t>(
        std::clamp(std::floor((v - lo[k]) / cellSize[static_cast<std::size_t>(l)]), 0.0,
                   static_cast<double>(kAxis)));
  }
  static std::int64_t key(std::int64_t cx, std::int64_t cy, std::int64_t cz) {
    return (cz << 42) | (cy << 21) | cx;
  }
  bool empty(int l) const {
    return levelSize[static_cast<std::size_t>(l)] == levelSize[static_cast<std::size_t>(l) + 1];
  }
  // Where a level's occupied cells fit a box of not many more cells than entries, a dense
  // index over that box: the first sorted entry at or after each cell (in key order), so a
  // row's entries are found with two loads instead of a search.
  struct Dense {
    std::int64_t min[3] = {0, 0, 0}, n[3] = {0, 0, 0};
    std::size_t offset = 0; // into `dense`
    bool on = false;
  };
  std::vector<Dense> levelDense;
  std::vector<std::uint32_t> dense;
  void indexCells(int l, const std::vector<std::pair<std::int64_t, std::uint32_t>>& order);

  // Calls f(begin, end) for the sorted entries of level l in the cells within R of x (a cube)
  // that reach into the ball of radius `ball` around x: the cube's rows (runs of cells along
  // x) that lie wholly outside the ball are left out (the callers' pairs all lie inside the
  // ball, so they see the same entries in the same order). Trimming each row's ends to the ball
  // as well cost more (a square root and two cell coordinates per row) than it saved.
  template <class F> void forCells(const double* x, double R, double ball, int l, F&& f) const {
    if (empty(l))
      return;
    const double cs = cellSize[static_cast<std::size_t>(l)];
    // rounding: the ball a hair larger, so that no entry on its edge is left out
    const double ball2 = ball * ball * (1.0 + 1e-12);
    std::int64_t c0[3], c1[3];
    for (int k = 0; k < 3; ++k) {
      c0[k] = coord(x[k] - R, k, l);
      c1[k] = coord(x[k] + R, k, l);
    }
    // the distance from x[k] to cell c's slab along axis k
    auto gap = [&](std::int64_t c, int k) {
      const double below = lo[k] + static_cast<double>(c) * cs - x[k];
      const double above = x[k] - (lo[k] + static_cast<double>(c + 1) * cs);
      return std::max({below, above, 0.0});
    };
    const Dense& d = levelDense[static_cast<std::size_t>(l)];
    if (d.on)
      for (int k = 0; k < 3; ++k) {
        c0[k] = std::max(c0[k], d.min[k]);
        c1[k] = std::min(c1[k], d.min[k] + d.n[k] - 1);
        if (c0[k] > c1[k]) // the cube misses the level's cells
          return;
      }
    const auto first =
        cellKey.begin() + static_cast<std::ptrdiff_t>(levelCells[static_cast<std::size_t>(l)]);
    const auto end =
        cellKey.begin() + static_cast<std::ptrdiff_t>(levelCells[static_cast<std::size_t>(l) + 1]);
    for (std::int64_t cz = c0[2]; cz <= c1[2]; ++cz) {
      const double gz = gap(cz, 2), gz2 = gz * gz;
      if (gz2 >= ball2)
        continue;
      for (std::int64_t cy = c0[1]; cy <= c1[1]; ++cy) {
        const double gy = gap(cy, 1);
        if (gz2 + gy * gy >= ball2)
          continue;
        const std::int64_t x0 = c0[0], x1 = c1[0];
        if (d.on) {
          const std::int64_t row = ((cz - d.min[2]) * d.n[1] + (cy - d.min[1])) * d.n[0] - d.min[0];
          const std::uint32_t b = dense[d.offset + static_cast<std::size_t>(row + x0)],
                              e = dense[d.offset + static_cast<std::size_t>(row + x1 + 1)];
          if (b != e)
            f(b, e);
          continue;
        }
        // The row's cells are contiguous in key order: one search for its first.
        auto it = std::lower_bound(first, end, key(x0, cy, cz));
        const std::int64_t last = key(x1, cy, cz);
        auto stop = it;
        while (stop != end && *stop <= last)
          ++stop;
        if (stop != it)
          f(cellStart[static_cast<std::size_t>(it - cellKey.begin())],
            cellStart[static_cast<std::size_t>(stop - cellKey.begin())]);
      }
    }
  }
};

} // namespace craterkit

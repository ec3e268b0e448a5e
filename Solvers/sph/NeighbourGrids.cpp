#include "sph/NeighbourGrids.h"

#include <stdexcept>
#include <string>

namespace craterkit {

// The dense index of level l (when its cells' box holds at most eight cells per entry, plus
// some: a spray of ejecta keeps the sorted search). `order` holds the level's entries sorted by
// cell key, at the level's range of the sorted arrays.
void NeighbourList::Grids::indexCells(
    int l, const std::vector<std::pair<std::int64_t, std::uint32_t>>& order) {
  const std::size_t r0 = levelSize[static_cast<std::size_t>(l)],
                    r1 = levelSize[static_cast<std::size_t>(l) + 1];
  Dense& d = levelDense[static_cast<std::size_t>(l)];
  auto axis = [](std::int64_t key, int k) { return (key >> (21 * k)) & kAxis; };
  std::int64_t hi[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k)
    d.min[k] = kAxis;
  for (std::size_t r = r0; r < r1; ++r)
    for (int k = 0; k < 3; ++k) {
      d.min[k] = std::min(d.min[k], axis(order[r].first, k));
      hi[k] = std::max(hi[k], axis(order[r].first, k));
    }
  double cells = 1.0;
  for (int k = 0; k < 3; ++k) {
    d.n[k] = hi[k] - d.min[k] + 1;
    cells *= static_cast<double>(d.n[k]);
  }
  if (r0 == r1 || cells > 8.0 * static_cast<double>(r1 - r0) + 4096.0)
    return;
  d.on = true;
  d.offset = dense.size();
  const std::size_t total = static_cast<std::size_t>(cells);
  dense.resize(d.offset + total + 1, 0);
  std::uint32_t* first = dense.data() + d.offset;
  for (std::size_t r = r0; r < r1; ++r) {
    const std::int64_t key = order[r].first;
    ++first[((axis(key, 2) - d.min[2]) * d.n[1] + (axis(key, 1) - d.min[1])) * d.n[0] +
            (axis(key, 0) - d.min[0]) + 1];
  }
  first[0] = static_cast<std::uint32_t>(r0);
  for (std::size_t c = 1; c <= total; ++c)
    first[c] += first[c - 1];
}

NeighbourList::Grids::Grids(const std::vector<double>& hOf, const std::vector<double>& pos,
                            const std::vector<std::uint32_t>& id,
                            const std::vector<std::uint8_t>& particleLevel, int levelCount,
                            const std::vector<double>& mu, double growth)
    : levels(levelCount), grow(growth) {
  const std::size_t m = id.size();
  std::vector<std::uint8_t> level(m);
  levelH.assign(static_cast<std::size_t>(levels), 0.0);
  levelMu.assign(static_cast<std::size_t>(levels), 0.0);
  levelSize.assign(static_cast<std::size_t>(levels) + 1, 0);
  for (std::size_t q = 0; q < m; ++q) {
    const double h = hOf[id[q] / 32];
    const int l = particleLevel[id[q] / 32];
    level[q] = static_cast<std::uint8_t>(l);
    levelH[static_cast<std::size_t>(l)] = std::max(levelH[static_cast<std::size_t>(l)], h);
    levelMu[static_cast<std::size_t>(l)] =
        std::max(levelMu[static_cast<std::size_t>(l)], mu[id[q] / 32]);
    ++levelSize[static_cast<std::size_t>(l) + 1];
  }
  cellSize.resize(static_cast<std::size_t>(levels));
  for (int l = 0; l < levels; ++l)
    cellSize[static_cast<std::size_t>(l)] =
        0.5 * (grow * levelH[static_cast<std::size_t>(l)] + levelMu[static_cast<std::size_t>(l)]);
  for (std::size_t q = 0; q < m; ++q)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(pos[3 * q + k]))
        throw std::runtime_error("SPH: particle " + std::to_string(id[q] / 32) +
                                 " has a non-finite position");
      lo[k] = std::min(lo[k], pos[3 * q + k]);
    }
  for (int l = 0; l < levels; ++l)
    levelSize[static_cast<std::size_t>(l) + 1] += levelSize[static_cast<std::size_t>(l)];
  std::vector<std::pair<std::int64_t, std::uint32_t>> order(m);
  {
    std::vector<std::size_t> at(levelSize.begin(), levelSize.end() - 1);
    for (std::size_t q = 0; q < m; ++q) {
      const int l = level[q];
      order[at[static_cast<std::size_t>(l)]++] = {
          key(coord(pos[3 * q], 0, l), coord(pos[3 * q + 1], 1, l), coord(pos[3 * q + 2], 2, l)),
          static_cast<std::uint32_t>(q)};
    }
  }
  for (int l = 0; l < levels; ++l)
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(levelSize[static_cast<std::size_t>(l)]),
              order.begin() +
                  static_cast<std::ptrdiff_t>(levelSize[static_cast<std::size_t>(l) + 1]));
  spx.resize(m), spy.resize(m), spz.resize(m), sh.resize(m), smu.resize(m);
  sid.resize(m);
  levelCells.assign(static_cast<std::size_t>(levels) + 1, 0);
  for (int l = 0; l < levels; ++l) {
    for (std::size_t r = levelSize[static_cast<std::size_t>(l)];
         r < levelSize[static_cast<std::size_t>(l) + 1]; ++r) {
      const std::uint32_t q = order[r].second;
      spx[r] = pos[3 * q], spy[r] = pos[3 * q + 1], spz[r] = pos[3 * q + 2];
      sid[r] = id[q];
      sh[r] = hOf[id[q] / 32];
      smu[r] = mu[id[q] / 32];
      if (r == levelSize[static_cast<std::size_t>(l)] || order[r].first != order[r - 1].first) {
        cellKey.push_back(order[r].first);
        cellStart.push_back(static_cast<std::uint32_t>(r));
      }
    }
    levelCells[static_cast<std::size_t>(l) + 1] = cellKey.size();
  }
  levelDense.assign(static_cast<std::size_t>(levels), Dense{});
  for (int l = 0; l < levels; ++l)
    indexCells(l, order);
  cellStart.push_back(static_cast<std::uint32_t>(m));
}

} // namespace craterkit

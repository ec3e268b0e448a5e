#include "edmd/HardDiskGrid.h"

#include "common/Error.h"
#include "edmd/EventTimes.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

using edmd::kInf;

void HardDiskSystem::setUpGrid(double rmin, double rmax) {
  const std::size_t n = h_.size();
  // Small and big disks (rmin, rmax: the smallest and largest radius): cells fit the small
  // ones.
  isBig_.assign(n, 0);
  smallMax_ = rmax;
  if (rmax > 3.0 * rmin) {
    std::size_t big = 0;
    double sm = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (h_[i].r > 3.0 * rmin)
        ++big;
      else
        sm = std::max(sm, h_[i].r);
    }
    if (big <= 64) {
      smallMax_ = sm;
      for (std::size_t i = 0; i < n; ++i)
        if (h_[i].r > 3.0 * rmin) {
          isBig_[i] = 1;
          bigs_.push_back(static_cast<std::uint32_t>(i));
        }
    }
  }
  const double gEnd = growth(p_.growthEnd);
  const double cell = 2.0 * smallMax_ * gEnd * (1.0 + 1e-9);
  if ((p_.periodicX && p_.width < 2.0 * cell * (bigs_.empty() ? 1.0 : rmax / smallMax_)) ||
      (p_.periodicY && p_.height < 2.0 * cell * (bigs_.empty() ? 1.0 : rmax / smallMax_)))
    throw InputError("a periodic box must be wider than twice the largest disk diameter");
  nx_ = std::max<std::size_t>(1, static_cast<std::size_t>(p_.width / cell));
  ny_ = std::max<std::size_t>(1, static_cast<std::size_t>(p_.height / cell));
  // Keep the grid within memory: at most ~4 cells per disk.
  while (nx_ * ny_ > 4 * n + 16) {
    nx_ = std::max<std::size_t>(1, nx_ / 2);
    ny_ = std::max<std::size_t>(1, ny_ / 2);
  }
  cellW_ = p_.width / nx_;
  cellH_ = p_.height / ny_;
  reach_.assign(n, 1);
  for (std::uint32_t b : bigs_)
    reach_[b] =
        static_cast<int>(std::ceil((h_[b].r + smallMax_) * gEnd / std::min(cellW_, cellH_)));

  head_.assign(nx_ * ny_ + 1, -1); // the last cell stays empty: what lies beyond a wall
  gridFast_ = nx_ >= 3 && ny_ >= 3 && p_.growthRate == 0.0;
  chooseScans();
  prevInCell_.assign(n, -1);
  cellOf_.assign(n, CellXY{0, 0});
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t cx = std::min(nx_ - 1, static_cast<std::size_t>(h_[i].x / cellW_));
    const std::size_t cy = std::min(ny_ - 1, static_cast<std::size_t>(h_[i].y / cellH_));
    insertInCell(i, cx, cy);
  }
}

double HardDiskSystem::smallestGapNearby() const {
  double best = kInf;
  for (std::size_t i = 0; i < h_.size(); ++i) {
    forNearby(i, [&](std::size_t j) {
      if (j > i && !isBig_[j])
        best = std::min(best, gapNow(i, j));
    });
    for (std::uint32_t b : bigs_)
      if (!isBig_[i] || b > i)
        best = std::min(best, gapNow(i, b));
  }
  return best;
}

} // namespace craterkit

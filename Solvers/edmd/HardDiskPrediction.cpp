// Event prediction of the hard-disk system (HardDiskSystem.h): each disk's next event, the
// earliest of its pair events (with the disks of the 3x3 cells around it and the big disks),
// its crossing of a cell face and its wall collision (the times from EventTimes.h). The
// common case (a small disk, no growth) runs through scans specialised for the kind of box;
// after a crossing only the row or column of cells that came within reach is scanned.
#include "edmd/HardDiskGrid.h"

#include "edmd/EventTimes.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

using edmd::kInf;
using edmd::minimumImage;
using edmd::wrapCell;

void HardDiskSystem::cellEvent(std::size_t i, Event& best) const {
  const std::size_t cx = cellOf_[i].x, cy = cellOf_[i].y;
  const double xlo = (cx == 0 && !p_.periodicX) ? -kInf : cx * cellW_;
  const double xhi = (cx + 1 == nx_ && !p_.periodicX) ? kInf : (cx + 1) * cellW_;
  const double ylo = (cy == 0 && !p_.periodicY) ? -kInf : cy * cellH_;
  const double yhi = (cy + 1 == ny_ && !p_.periodicY) ? kInf : (cy + 1) * cellH_;
  // A face at infinity (a walled end of the grid) gives an infinite time, so no event.
  int sx, sy;
  const double tx = edmd::straightExitTime(h_[i].x, h_[i].vx, xlo, xhi, sx);
  const double ty = p_.gravity == 0.0
                        ? edmd::straightExitTime(h_[i].y, h_[i].vy, ylo, yhi, sy)
                        : edmd::exitTime(h_[i].y, h_[i].vy, -p_.gravity, ylo, yhi, sy);
  if (time_ + tx < best.t && sx != 0)
    best = Event{time_ + tx, static_cast<std::uint32_t>(sx < 0 ? 0 : 1), EventType::Cell, 0};
  if (time_ + ty < best.t && sy != 0)
    best = Event{time_ + ty, static_cast<std::uint32_t>(sy < 0 ? 2 : 3), EventType::Cell, 0};
}

void HardDiskSystem::wallEvent(std::size_t i, Event& best) const {
  const double r = h_[i].r * growth(time_), rdot = h_[i].r * p_.growthRate;
  auto linear = [&](double pos, double vel, double size, std::uint32_t lowWall) {
    if (vel - rdot < 0.0) {
      const double t = time_ + edmd::lowWallTime(pos, vel, r, rdot);
      if (t < best.t)
        best = Event{t, lowWall, EventType::Wall, 0};
    }
    if (vel + rdot > 0.0) {
      const double t = time_ + edmd::highWallTime(pos, vel, size, r, rdot);
      if (t < best.t)
        best = Event{t, lowWall + 1, EventType::Wall, 0};
    }
  };
  if (!p_.periodicX)
    linear(h_[i].x, h_[i].vx, p_.width, 0);
  if (!p_.periodicY) {
    if (p_.gravity == 0.0) {
      linear(h_[i].y, h_[i].vy, p_.height, 2);
    } else {
      int side;
      const double t =
          time_ + edmd::exitTime(h_[i].y, h_[i].vy, -p_.gravity, r, p_.height - r, side);
      if (side != 0 && t < best.t)
        best = Event{t, static_cast<std::uint32_t>(side < 0 ? 2 : 3), EventType::Wall, 0};
    }
  }
}

void HardDiskSystem::consider(std::size_t i, std::size_t j, Event& best) const {
  // i is current; j is taken to the current time on the fly.
  const double dtj = time_ - h_[j].t, g = p_.gravity;
  double rx = h_[j].x + h_[j].vx * dtj - h_[i].x;
  double ry = h_[j].y + (h_[j].vy - 0.5 * g * dtj) * dtj - h_[i].y;
  if (p_.periodicX)
    rx = minimumImage(rx, p_.width);
  if (p_.periodicY)
    ry = minimumImage(ry, p_.height);
  const double ux = h_[j].vx - h_[i].vx, uy = h_[j].vy - g * dtj - h_[i].vy;
  const double sigma0 = h_[i].r + h_[j].r;
  const double sigma = sigma0 * growth(time_), sdot = sigma0 * p_.growthRate;
  double tau;
  if (!edmd::pairContactTime(rx, ry, ux, uy, sigma, sdot, tau))
    return;
  const double t = time_ + tau;
  if (t < best.t)
    best = Event{t, static_cast<std::uint32_t>(j), EventType::Pair, h_[j].count};
}

// Pair events of small disk i with the small disks of one cell list, for a fixed kind of box
// (gravity or not, periodic axes): the common case, with no growth, compiled without the
// branches the general code needs.
template <bool Grav, bool PX, bool PY> __attribute__((always_inline)) inline void
HardDiskSystem::scanList(std::size_t i, std::int32_t k, Event& best) const {
  const Hot& a = h_[i];
  const double g = p_.gravity, now = time_;
  const double W = p_.width, H = p_.height;
  while (k >= 0) {
    const std::size_t j = static_cast<std::size_t>(k);
    const Hot& o = h_[j];
    k = o.next;
    if (j == i)
      continue;
    const double dtj = now - o.t;
    double rx = o.x + o.vx * dtj - a.x, ry, uy;
    if constexpr (Grav) {
      ry = o.y + (o.vy - 0.5 * g * dtj) * dtj - a.y;
      uy = o.vy - g * dtj - a.vy;
    } else {
      ry = o.y + o.vy * dtj - a.y;
      uy = o.vy - a.vy;
    }
    if constexpr (PX) // nearest image (rarely another: the branch is predicted)
      rx = minimumImage(rx, W);
    if constexpr (PY)
      ry = minimumImage(ry, H);
    const double ux = o.vx - a.vx;
    const double b = rx * ux + ry * uy;
    if (b >= 0.0)
      continue; // receding (a >= 0 without growth)
    const double sigma = a.r + o.r;
    const double c2 = rx * rx + ry * ry - sigma * sigma;
    double tau = 0.0;
    if (c2 > 0.0) {
      const double disc = b * b - (ux * ux + uy * uy) * c2;
      if (disc < 0.0)
        continue;
      tau = c2 / (-b + std::sqrt(disc));
    }
    if (now + tau < best.t)
      best = Event{now + tau, static_cast<std::uint32_t>(j), EventType::Pair, o.count};
  }
}

// The cell lists that start at first[0 .. cells-1], one after the other.
template <bool Grav, bool PX, bool PY> inline void
HardDiskSystem::scanLists(std::size_t i, const std::int32_t* first, int cells, Event& best) const {
  for (int c = 0; c < cells; ++c)
    scanList<Grav, PX, PY>(i, first[c], best);
}

template <bool Grav, bool PX, bool PY>
void HardDiskSystem::scanBlock(std::size_t i, Event& best) const {
  Block block;
  gatherBlock<PX, PY>(i, block);
  scanLists<Grav, PX, PY>(i, block.first, block.cells, best);
}

template <bool PX, bool PY>
inline void HardDiskSystem::gatherBlock(std::size_t i, Block& block) const {
  // The 3x3 cells around i (an axis without periodicity reads the always empty cell beyond
  // the grid at its ends); their first disks' records are requested together, since most
  // cells hold zero or one disk and these are most of a prediction's loads.
  const long cx = static_cast<long>(cellOf_[i].x), cy = static_cast<long>(cellOf_[i].y);
  const long nx = static_cast<long>(nx_), ny = static_cast<long>(ny_), none = nx * ny;
  long col[3], row[3];
  for (int d = 0; d < 3; ++d) {
    col[d] = wrapCell<PX>(cx + d - 1, nx);
    const long ky = wrapCell<PY>(cy + d - 1, ny);
    row[d] = ky < 0 ? -1 : ky * nx;
  }
  int cells = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const bool inside = col[c] >= 0 && row[r] >= 0;
      const std::int32_t k = head_[static_cast<std::size_t>(inside ? row[r] + col[c] : none)];
      __builtin_prefetch(&h_[static_cast<std::size_t>(k < 0 ? 0 : k)]);
      block.first[cells] = k;
      cells += k >= 0;
    }
  block.cells = cells;
}

template <bool Grav, bool PX, bool PY>
void HardDiskSystem::predictPair(std::size_t i, std::size_t j) {
  // Both disks of a collision: the two blocks' cells and first records are requested before
  // either is scanned, so that their loads overlap.
  Block bi, bj;
  gatherBlock<PX, PY>(i, bi);
  gatherBlock<PX, PY>(j, bj);
  Event best{kInf, 0, EventType::None, 0};
  scanLists<Grav, PX, PY>(i, bi.first, bi.cells, best);
  finishPrediction(i, best);
  best = Event{kInf, 0, EventType::None, 0};
  scanLists<Grav, PX, PY>(j, bj.first, bj.cells, best);
  finishPrediction(j, best);
}

template <bool Grav, bool PX, bool PY>
void HardDiskSystem::scanEdge(std::size_t i, std::uint32_t direction, Event& best) const {
  // After a crossing: the row or column of three cells that just came within reach.
  const long nx = static_cast<long>(nx_), ny = static_cast<long>(ny_);
  const long cx = static_cast<long>(cellOf_[i].x), cy = static_cast<long>(cellOf_[i].y);
  const long step = (direction % 2 == 0) ? -1 : 1;
  std::int32_t first[3];
  int cells = 0;
  for (long d = -1; d <= 1; ++d) {
    const long kx = wrapCell<PX>(direction < 2 ? cx + step : cx + d, nx);
    const long ky = wrapCell<PY>(direction < 2 ? cy + d : cy + step, ny);
    const std::int32_t k = kx < 0 || ky < 0 ? -1 : head_[static_cast<std::size_t>(ky * nx + kx)];
    __builtin_prefetch(&h_[static_cast<std::size_t>(k < 0 ? 0 : k)]);
    first[cells] = k;
    cells += k >= 0;
  }
  scanLists<Grav, PX, PY>(i, first, cells, best);
}

// The specialised scans for this box (gravity or not, periodic axes).
void HardDiskSystem::chooseScans() {
  const int kind = (p_.gravity != 0.0 ? 4 : 0) + (p_.periodicX ? 2 : 0) + (p_.periodicY ? 1 : 0);
  switch (kind) {
#define CK_SCANS(K, G, X, Y)                                                                       \
  case K:                                                                                          \
    scanBlock_ = &HardDiskSystem::scanBlock<G, X, Y>;                                              \
    scanEdge_ = &HardDiskSystem::scanEdge<G, X, Y>;                                                \
    predictPair_ = &HardDiskSystem::predictPair<G, X, Y>;                                          \
    break;
    CK_SCANS(0, false, false, false)
    CK_SCANS(1, false, false, true)
    CK_SCANS(2, false, true, false)
    CK_SCANS(3, false, true, true)
    CK_SCANS(4, true, false, false)
    CK_SCANS(5, true, false, true)
    CK_SCANS(6, true, true, false)
    CK_SCANS(7, true, true, true)
#undef CK_SCANS
  }
}

void HardDiskSystem::predict(std::size_t i) {
  Event best{kInf, 0, EventType::None, 0}; // the best pair event
  if (fastScan(i)) {
    (this->*scanBlock_)(i, best);
  } else {
    forNearby(i, [&](std::size_t j) {
      if (j != i)
        consider(i, j, best);
    });
  }
  finishPrediction(i, best);
}

void HardDiskSystem::finishPrediction(std::size_t i, Event& best) {
  // best holds i's pair events with the small disks near it: add the big disks.
  for (std::uint32_t b : bigs_)
    if (b != i)
      consider(i, b, best);
  scheduleNext(i, best);
}

void HardDiskSystem::scheduleNext(std::size_t i, Event& best) {
  // best is i's best pair event: keep it for the next crossing, add the cell and wall events,
  // schedule the earliest.
  pairBest_[i] = best;
  cellEvent(i, best);
  wallEvent(i, best);
  schedule(i, best);
}

void HardDiskSystem::predictAfterCrossing(std::size_t i, std::uint32_t direction) {
  // The pair events with the old neighbours cannot come before the crossing and do not change
  // with it: keep the best of them (if its partner has not collided since) and scan only the
  // row or column of cells that just came within reach.
  Event best = pairBest_[i];
  if (!fastScan(i) ||
      (best.type == EventType::Pair && h_[best.partner].count != best.partnerCount)) {
    predict(i);
    return;
  }
  (this->*scanEdge_)(i, direction, best);
  scheduleNext(i, best);
}

void HardDiskSystem::predictAll() {
  const std::size_t n = h_.size();
  for (std::size_t i = 0; i < n; ++i)
    stream(i);
  queue_.reset(n, time_);
  for (std::size_t i = 0; i < n; ++i)
    predict(i);
  queue_.tune(time_); // size the buckets from the real events
}

} // namespace craterkit

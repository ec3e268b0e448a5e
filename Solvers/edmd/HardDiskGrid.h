// The cell grid of the hard-disk system (HardDiskSystem.h; docs/physics.md §6): a uniform grid of
// cells at least one small-disk diameter wide, each holding an intrusive doubly linked list of
// its small disks (the forward link sits in the disk's hot record, the backward one beside it),
// so that a disk's possible partners are the disks of the 3x3 cells around it and a crossing
// moves the disk between two lists in O(1) (Rapaport, "The Art of Molecular Dynamics
// Simulation", 2nd ed., §14.3). Big disks are not listed; they scan the ring of cells they
// reach.
//
// Private to Solvers/edmd: the inline members the event loop, the prediction and the checks
// all use, kept in a header so that each of their files inlines them.
#pragma once

#include "edmd/HardDiskSystem.h"

#include <cstddef>
#include <cstdint>

namespace craterkit {
namespace edmd {

// A cell index along an axis of n cells, wrapped on a periodic axis; -1 beyond a wall.
template <bool Periodic> inline long wrapCell(long k, long n) {
  if (k >= 0 && k < n)
    return k;
  if constexpr (Periodic)
    return k < 0 ? n - 1 : 0;
  return -1;
}

// Distinct cell indices within `reach` of c along an axis of n cells.
template <class F> void forAxisCells(long c, long reach, long n, bool periodic, F&& f) {
  if (periodic && 2 * reach + 1 >= n) {
    for (long k = 0; k < n; ++k)
      f(k);
    return;
  }
  for (long k = c - reach; k <= c + reach; ++k) {
    if (k >= 0 && k < n)
      f(k);
    else if (periodic)
      f((k % n + n) % n);
  }
}

} // namespace edmd

template <class F> void HardDiskSystem::forNearby(std::size_t i, F&& f) const {
  const long cx = static_cast<long>(cellOf_[i].x), cy = static_cast<long>(cellOf_[i].y);
  edmd::forAxisCells(cy, reach_[i], static_cast<long>(ny_), p_.periodicY, [&](long ky) {
    edmd::forAxisCells(cx, reach_[i], static_cast<long>(nx_), p_.periodicX, [&](long kx) {
      const std::size_t cell = static_cast<std::size_t>(ky) * nx_ + static_cast<std::size_t>(kx);
      for (std::int32_t k = head_[cell]; k >= 0; k = h_[static_cast<std::size_t>(k)].next)
        f(static_cast<std::size_t>(k));
    });
  });
}

inline void HardDiskSystem::insertInCell(std::size_t i, std::size_t cx, std::size_t cy) {
  cellOf_[i] = CellXY{static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy)};
  if (isBig_[i])
    return; // big disks are not listed: they scan for the small ones, and everyone checks them
  const std::size_t cell = cy * nx_ + cx;
  prevInCell_[i] = -1;
  h_[i].next = head_[cell];
  if (head_[cell] >= 0)
    prevInCell_[static_cast<std::size_t>(head_[cell])] = static_cast<std::int32_t>(i);
  head_[cell] = static_cast<std::int32_t>(i);
}

inline void HardDiskSystem::removeFromCell(std::size_t i) {
  if (isBig_[i])
    return;
  const std::int32_t prev = prevInCell_[i], next = h_[i].next;
  if (prev >= 0)
    h_[static_cast<std::size_t>(prev)].next = next;
  else
    head_[static_cast<std::size_t>(cellOf_[i].y) * nx_ + cellOf_[i].x] = next;
  if (next >= 0)
    prevInCell_[static_cast<std::size_t>(next)] = prev;
}

} // namespace craterkit

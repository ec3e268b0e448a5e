// A sparse grid of cubic cells keyed by their integer coordinates: items (indices) listed by
// the cell that holds a point, for neighbour searches over the 27 cells around a point and for
// grouping by cell. Only occupied cells cost memory, so a wide, thinly filled domain (an ejecta
// curtain) is cheap. Neighbours are found by offsetting the integer coordinates, never by
// re-dividing shifted positions (which can round into the wrong cell).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <unordered_map>
#include <vector>

namespace craterkit {

class SparseGrid {
public:
  using Cell = std::array<long long, 3>;

  explicit SparseGrid(double edge) : edge_(edge) {}

  double edge() const { return edge_; }

  // The cell (cubes `edge` wide) that holds x.
  Cell cellOf(const double* x) const {
    Cell c;
    for (int a = 0; a < 3; ++a)
      c[a] = static_cast<long long>(std::floor(x[a] / edge_));
    return c;
  }

  void reserve(std::size_t cells) { cells_.reserve(cells); }
  void insert(const double* x, std::size_t item) { cells_[cellOf(x)].push_back(item); }

  // Calls f(item) for every item listed in the 27 cells around the cell of x; f returns true to
  // take the item off the grid (the others keep their order).
  template <class F> void forEachNear(const double* x, F&& f) { forEachWithin(x, 1, f); }

  // The same for the (2 rings + 1)^3 cells around the cell of x: every item closer to x than
  // `rings` cell edges on each axis is among them.
  template <class F> void forEachWithin(const double* x, long long rings, F&& f) {
    const Cell c = cellOf(x);
    for (long long dx = -rings; dx <= rings; ++dx)
      for (long long dy = -rings; dy <= rings; ++dy)
        for (long long dz = -rings; dz <= rings; ++dz) {
          const auto cell = cells_.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (cell == cells_.end())
            continue;
          std::vector<std::size_t>& items = cell->second;
          std::size_t w = 0;
          for (std::size_t k = 0; k < items.size(); ++k)
            if (!f(items[k]))
              items[w++] = items[k];
          items.resize(w);
        }
  }

  // Calls f(items) for every occupied cell in ascending order of its coordinates (x, then y,
  // then z): an order that does not depend on the hash table.
  template <class F> void forEachCellInOrder(F&& f) const {
    std::vector<const std::pair<const Cell, std::vector<std::size_t>>*> order;
    order.reserve(cells_.size());
    for (const auto& cell : cells_)
      order.push_back(&cell);
    std::sort(order.begin(), order.end(), [](auto a, auto b) { return a->first < b->first; });
    for (const auto* cell : order)
      f(cell->second);
  }

private:
  struct Hash {
    std::size_t operator()(const Cell& c) const {
      const long long h = (c[0] * 73856093LL) ^ (c[1] * 19349663LL) ^ (c[2] * 83492791LL);
      return static_cast<std::size_t>(h);
    }
  };
  double edge_;
  std::unordered_map<Cell, std::vector<std::size_t>, Hash> cells_;
};

// Spheres of different radii on two sparse grids: those up to `ordinary` on cells twice that
// wide, the few larger ones (up to `largest`) on cells of twice theirs, so that one large body
// (common/CellList.h, sizeClasses) makes no cell, and no search for the others, larger. Cells
// a hundred-millionth wider than two radii keep the rounding of the division that files a
// point from putting an overlapping sphere's centre one ring too far.
class SphereGrid {
public:
  SphereGrid(double ordinary, double largest)
      : ordinary_(ordinary), small_(2.0 * ordinary * (1.0 + 1e-8)),
        large_(2.0 * largest * (1.0 + 1e-8)) {}

  void reserve(std::size_t cells) { small_.reserve(cells); }
  // A sphere of radius r (at most `largest`) at x.
  void insert(const double* x, double r, std::size_t item) {
    const bool large = r > ordinary_;
    (large ? large_ : small_).insert(x, item);
    hasLarge_ = hasLarge_ || large;
  }

  // Calls f(item) for every listed sphere that a sphere of radius r (at most `largest`) at x
  // overlaps (centres closer than the sum of the radii), and for some others near it; f
  // returns true to take the item off the grid.
  template <class F> void forEachOverlapCandidate(const double* x, double r, F&& f) {
    long long rings = 1; // r + r_j <= two ordinary radii < one cell
    if (r > ordinary_)   // r + r_j <= r + ordinary, with a margin for the rounding
      rings += static_cast<long long>(std::floor((r + ordinary_) / small_.edge() * (1.0 + 1e-8)));
    small_.forEachWithin(x, rings, f);
    if (hasLarge_)
      large_.forEachNear(x, f);
  }

private:
  double ordinary_;
  SparseGrid small_, large_;
  bool hasLarge_ = false;
};

} // namespace craterkit

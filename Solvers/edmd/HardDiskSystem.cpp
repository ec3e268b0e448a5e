#include "edmd/HardDiskSystem.h"

#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace craterkit {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string describeDisk(const HardDisks& d, std::size_t i) {
  std::ostringstream s;
  s << "disk " << i << " (Id " << d.id[i] << ")";
  return s.str();
}

// Nearest periodic image of a separation (|d| < 1.5 L for disks in neighbouring cells).
inline double minimumImage(double d, double length) {
  if (d > 0.5 * length)
    return d - length;
  if (d < -0.5 * length)
    return d + length;
  return d;
}

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
} // namespace

void HardDisks::add(double px, double py, double pvx, double pvy, double r, double m, int mat,
                    std::int64_t ident) {
  x.push_back(px);
  y.push_back(py);
  vx.push_back(pvx);
  vy.push_back(pvy);
  radius.push_back(r);
  mass.push_back(m);
  material.push_back(mat);
  id.push_back(ident);
}

void HardDiskParams::validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError(std::string(name) + " must be positive and finite (got " +
                       std::to_string(v) + ")");
  };
  positive(width, "the box width");
  positive(height, "the box height");
  if (!(restitution > 0.0 && restitution <= 1.0))
    throw InputError("Restitution must be in (0, 1] (got " + std::to_string(restitution) + ")");
  if (!(wallRestitution > 0.0 && wallRestitution <= 1.0))
    throw InputError("the wall restitution must be in (0, 1] (got " +
                     std::to_string(wallRestitution) + ")");
  if (!(gravity >= 0.0) || !std::isfinite(gravity))
    throw InputError("Gravity must be zero or positive (got " + std::to_string(gravity) + ")");
  if (!(tcTime >= 0.0) || !std::isfinite(tcTime))
    throw InputError("the TC-model time must be zero or positive");
  if (!(growthRate >= 0.0) || !std::isfinite(growthRate))
    throw InputError("the growth rate must be zero or positive");
  if (growthRate > 0.0 && gravity > 0.0)
    throw InputError("radius growth (compression) runs without gravity");
  if (periodicY && gravity > 0.0)
    throw InputError("gravity along a periodic axis is not supported");
}

HardDiskSystem::HardDiskSystem(const HardDisks& disks, const HardDiskParams& params)
    : d_(disks), p_(params) {
  p_.validate();
  const std::size_t n = d_.size();
  if (n == 0)
    throw InputError("no disks to simulate");
  if (d_.x.size() != n || d_.y.size() != n || d_.vx.size() != n || d_.vy.size() != n ||
      d_.mass.size() != n || d_.material.size() != n || d_.id.size() != n)
    throw InputError("the disk arrays differ in length");
  h_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    h_[i] = Hot{disks.x[i],      disks.y[i],    disks.vx[i], disks.vy[i], 0.0,
                disks.radius[i], disks.mass[i], 0,           -1};
  if (n >= std::numeric_limits<std::uint32_t>::max() / 2)
    throw InputError("too many disks");
  for (std::size_t i = 0; i < n; ++i) {
    const double vals[5] = {h_[i].x, h_[i].y, h_[i].vx, h_[i].vy, h_[i].r};
    for (double v : vals)
      if (!std::isfinite(v))
        throw InputError(describeDisk(d_, i) + " has a non-finite position, velocity or radius");
    if (!(h_[i].r > 0.0))
      throw InputError(describeDisk(d_, i) + " has a non-positive radius");
    if (!(h_[i].m > 0.0) || !std::isfinite(h_[i].m))
      throw InputError(describeDisk(d_, i) + " has a non-positive mass");
    const double r = h_[i].r;
    const bool inX = p_.periodicX ? (h_[i].x >= 0.0 && h_[i].x < p_.width)
                                  : (h_[i].x >= r && h_[i].x <= p_.width - r);
    const bool inY = p_.periodicY ? (h_[i].y >= 0.0 && h_[i].y < p_.height)
                                  : (h_[i].y >= r && h_[i].y <= p_.height - r);
    if (!inX || !inY)
      throw InputError(describeDisk(d_, i) + " is not inside the box (or is larger than it)");
  }
  // Small and big disks: cells fit the small ones.
  const double rmin = *std::min_element(disks.radius.begin(), disks.radius.end());
  const double rmax = *std::max_element(disks.radius.begin(), disks.radius.end());
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
  lastCollision_.assign(n, -kInf);
  pairBest_.assign(n, Event{kInf, 0, EventType::None, 0});

  // Overlapping input is an error: the dynamics of hard disks is undefined for it.
  const double gap = smallestGapNearby();
  if (gap < -1e-9 * rmin)
    throw InputError("disks overlap in the input (deepest overlap " + std::to_string(-gap) +
                     " m): space them first");
  predictAll();
}

const HardDisks& HardDiskSystem::disks() const {
  for (std::size_t i = 0; i < h_.size(); ++i) {
    d_.x[i] = h_[i].x;
    d_.y[i] = h_[i].y;
    d_.vx[i] = h_[i].vx;
    d_.vy[i] = h_[i].vy;
  }
  return d_;
}

double HardDiskSystem::smallestGap() const {
  // Brute force over neighbouring cells plus all big disks (tests call it on small systems).
  double best = kInf;
  const std::size_t n = d_.size();
  const double g = growth(time_);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      double dx = h_[j].x - h_[i].x, dy = h_[j].y - h_[i].y;
      if (p_.periodicX)
        dx -= p_.width * std::round(dx / p_.width);
      if (p_.periodicY)
        dy -= p_.height * std::round(dy / p_.height);
      best = std::min(best, std::sqrt(dx * dx + dy * dy) - (h_[i].r + h_[j].r) * g);
    }
  return best;
}

double HardDiskSystem::gapNow(std::size_t i, std::size_t j) const {
  const double dti = time_ - h_[i].t, dtj = time_ - h_[j].t, acc = p_.gravity;
  double dx = h_[j].x + h_[j].vx * dtj - h_[i].x - h_[i].vx * dti;
  double dy =
      h_[j].y + (h_[j].vy - 0.5 * acc * dtj) * dtj - h_[i].y - (h_[i].vy - 0.5 * acc * dti) * dti;
  if (p_.periodicX)
    dx = minimumImage(dx, p_.width);
  if (p_.periodicY)
    dy = minimumImage(dy, p_.height);
  return std::sqrt(dx * dx + dy * dy) - (h_[i].r + h_[j].r) * growth(time_);
}

template <class F> void HardDiskSystem::forNearby(std::size_t i, F&& f) const {
  const long cx = static_cast<long>(cellOf_[i].x), cy = static_cast<long>(cellOf_[i].y);
  forAxisCells(cy, reach_[i], static_cast<long>(ny_), p_.periodicY, [&](long ky) {
    forAxisCells(cx, reach_[i], static_cast<long>(nx_), p_.periodicX, [&](long kx) {
      for (std::int32_t k =
               head_[static_cast<std::size_t>(ky) * nx_ + static_cast<std::size_t>(kx)];
           k >= 0; k = h_[static_cast<std::size_t>(k)].next)
        f(static_cast<std::size_t>(k));
    });
  });
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

void HardDiskSystem::insertInCell(std::size_t i, std::size_t cx, std::size_t cy) {
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

void HardDiskSystem::removeFromCell(std::size_t i) {
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

void HardDiskSystem::stream(std::size_t i) {
  const double dt = time_ - h_[i].t;
  if (dt == 0.0)
    return;
  const double g = p_.gravity;
  const double y0 = h_[i].y, vy0 = h_[i].vy;
  h_[i].x += h_[i].vx * dt;
  h_[i].y = y0 + vy0 * dt - 0.5 * g * dt * dt;
  h_[i].vy = vy0 - g * dt;
  h_[i].t = time_;
  if (watchSurface_ && !crossed_[i] && y0 < surface_ && h_[i].y >= surface_ &&
      d_.material[i] == groundMaterial_) {
    // First upward crossing on this segment: y0 + vy0 τ - g τ²/2 = surface, smallest root.
    const double h = surface_ - y0;
    const double disc = std::max(0.0, vy0 * vy0 - 2.0 * g * h);
    const double tau = vy0 > 0.0 ? 2.0 * h / (vy0 + std::sqrt(disc)) : dt;
    crossed_[i] = 1;
    crossings_.push_back(SurfaceCrossing{static_cast<std::uint32_t>(i), time_ - dt + tau,
                                         h_[i].x - h_[i].vx * (dt - tau), h_[i].vx, vy0 - g * tau});
  }
}

double HardDiskSystem::exitTime(double pos, double vel, double acc, double lo, double hi,
                                int& side) const {
  // Time until pos + vel τ + acc τ²/2 reaches lo (side -1) or hi (side +1); acc <= 0.
  side = 0;
  if (acc == 0.0) {
    if (vel > 0.0 && hi < kInf) {
      side = 1;
      return std::max(0.0, (hi - pos) / vel);
    }
    if (vel < 0.0 && lo > -kInf) {
      side = -1;
      return std::max(0.0, (lo - pos) / vel);
    }
    return kInf;
  }
  const double g = -acc;
  if (vel > 0.0 && hi < kInf) {
    const double up = hi - pos, disc = vel * vel - 2.0 * g * up;
    if (disc >= 0.0) {
      side = 1;
      return std::max(0.0, 2.0 * up / (vel + std::sqrt(disc)));
    }
  }
  if (lo == -kInf)
    return kInf;
  side = -1;
  const double down = std::max(0.0, pos - lo), root = std::sqrt(vel * vel + 2.0 * g * down);
  return vel >= 0.0 ? (vel + root) / g : 2.0 * down / (root - vel);
}

void HardDiskSystem::cellEvent(std::size_t i, Event& best) const {
  const std::size_t cx = cellOf_[i].x, cy = cellOf_[i].y;
  const double xlo = (cx == 0 && !p_.periodicX) ? -kInf : cx * cellW_;
  const double xhi = (cx + 1 == nx_ && !p_.periodicX) ? kInf : (cx + 1) * cellW_;
  const double ylo = (cy == 0 && !p_.periodicY) ? -kInf : cy * cellH_;
  const double yhi = (cy + 1 == ny_ && !p_.periodicY) ? kInf : (cy + 1) * cellH_;
  // A straight flight reaches the face it moves towards at (face - pos) / vel; a face at
  // infinity (a walled end of the grid) gives an infinite time, so no event.
  auto straight = [](double pos, double vel, double lo, double hi, int& side) {
    side = vel > 0.0 ? 1 : vel < 0.0 ? -1 : 0;
    return side == 0 ? kInf : std::max(0.0, ((side > 0 ? hi : lo) - pos) / vel);
  };
  int sx, sy;
  const double tx = straight(h_[i].x, h_[i].vx, xlo, xhi, sx);
  const double ty = p_.gravity == 0.0 ? straight(h_[i].y, h_[i].vy, ylo, yhi, sy)
                                      : exitTime(h_[i].y, h_[i].vy, -p_.gravity, ylo, yhi, sy);
  if (time_ + tx < best.t && sx != 0)
    best = Event{time_ + tx, static_cast<std::uint32_t>(sx < 0 ? 0 : 1), EventType::Cell, 0};
  if (time_ + ty < best.t && sy != 0)
    best = Event{time_ + ty, static_cast<std::uint32_t>(sy < 0 ? 2 : 3), EventType::Cell, 0};
}

void HardDiskSystem::wallEvent(std::size_t i, Event& best) const {
  const double r = h_[i].r * growth(time_), rdot = h_[i].r * p_.growthRate;
  auto linear = [&](double pos, double vel, double size, std::uint32_t lowWall) {
    // Low wall: pos + vel τ = r + ṙ τ; high wall: pos + vel τ = size - r - ṙ τ.
    if (vel - rdot < 0.0) {
      const double t = time_ + std::max(0.0, (pos - r) / (rdot - vel));
      if (t < best.t)
        best = Event{t, lowWall, EventType::Wall, 0};
    }
    if (vel + rdot > 0.0) {
      const double t = time_ + std::max(0.0, (size - r - pos) / (vel + rdot));
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
      const double t = time_ + exitTime(h_[i].y, h_[i].vy, -p_.gravity, r, p_.height - r, side);
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
  const double c = rx * rx + ry * ry - sigma * sigma;
  const double b = rx * ux + ry * uy - sigma * sdot;
  const double a = ux * ux + uy * uy - sdot * sdot;
  double tau;
  if (c <= 0.0) {
    if (b >= 0.0)
      return; // touching or overlapping by round-off, and separating
    tau = 0.0;
  } else {
    if (b >= 0.0 && a >= 0.0)
      return;
    const double disc = b * b - a * c;
    if (disc < 0.0)
      return;
    tau = c / (-b + std::sqrt(disc));
  }
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

void HardDiskSystem::collide(std::size_t i, std::size_t j) {
  stream(i);
  stream(j);
  double rx = h_[j].x - h_[i].x, ry = h_[j].y - h_[i].y;
  if (p_.periodicX)
    rx = minimumImage(rx, p_.width);
  if (p_.periodicY)
    ry = minimumImage(ry, p_.height);
  const double dist = std::sqrt(rx * rx + ry * ry);
  const double nx = rx / dist, ny = ry / dist;
  const double approach = (h_[i].vx - h_[j].vx) * nx + (h_[i].vy - h_[j].vy) * ny;
  const double mi = h_[i].m, mj = h_[j].m, mred = mi * mj / (mi + mj);
  const double sigma0 = h_[i].r + h_[j].r;
  double e = p_.restitution;
  if (p_.tcTime > 0.0 &&
      (time_ - lastCollision_[i] < p_.tcTime || time_ - lastCollision_[j] < p_.tcTime))
    e = 1.0;
  const double J = std::max(0.0, mred * ((1.0 + e) * approach + 2.0 * sigma0 * p_.growthRate));
  h_[i].vx -= J / mi * nx;
  h_[i].vy -= J / mi * ny;
  h_[j].vx += J / mj * nx;
  h_[j].vy += J / mj * ny;
  virial_ += sigma0 * growth(time_) * J;
  ++h_[i].count;
  ++h_[j].count;
  if (p_.tcTime > 0.0)
    lastCollision_[i] = lastCollision_[j] = time_;
  ++pairCollisions_;
  if (sourceMaterial_ >= 0 && (disturbed_[i] || disturbed_[j]))
    disturbed_[i] = disturbed_[j] = 1;
  if (log_)
    log_->push_back(EventRecord{time_, EventType::Pair, static_cast<std::uint32_t>(i),
                                static_cast<std::uint32_t>(j)});
  if (fastScan(i) && fastScan(j)) {
    (this->*predictPair_)(i, j);
  } else {
    predict(i);
    predict(j);
  }
}

void HardDiskSystem::hitWall(std::size_t i, std::uint32_t wall) {
  stream(i);
  double e = p_.wallRestitution;
  if (p_.tcTime > 0.0 && time_ - lastCollision_[i] < p_.tcTime)
    e = 1.0;
  const double rdot = h_[i].r * p_.growthRate;
  double& v = wall < 2 ? h_[i].vx : h_[i].vy;
  const double away = (wall % 2 == 0) ? 1.0 : -1.0; // direction pointing into the box
  // Incoming speed towards the wall (relative to the growing radius), reversed and scaled.
  const double incoming = std::max(0.0, -away * v + rdot);
  double out = e * incoming + rdot;
  if (wall == 2 && p_.gravity > 0.0) {
    // A disk resting on the floor would collide infinitely often: give it a rebound of at
    // least the speed that lifts it by 1e-6 of its radius.
    out = std::max(out, std::sqrt(2.0 * p_.gravity * 1e-6 * h_[i].r));
  }
  v = away * out;
  ++h_[i].count;
  if (p_.tcTime > 0.0)
    lastCollision_[i] = time_;
  ++wallCollisions_;
  if (log_)
    log_->push_back(EventRecord{time_, EventType::Wall, static_cast<std::uint32_t>(i), wall});
  predict(i);
}

void HardDiskSystem::crossCell(std::size_t i, std::uint32_t direction) {
  stream(i);
  long cx = static_cast<long>(cellOf_[i].x), cy = static_cast<long>(cellOf_[i].y);
  switch (direction) {
  case 0:
    if (--cx < 0) {
      cx = static_cast<long>(nx_) - 1;
      h_[i].x += p_.width;
    }
    break;
  case 1:
    if (++cx == static_cast<long>(nx_)) {
      cx = 0;
      h_[i].x -= p_.width;
    }
    break;
  case 2:
    if (--cy < 0) {
      cy = static_cast<long>(ny_) - 1;
      h_[i].y += p_.height;
    }
    break;
  default:
    if (++cy == static_cast<long>(ny_)) {
      cy = 0;
      h_[i].y -= p_.height;
    }
    break;
  }
  removeFromCell(i);
  insertInCell(i, static_cast<std::size_t>(cx), static_cast<std::size_t>(cy));
  ++cellCrossings_;
  if (log_)
    log_->push_back(EventRecord{time_, EventType::Cell, static_cast<std::uint32_t>(i), direction});
  predictAfterCrossing(i, direction);
}

bool HardDiskSystem::step(double limit) {
  const auto* top = queue_.top();
  if (!top || !(top->event.t < limit))
    return false;
  const std::size_t i = top->disk;
  const Event ev = top->event;
  // Everything this event reads first, requested at once: the disks' records and cells (the
  // partner's record also decides whether the event is stale).
  __builtin_prefetch(&h_[i]);
  __builtin_prefetch(&cellOf_[i]);
  if (ev.type == EventType::Pair) {
    __builtin_prefetch(&h_[ev.partner]);
    __builtin_prefetch(&cellOf_[ev.partner]);
  } else if (ev.type == EventType::Cell) {
    __builtin_prefetch(&pairBest_[i]);
    __builtin_prefetch(&prevInCell_[i]);
  }
  queue_.pop();
  time_ = std::max(time_, ev.t);
  switch (ev.type) {
  case EventType::Pair:
    if (h_[ev.partner].count != ev.partnerCount) {
      ++stale_;
      stream(i);
      predict(i);
    } else {
      collide(i, ev.partner);
    }
    break;
  case EventType::Wall:
    hitWall(i, ev.partner);
    break;
  case EventType::Cell:
    crossCell(i, ev.partner);
    break;
  case EventType::None:
    return false;
  }
  if (checkOverlaps_) {
    verify(i);
    if (ev.type == EventType::Pair)
      verify(ev.partner);
  }
  return true;
}

void HardDiskSystem::verify(std::size_t i) const {
  const double g = growth(time_);
  auto check = [&](std::size_t j) {
    if (j != i && gapNow(i, j) < -1e-9 * (h_[i].r + h_[j].r) * g) {
      std::ostringstream msg;
      msg << describeDisk(d_, i) << " overlaps " << describeDisk(d_, j) << " at t = " << time_;
      throw std::logic_error(msg.str());
    }
  };
  forNearby(i, check);
  for (std::uint32_t b : bigs_)
    check(b);
  // Inside the box along walled axes.
  const double r = h_[i].r * g, dti = time_ - h_[i].t;
  const double x = h_[i].x + h_[i].vx * dti,
               y = h_[i].y + (h_[i].vy - 0.5 * p_.gravity * dti) * dti;
  const double tol = 1e-9 * r;
  if ((!p_.periodicX && (x < r - tol || x > p_.width - r + tol)) ||
      (!p_.periodicY && (y < r - tol || y > p_.height - r + tol))) {
    std::ostringstream msg;
    msg << describeDisk(d_, i) << " left the box at t = " << time_;
    throw std::logic_error(msg.str());
  }
}

void HardDiskSystem::advanceTo(double t, const ProgressCallback& progress) {
  if (!(t >= time_) || !std::isfinite(t))
    throw InputError("cannot advance hard disks backwards or to a non-finite time");
  if (p_.growthRate > 0.0 && t > p_.growthEnd * (1.0 + 1e-12))
    throw InputError("radius growth beyond the planned end of compression");
  const double start = time_;
  std::uint64_t events = 0;
  while (step(t)) {
    if ((++events & 0xFFFF) == 0 && progress)
      reportProgress(progress, (time_ - start) / (t - start));
  }
  time_ = t;
  for (std::size_t i = 0; i < d_.size(); ++i)
    stream(i);
}

double HardDiskSystem::processEvents(std::uint64_t n) {
  std::uint64_t done = 0;
  while (done < n) {
    const std::uint64_t staleBefore = stale_;
    if (!step(kInf))
      break;
    if (stale_ == staleBefore)
      ++done;
  }
  return time_;
}

double HardDiskSystem::kineticEnergy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < d_.size(); ++i) {
    const double vy = h_[i].vy - p_.gravity * (time_ - h_[i].t);
    e += 0.5 * h_[i].m * (h_[i].vx * h_[i].vx + vy * vy);
  }
  return e;
}

void HardDiskSystem::momentum(double& px, double& py) const {
  px = py = 0.0;
  for (std::size_t i = 0; i < d_.size(); ++i) {
    px += h_[i].m * h_[i].vx;
    py += h_[i].m * (h_[i].vy - p_.gravity * (time_ - h_[i].t));
  }
}

void HardDiskSystem::watchSurface(double level, int groundMaterial) {
  watchSurface_ = true;
  surface_ = level;
  groundMaterial_ = groundMaterial;
  crossed_.assign(d_.size(), 0);
  crossings_.clear();
}

void HardDiskSystem::trackDisturbance(int sourceMaterial) {
  sourceMaterial_ = sourceMaterial;
  disturbed_.assign(d_.size(), 0);
  for (std::size_t i = 0; i < d_.size(); ++i)
    disturbed_[i] = d_.material[i] == sourceMaterial;
}

void HardDiskSystem::scaleVelocities(double factor) {
  for (std::size_t i = 0; i < d_.size(); ++i) {
    stream(i);
    h_[i].vx *= factor;
    h_[i].vy *= factor;
    ++h_[i].count;
  }
  predictAll();
}

} // namespace craterkit

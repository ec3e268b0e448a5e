// The hard-disk system (HardDiskSystem.h): its set-up from the input, the disks and
// observables it reports, the records it keeps and the checks the tests run. The event loop,
// the event prediction and the cell grid have their own files.
#include "edmd/HardDiskGrid.h"

#include "common/Error.h"
#include "edmd/EventTimes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace craterkit {

using edmd::kInf;
using edmd::minimumImage;

namespace {
std::string describeDisk(const HardDisks& d, std::size_t i) {
  std::ostringstream s;
  s << "disk " << i << " (Id " << d.id[i] << ")";
  return s.str();
}
} // namespace

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
  const double rmin = *std::min_element(disks.radius.begin(), disks.radius.end());
  const double rmax = *std::max_element(disks.radius.begin(), disks.radius.end());
  setUpGrid(rmin, rmax);
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

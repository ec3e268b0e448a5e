// The event loop of the hard-disk system (HardDiskSystem.h): lazy streaming of a disk to the
// current time, the three kinds of event (pair collision, wall collision, cell crossing) and
// the loop that takes the earliest event from the queue until a stop.
#include "edmd/HardDiskGrid.h"

#include "common/Error.h"
#include "edmd/EventTimes.h"

#include <algorithm>
#include <cmath>

namespace craterkit {

using edmd::kInf;
using edmd::minimumImage;

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

} // namespace craterkit

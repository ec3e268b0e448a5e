// Event times of hard disks in free flight (docs/physics.md §6): the closed-form roots that
// event-driven molecular dynamics schedules (Alder & Wainwright 1959; Rapaport, "The Art of
// Molecular Dynamics Simulation", 2nd ed., ch. 14).
//
// A disk flies on a straight line, or on a parabola pos + vel τ + acc τ²/2 under uniform
// gravity along -y. The time it reaches a cell face or a wall is the smallest positive root
// of a linear or quadratic equation; a pair meets when |r + u τ| = σ + σ̇ τ (σ̇ > 0 only while
// the radii grow, Lubachevsky & Stillinger 1990), the smaller root of
//   a τ² + 2 b τ + c = 0,  a = u² - σ̇²,  b = r·u - σ σ̇,  c = r² - σ².
// Gravity drops out of the pair equation: both disks fall alike. The roots are written in the
// forms that do not cancel (2c / (-b + √disc) rather than (-b - √disc) / a).
//
// Header-only: the event loop calls these for every disk it predicts, so they are inlined.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace craterkit::edmd {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Nearest periodic image of a separation (|d| < 1.5 L for disks in neighbouring cells).
inline double minimumImage(double d, double length) {
  if (d > 0.5 * length)
    return d - length;
  if (d < -0.5 * length)
    return d + length;
  return d;
}

// Time until a straight flight from pos reaches lo (side -1) or hi (side +1): the face it moves
// towards at (face - pos) / vel; a face at infinity (a walled end of the grid) gives an
// infinite time, so no event.
inline double straightExitTime(double pos, double vel, double lo, double hi, int& side) {
  side = vel > 0.0 ? 1 : vel < 0.0 ? -1 : 0;
  return side == 0 ? kInf : std::max(0.0, ((side > 0 ? hi : lo) - pos) / vel);
}

// Time until pos + vel τ + acc τ²/2 reaches lo (side -1) or hi (side +1); acc <= 0.
inline double exitTime(double pos, double vel, double acc, double lo, double hi, int& side) {
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

// A disk of radius r growing at ṙ, at pos with velocity vel along an axis walled at 0 and at
// size: the time it touches the low wall (pos + vel τ = r + ṙ τ, when vel - ṙ < 0) and the
// high wall (pos + vel τ = size - r - ṙ τ, when vel + ṙ > 0).
inline double lowWallTime(double pos, double vel, double r, double rdot) {
  return std::max(0.0, (pos - r) / (rdot - vel));
}
inline double highWallTime(double pos, double vel, double size, double r, double rdot) {
  return std::max(0.0, (size - r - pos) / (vel + rdot));
}

// The time τ >= 0 until two disks at separation (rx, ry) with relative velocity (ux, uy) touch
// at contact distance sigma growing at sdot; false when they never do (or are touching or
// overlapping by round-off and separating).
inline bool pairContactTime(double rx, double ry, double ux, double uy, double sigma, double sdot,
                            double& tau) {
  const double c = rx * rx + ry * ry - sigma * sigma;
  const double b = rx * ux + ry * uy - sigma * sdot;
  const double a = ux * ux + uy * uy - sdot * sdot;
  if (c <= 0.0) {
    if (b >= 0.0)
      return false;
    tau = 0.0;
    return true;
  }
  if (b >= 0.0 && a >= 0.0)
    return false;
  const double disc = b * b - a * c;
  if (disc < 0.0)
    return false;
  tau = c / (-b + std::sqrt(disc));
  return true;
}

} // namespace craterkit::edmd

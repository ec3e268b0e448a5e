// SPH smoothing kernels in 3D with compact support h (the miluphcuda convention: W = 0 for
// r >= h; a code using support 2h passes 2h). docs/physics.md §2.1.
//   CubicSpline: W = 8/(π h³) {6q³ − 6q² + 1 (q < ½); 2(1 − q)³ (½ ≤ q ≤ 1); 0}, q = r/h.
//   WendlandC2:  W = 21/(2π h³) (1 − q)⁴ (1 + 4q) (Wendland 1995; Dehnen & Aly 2012), no pairing
//                instability for large neighbour numbers.
// Each gives W(r, h) and dW/dr(r, h); the gradient with respect to x_a is dW/dr · r_ab / r.
#pragma once

#include <cmath>

namespace craterkit {

struct CubicSpline {
  static constexpr const char* name = "CubicSpline";
  static double W(double r, double h) {
    const double q = r / h, s = 8.0 / (M_PI * h * h * h);
    if (q < 0.5)
      return s * (6.0 * q * q * q - 6.0 * q * q + 1.0);
    if (q < 1.0) {
      const double t = 1.0 - q;
      return s * 2.0 * t * t * t;
    }
    return 0.0;
  }
  static double dWdr(double r, double h) {
    const double q = r / h, s = 8.0 / (M_PI * h * h * h * h);
    if (q < 0.5)
      return s * (18.0 * q * q - 12.0 * q);
    if (q < 1.0) {
      const double t = 1.0 - q;
      return -s * 6.0 * t * t;
    }
    return 0.0;
  }
};

// Branch-free forms for vectorised loops, valid for 0 < q = r/h < 1 (callers filter first):
// gradOverR(q, ih, iq) = (dW/dr) / r and value(q, ih) = W, with ih = 1/h and iq = 1/q (the
// caller has 1/r at hand, so the kernel needs no division of its own).
inline double cubicGradOverR(double q, double ih, double iq) {
  const double ih2 = ih * ih, s = 8.0 / M_PI * ih2 * ih2 * ih; // 8/(π h⁵)
  const double t = 1.0 - q;
  const double inner = 18.0 * q - 12.0; // (18q² − 12q)/q
  const double outer = -6.0 * t * t * iq;
  return s * (q < 0.5 ? inner : outer);
}
// The cubic spline's shape without its normalisation 8/(π h³), for 0 ≤ q < 1: W/W(0). Also a
// weight where the normalisation cancels (the hand-off's velocity fit).
inline double cubicShape(double q) {
  const double t = 1.0 - q;
  return q < 0.5 ? 6.0 * q * q * q - 6.0 * q * q + 1.0 : 2.0 * t * t * t;
}
inline double cubicValue(double q, double ih) {
  const double s = 8.0 / M_PI * ih * ih * ih;
  return s * cubicShape(q);
}

struct WendlandC2 {
  static constexpr const char* name = "WendlandC2";
  static double W(double r, double h) {
    const double q = r / h;
    if (q >= 1.0)
      return 0.0;
    const double t = 1.0 - q;
    return 21.0 / (2.0 * M_PI * h * h * h) * t * t * t * t * (1.0 + 4.0 * q);
  }
  static double dWdr(double r, double h) {
    const double q = r / h;
    if (q >= 1.0)
      return 0.0;
    const double t = 1.0 - q;
    // d/dq [(1-q)^4 (1+4q)] = -20 q (1-q)^3
    return 21.0 / (2.0 * M_PI * h * h * h * h) * (-20.0 * q * t * t * t);
  }
};

inline double wendlandGradOverR(double q, double ih, double /*iq*/) {
  const double t = 1.0 - q, ih2 = ih * ih;
  return 21.0 / (2.0 * M_PI) * ih2 * ih2 * ih * (-20.0 * t * t * t);
}
inline double wendlandValue(double q, double ih) {
  const double t = 1.0 - q;
  return 21.0 / (2.0 * M_PI) * ih * ih * ih * t * t * t * t * (1.0 + 4.0 * q);
}

template <class K> struct Branchless;
template <> struct Branchless<CubicSpline> {
  static double gradOverR(double q, double ih, double iq) { return cubicGradOverR(q, ih, iq); }
  static double value(double q, double ih) { return cubicValue(q, ih); }
};
template <> struct Branchless<WendlandC2> {
  static double gradOverR(double q, double ih, double iq) { return wendlandGradOverR(q, ih, iq); }
  static double value(double q, double ih) { return wendlandValue(q, ih); }
};

} // namespace craterkit

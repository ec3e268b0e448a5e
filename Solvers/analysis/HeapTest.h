// The fixed-base heap test of a contact model's angle of repose: a loose column of
// monodisperse spheres collapses onto a thin horizontal disk; what falls past the rim is
// removed, and the heap left on the disk is measured once it is at rest.
//
// Two angles: the cone angle atan(height / base radius), and the flank angle (least-squares
// slope of the surface between 30 % and 90 % of the base radius, HeapAngle.h). They agree
// once the base spans about 30 particle radii (benchmarks/README.md).
#pragma once

#include "dem/ContactModels.h"

#include <cstddef>

namespace craterkit {

struct HeapTestResult {
  std::size_t particlesStart = 0, particlesHeap = 0;
  double time = 0.0; // s until at rest
  double flankDegrees = 0.0;
  double coneDegrees = 0.0;
  double height = 0.0; // m, top of the heap above the base
  double base = 0.0;   // m, base radius
};

// contact: the model under test (k_N and Δt are chosen here); baseInRadii: base radius in
// particle radii (12 is a quick check, 30 a calibration).
HeapTestResult runFixedBaseHeap(const ContactParams& contact, double baseInRadii);

} // namespace craterkit

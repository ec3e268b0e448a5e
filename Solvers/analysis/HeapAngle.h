// Angle of repose of a granular heap on a horizontal floor.
//
// The surface height h(ρ) is the highest particle top in radial bins around the heap
// axis (through the centre of mass); the angle is atan of the least-squares slope of h
// over the flank, between fractions lo and hi of the heap's radial extent.
#pragma once

#include "common/ParticleSet.h"

namespace craterkit {

struct HeapAngle {
  double degrees = 0.0; // angle of repose
  double extent = 0.0;  // radial extent of the heap, m
  double height = 0.0;  // height of the top above the floor, m
  int bins = 0;         // bins used in the fit
};

HeapAngle measureHeapAngle(const ParticleSet& particles, double floorHeight, double lo = 0.25,
                           double hi = 0.75);

} // namespace craterkit

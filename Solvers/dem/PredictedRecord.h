// One record per particle of what the DEM's contact law and the force gather read of it
// besides its position: predicted velocity and spin (written by the drift, read by the law and
// the walls), mass and radius. Eight doubles, one cache line: the law's gathered loads of a
// pair's two particles touch two lines each (position and record) instead of five (position,
// radius, mass, predicted velocity, predicted spin), and the gather writes one line instead of
// two. Mass and radius are copies of the ParticleSet's (set with the record, compacted with it).
#pragma once

#include <cstddef>
#include <vector>

namespace craterkit {

struct alignas(64) PredictedRecord {
  double v[3], w[3], m, r;
};
static_assert(sizeof(PredictedRecord) == 64, "one cache line a particle");

} // namespace craterkit

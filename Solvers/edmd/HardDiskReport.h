// What the HardDiskCrater source shows of a hard-disk crater run (HardDiskCrater.h,
// docs/physics.md §4.3 and §6) at its current frame: the disks, the tracer paths and the
// transient crater outline, each in the output's x-z plane (the model's (x, y) as (x, 0, y)),
// and the run's figures in the order the source writes them as field data.
#pragma once

#include "analysis/CraterProfile.h"
#include "common/NamedValue.h"
#include "edmd/HardDiskCrater.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

// Per disk: position and velocity (3 components), areal density mass / (π r²), whether it is
// a tracer and whether the impact has disturbed it.
struct HardDiskPoints {
  std::vector<double> xyz, velocity, density;
  std::vector<int> tracer, disturbed;
};
HardDiskPoints hardDiskPoints(const HardDiskCraterRun& run);

// Polylines: `counts[k]` consecutive points of xyz per line.
struct HardDiskLines {
  std::vector<double> xyz;
  std::vector<std::size_t> counts;
  std::vector<double> time;      // per point: the frame time (tracer paths)
  std::vector<std::int64_t> ids; // per line: the tracer's disk id (tracer paths)
  SectionCrater crater;          // the outline's crater
};
// Each tracer's path up to the current frame.
HardDiskLines hardDiskTracerPaths(const HardDiskCraterRun& run);
// The ground's top in bins of four disk radii (the largest radius), one line, and the crater
// it outlines: more than one disk diameter below the original surface.
HardDiskLines hardDiskOutline(const HardDiskCraterRun& run);

// Time, frame, collision counts, energy and momentum, the shock front, the box, the ejections
// (per ejected disk: first upward crossing of the original surface, exact on its path), the
// crater's depth and width, the shock front at every frame so far and the ground disks.
std::vector<NamedValue> hardDiskFields(const HardDiskCraterRun& run, const SectionCrater& crater);

} // namespace craterkit

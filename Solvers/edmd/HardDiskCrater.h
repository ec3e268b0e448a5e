// The 2D hard-disk crater model (the "ball pit" of the third seed, docs/physics.md §4.3 and §6):
// a ground of hard disks at rest in a box, struck by one large disk or a clump of small
// ones, run event by event and stopped exactly at evenly spaced frame times.
//
// Coordinates: x across the box, y up; the ground fills 0 <= y <= groundDepth and the
// impact point is (width/2, groundDepth). Mass of a disk: density × π r² (unit thickness).
#pragma once

#include "common/Progress.h"
#include "edmd/HardDiskSystem.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace craterkit {

struct HardDiskCraterParams {
  // Box and ground.
  double width = 1.0;            // m
  double groundDepth = 0.5;      // m
  double headroom = 0.5;         // m of empty box above the ground
  double diskRadius = 0.005;     // m (smallest ground disk)
  double maxDiskRadius = 0.0;    // m; 0 or equal to diskRadius: one size; else uniform in radius
  double areaFraction = 0.70;    // of the ground layer
  double groundDensity = 1000.0; // kg/m³
  // Impactor.
  enum class Impactor { Disk, Clump } impactor = Impactor::Disk;
  double impactorRadius = 0.03; // m (the clump fills a disk of this radius)
  double densityRatio = 3.0;    // impactor density / ground density
  double impactSpeed = 10.0;    // m/s
  double impactAngle = 0.0;     // degrees from the vertical
  // Physics.
  double restitution = 1.0;
  double gravity = 0.0; // m/s²
  // Output.
  double frameInterval = 1e-3; // s
  double endTime = 0.1;        // s
  double tracerFraction = 0.02;
  std::uint64_t seed = 1;

  void validate() const;
  // Presets for teaching: "Ball pit", "Dense sand", "Clump impactor".
  static HardDiskCraterParams preset(const std::string& name);
  static std::vector<std::string> presetNames();
};

// The frame times a run with this frame interval and end time shows: 0, then every interval up
// to the end (at most 100000 frames); only 0 when either is not positive.
std::vector<double> hardDiskFrameTimes(double frameInterval, double endTime);

enum HardDiskMaterial { kGround = 0, kImpactor = 1 };

// Random ground at the requested area fraction: random sequential addition up to 0.40,
// then Lubachevsky–Stillinger compression (event-driven radius growth) to the target.
HardDisks generateHardDiskGround(const HardDiskCraterParams& p,
                                 const ProgressCallback& progress = {});

// One crater run: the system, frame bookkeeping, tracer paths and per-frame analysis.
class HardDiskCraterRun {
public:
  explicit HardDiskCraterRun(const HardDiskCraterParams& p, const ProgressCallback& progress = {});

  std::size_t frameCount() const { return frames_; } // frames 0..frameCount-1
  double frameTime(std::size_t k) const;
  // Advances to frame k (forwards only), recording every frame on the way.
  void advanceToFrame(std::size_t k, const ProgressCallback& progress = {});
  std::size_t currentFrame() const { return current_; }
  const HardDiskSystem& system() const { return *system_; }
  const HardDiskCraterParams& params() const { return p_; }

  const std::vector<std::uint32_t>& tracers() const { return tracers_; }
  // Tracer positions at frames 0..currentFrame, tracer-major: path[t][2 * frame + {0,1}].
  const std::vector<std::vector<double>>& tracerPaths() const { return paths_; }
  // Distance from the impact point of the farthest disturbed ground disk, per frame.
  const std::vector<double>& shockFront() const { return shock_; }

  struct Ejection {
    double angleDeg; // from the horizontal surface
    double distance; // launch distance from the impact point
    double speed;
    double time;
  };
  std::vector<Ejection> ejections() const;
  // The mean launch angle of these ejections, NaN when there are none.
  static double meanEjectionAngle(const std::vector<Ejection>& ejections);
  double impactX() const { return 0.5 * p_.width; }
  double surfaceLevel() const { return p_.groundDepth; }

  // Transient crater outline: the top of the connected ground column in bins of width `bin`
  // (gaps above a column larger than two disk diameters count as ejecta and are skipped).
  std::vector<double> surfaceProfile(double bin) const;

private:
  void recordFrame();
  HardDiskCraterParams p_;
  std::unique_ptr<HardDiskSystem> system_;
  std::size_t frames_ = 1, current_ = 0;
  std::vector<std::uint32_t> tracers_;
  std::vector<std::vector<double>> paths_;
  std::vector<double> shock_;
};

} // namespace craterkit

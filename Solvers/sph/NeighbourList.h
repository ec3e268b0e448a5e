// Neighbour lists for the SPH solver (docs/physics.md §2): a Verlet list built from cell
// lists, one sparse grid per level of h (√2 apart, so a graded target's fine particles do not
// scan cells sized for its coarse ones), with a margin per particle (skin h, more for fast
// ones) for motion and for growth of h, kept over steps until some pair could have come into
// range unlisted. Periodic axes are handled by storing, with each neighbour, which image of it
// is near. A pair (a, b) is listed when r_ab < grow max(h_a, h_b) + max(μ_a, μ_b), μ the
// margins. The build gives the same lists, in the same order, for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct SphState;
struct SphParams;

// A neighbour entry is index * 32 + image code, the code (sx+1) + 3 (sy+1) + 9 (sz+1) of the
// periodic shift; this one is the particle itself, unshifted.
constexpr std::uint32_t kNoShift = 13;

// Beyond the parameters' domainRadius from domainCentre (no limit when it is 0).
bool outsideDomain(const SphState& s, const SphParams& par, std::size_t i);

class NeighbourList {
public:
  // Lists the pairs of s: each particle's margin is skin h, or more for one that moves fast in
  // steps of dt (its velocity plus `dx`, the XSPH correction, when sized like v); none when
  // !margins.
  void build(const SphState& s, const SphParams& par, const std::vector<double>& dx, double dt,
             bool margins = true);
  // Whether the list still holds every pair for a step of dt: `dx` as for build (empty: no
  // XSPH), `dv` the accelerations (used when sized like v).
  bool valid(const SphState& s, const SphParams& par, const std::vector<double>& dx,
             const std::vector<double>& dv, double dt) const;
  const std::vector<std::uint32_t>& start() const { return start_; } // CSR offsets, size n+1
  const std::vector<std::uint32_t>& entry() const { return entry_; } // index * 32 + image code
  std::vector<std::uint32_t> sortedOf(std::size_t a) const;          // a's entries, sorted
  double margin(std::size_t a) const { return margin_[a]; }
  std::size_t builds() const { return builds_; }

private:
  struct Grids; // the candidates sorted into one sparse grid per level of h
  struct Handed {
    std::uint32_t to, entry;
  };
  // One thread's buffers for a build, kept over builds (no reallocation, no fresh pages) and
  // each on cache lines of its own: side by side, the two threads' vector headers shared a
  // line that both wrote at every cell row, which doubled the build's time on two threads.
  struct alignas(64) Work {
    std::vector<std::uint32_t> out; // the listed entries of the thread's particles, in order
    std::vector<Handed> handed;
    std::vector<std::uint8_t> keep; // which candidates of a run are listed
  };
  void setMargins(const SphState& s, const SphParams& par, const std::vector<double>& dx, double dt,
                  bool margins, double& hmax, double& hmin, double& muMax);
  void setLevels(const SphState& s, double hmax, double hmin);
  bool visit(const Grids& g, const SphState& s, std::size_t a, std::vector<std::uint32_t>& out,
             std::vector<Handed>& handed, std::vector<std::uint8_t>& keep) const;
  double clearanceOf(const Grids& g, const SphState& s, const SphParams& par, std::size_t a,
                     double far) const;
  void listAll(const Grids& g, const SphState& s, const SphParams& par, double reach, bool margins);

  std::vector<std::uint32_t> start_; // CSR offsets, size n+1
  std::vector<std::uint32_t> entry_; // neighbour index * 32 + periodic image code
  std::vector<double> x_, h_;        // positions and smoothing lengths at the build
  std::vector<char> out_;            // outside the domain at the build (no neighbours)
  // > 0: no unlisted particle within twice the margin; this much to spare (m)
  std::vector<double> clearance_;
  std::vector<double> margin_; // each particle's: a pair is listed within the larger of its two (m)
  std::vector<std::uint8_t> level_; // each particle's level of h (0: the largest)
  std::size_t levels_ = 1;
  double grow_ = 1.0;
  std::size_t builds_ = 0;
  mutable std::vector<double> moved_; // valid()'s displacement bounds (reused)
  std::vector<Work> work_;            // per thread
};

} // namespace craterkit

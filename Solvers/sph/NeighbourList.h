// Neighbour lists for the SPH solver (docs/physics.md §2): a Verlet list built from cell
// lists, one sparse grid per level of h (√2 apart, so a graded target's fine particles do not
// scan cells sized for its coarse ones), with a margin per particle (skin h, more for fast
// ones) for motion and for growth of h, kept over steps until some pair could have come into
// range unlisted. Periodic axes are handled by storing, with each neighbour, which image of it
// is near. A pair (a, b) is listed when r_ab < grow max(h_a, h_b) + max(μ_a, μ_b), μ the
// margins. The build gives the same lists, in the same order, for any thread count.
// Between full builds a partial rebuild (refresh, sph/PartialRebuild.cpp) searches again only
// the particles that have moved: each particle keeps its own reference position, h and margin
// (those of its last search), and the pairs are those of a full build over the references.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
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
  // A partial rebuild (sph/PartialRebuild.cpp): the particles that have moved a quarter of
  // their margin since their last search (or whose h has outgrown the allowance) get new
  // references and are searched again against everybody's references; their new pairs are
  // added to both partners' lists (no pair is dropped before the next full build). False,
  // with the lists untouched, where a full build is due (periodic axes, a particle back in
  // the domain, too many movers, references far from their cells or lists grown too much);
  // valid() must be asked again after a true.
  bool refresh(const SphState& s, const SphParams& par, const std::vector<double>& dx,
               const std::vector<double>& dv, double dt);
  // The particles whose lists gained pairs in the last refresh (ascending).
  const std::vector<std::uint32_t>& changed() const { return changed_; }
  const std::vector<std::uint32_t>& start() const { return start_; } // CSR offsets, size n+1
  const std::vector<std::uint32_t>& entry() const { return entry_; } // index * 32 + image code
  std::vector<std::uint32_t> sortedOf(std::size_t a) const;          // a's entries, sorted
  double margin(std::size_t a) const { return margin_[a]; }
  std::size_t builds() const { return builds_; }       // full builds
  std::size_t refreshes() const { return refreshes_; } // partial rebuilds
  // Changes with every build and refresh (for caches that follow the lists).
  std::size_t version() const { return builds_ + refreshes_; }
  // The version at which a's list last changed (a cache of some lists only needs to follow
  // those).
  std::size_t stamp(std::size_t a) const { return stamp_[a]; }

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
  double marginOf(const SphState& s, const SphParams& par, const std::vector<double>& dx, double dt,
                  std::size_t i) const;
  // sph/PartialRebuild.cpp: a's partners at the references over all levels (into `found`),
  // its clearance, and the clearances a's new reference lowers (into `lowered`).
  struct Lowered {
    std::uint32_t to;
    double clearance;
  };
  double searchFresh(const Grids& g, std::size_t a, const std::vector<double>& levelC,
                     const std::vector<char>& fresh, std::vector<std::uint32_t>& found,
                     std::vector<Lowered>& lowered) const;
  void addPairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs);
  bool pickMovers(const SphState& s, const SphParams& par, const std::vector<double>& dx,
                  const std::vector<double>& dv, double dt, std::vector<char>& fresh,
                  std::vector<std::uint32_t>& movers);
  double clearanceOf(const Grids& g, const SphState& s, const SphParams& par, std::size_t a,
                     double far) const;
  void listAll(const Grids& g, const SphState& s, const SphParams& par, double reach, bool margins);

  std::vector<std::uint32_t> start_; // CSR offsets, size n+1
  std::vector<std::uint32_t> entry_; // neighbour index * 32 + periodic image code
  std::vector<double> x_, h_; // references: position and h at the last search (build or refresh)
  std::vector<char> out_;     // outside the domain at the build (no neighbours)
  // > 0: no unlisted particle within twice the margin; this much to spare (m)
  std::vector<double> clearance_;
  std::vector<double> margin_; // each particle's: a pair is listed within the larger of its two (m)
  std::vector<std::uint8_t> level_; // each particle's level of h (0: the largest)
  std::size_t levels_ = 1;
  double grow_ = 1.0;
  std::size_t builds_ = 0, refreshes_ = 0;
  std::vector<std::uint32_t> changed_;
  std::vector<std::size_t> stamp_;
  // Kept from the last full build once refresh() is used: the grids (their entries updated to
  // the references of the particles searched since, each still in the cell of its position at
  // the build), each particle's entry in them, those positions and, per level, how far a
  // reference has moved from its cell's position since (searches reach that much further).
  std::shared_ptr<Grids> grids_;
  std::vector<std::uint32_t> slot_;
  std::vector<double> gridX_, slack_;
  std::vector<char> loose_; // references far from their cells, in looseList_ instead
  std::vector<std::uint32_t> looseList_;
  std::size_t builtEntries_ = 0; // entries at the last full build
  bool keepGrids_ = false;
  void keepGrids(std::shared_ptr<Grids> g);
  void moveReferences(const std::vector<std::uint32_t>& movers);
  mutable std::vector<double> moved_; // valid()'s displacement bounds (reused)
  std::vector<Work> work_;            // per thread
};

} // namespace craterkit

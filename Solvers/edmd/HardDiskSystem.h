// Event-driven molecular dynamics of hard disks in 2D (docs/physics.md §6).
//
// Disks fly ballistically between events (straight lines, or parabolas under uniform
// gravity along -y) and are advanced lazily: each disk keeps the time of its last update.
// Events are pair collisions, wall collisions, crossings of a uniform cell grid and the
// caller's stops (frames). Each disk keeps only its next event, chosen among its partners in
// the 3x3 cells around it, and the future-event list is a bounded priority queue
// (EventQueue.h: O(1) scheduling, exact order). An event with a partner records the
// partner's collision counter; if the partner has collided since, the event is stale and the
// disk is simply predicted again (Rapaport's scheme; no search, no deletion).
//
// Disks much larger than the cell size (a single impactor disk) are "big": they scan the
// ring of cells within their reach, and every small disk also checks every big disk.
//
// Mass: a disk is a cylinder of unit thickness, m = ρ π r² (kg per metre of thickness), so
// the density ratio of impactor and ground sets their mass ratio as in the seed's model.
//
// Optional radius growth (Lubachevsky–Stillinger compression) makes every radius grow as
// r_i(t) = r_i(0) (1 + γ t); collisions then separate the pair at least at the growth rate.
#pragma once

#include "common/Progress.h"
#include "edmd/EventQueue.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct HardDisks {
  std::vector<double> x, y, vx, vy, radius, mass;
  std::vector<int> material;
  std::vector<std::int64_t> id;
  std::size_t size() const { return radius.size(); }
  void add(double px, double py, double pvx, double pvy, double r, double m, int mat,
           std::int64_t ident);
};

struct HardDiskParams {
  double width = 1.0, height = 1.0; // box [0, width] x [0, height], m
  bool periodicX = false, periodicY = false;
  double restitution = 1.0;     // disk-disk normal restitution
  double wallRestitution = 1.0; // disk-wall
  double gravity = 0.0;         // m/s², along -y
  // TC model against inelastic collapse (Luding & McNamara 1998): a collision of a disk whose
  // previous collision was less than tcTime ago is elastic. 0 disables it.
  double tcTime = 0.0;
  double growthRate = 0.0; // γ, 1/s (compression only; needs gravity = 0)
  double growthEnd = 0.0;  // s, the time growth stops being allowed (sizes the cells)
  void validate() const;
};

enum class EventType : std::uint8_t { None, Pair, Wall, Cell };

// One processed event, for tests and analysis.
struct EventRecord {
  double time;
  EventType type;
  std::uint32_t i, partner; // partner: disk, wall (0 -x, 1 +x, 2 -y, 3 +y) or direction
};

// First upward crossing of the original surface by a ground disk (exact, on its trajectory).
struct SurfaceCrossing {
  std::uint32_t disk;
  double time, x, vx, vy;
};

class HardDiskSystem {
public:
  HardDiskSystem(const HardDisks& disks, const HardDiskParams& params);

  // Processes every event before t, then brings all disks to time t exactly.
  void advanceTo(double t, const ProgressCallback& progress = {});
  // Processes exactly n events (of any kind, stale ones excluded); returns the new time.
  double processEvents(std::uint64_t n);

  double time() const { return time_; }
  // Disks at the current time (after advanceTo every disk is current).
  const HardDisks& disks() const;
  const HardDiskParams& params() const { return p_; }
  double radiusAt(std::size_t i) const { return d_.radius[i] * growth(time_); }

  std::uint64_t pairCollisions() const { return pairCollisions_; }
  std::uint64_t wallCollisions() const { return wallCollisions_; }
  std::uint64_t cellCrossings() const { return cellCrossings_; }
  std::uint64_t staleEvents() const { return stale_; }
  // Σ σ_ij J_ij over pair collisions: P A = N k T + virial / (2 t) in 2D.
  double virialSum() const { return virial_; }
  double kineticEnergy() const;
  void momentum(double& px, double& py) const;
  // Smallest centre distance minus contact distance over all pairs (brute force, for tests).
  double smallestGap() const;
  // The same through the cell grid (every pair that can touch), O(N).
  double smallestGapNearby() const;

  // Debug check (tests): after every event, the disks involved must not overlap any
  // neighbour by more than 1e-9 of the contact distance; throws std::logic_error otherwise.
  void checkOverlaps(bool on) { checkOverlaps_ = on; }

  // Optional records (off by default).
  void recordEvents(std::vector<EventRecord>* log) { log_ = log; }
  void watchSurface(double level, int groundMaterial);
  const std::vector<SurfaceCrossing>& surfaceCrossings() const { return crossings_; }
  // Disks touched (directly or through a chain of collisions) by a disk of this material.
  void trackDisturbance(int sourceMaterial);
  const std::vector<char>& disturbed() const { return disturbed_; }
  // Scales velocities (e.g. to hold the temperature during compression); keeps the events
  // consistent by predicting everything again.
  void scaleVelocities(double factor);

private:
  struct Event {
    double t;
    std::uint32_t partner;
    EventType type;
    std::uint32_t partnerCount;
  };
  double growth(double t) const { return 1.0 + p_.growthRate * t; }
  void stream(std::size_t i);
  void predict(std::size_t i);
  // The common case (a small disk, the 3x3 cells, no growth), specialised for the box.
  bool fastScan(std::size_t i) const { return gridFast_ && !isBig_[i]; }
  template <bool Grav, bool PX, bool PY>
  void scanList(std::size_t i, std::int32_t k, Event& best) const;
  template <bool Grav, bool PX, bool PY> void scanBlock(std::size_t i, Event& best) const;
  struct Block {
    std::int32_t first[9]; // first disk of each non-empty cell of the 3x3 block
    int cells;
  };
  template <bool PX, bool PY> void gatherBlock(std::size_t i, Block& block) const;
  template <bool Grav, bool PX, bool PY> void predictPair(std::size_t i, std::size_t j);
  void (HardDiskSystem::*predictPair_)(std::size_t, std::size_t) = nullptr;
  void finishPrediction(std::size_t i, Event& best);
  void scheduleNext(std::size_t i, Event& best);
  template <bool Grav, bool PX, bool PY>
  void scanLists(std::size_t i, const std::int32_t* first, int cells, Event& best) const;
  template <bool Grav, bool PX, bool PY>
  void scanEdge(std::size_t i, std::uint32_t direction, Event& best) const;
  void chooseScans();
  void (HardDiskSystem::*scanBlock_)(std::size_t, Event&) const = nullptr;
  void (HardDiskSystem::*scanEdge_)(std::size_t, std::uint32_t, Event&) const = nullptr;
  bool gridFast_ = false;
  void predictAfterCrossing(std::size_t i, std::uint32_t direction);
  void consider(std::size_t i, std::size_t j, Event& best) const;
  void wallEvent(std::size_t i, Event& best) const;
  void cellEvent(std::size_t i, Event& best) const;
  void collide(std::size_t i, std::size_t j);
  void hitWall(std::size_t i, std::uint32_t wall);
  void crossCell(std::size_t i, std::uint32_t direction);
  bool step(double limit); // one event before limit; false if none
  void verify(std::size_t i) const;
  double gapNow(std::size_t i, std::size_t j) const; // distance minus contact distance, now
  template <class F> void forNearby(std::size_t i, F&& f) const; // disks in i's cells
  bool checkOverlaps_ = false;
  void insertInCell(std::size_t i, std::size_t cx, std::size_t cy);
  void removeFromCell(std::size_t i);
  void schedule(std::size_t i, const Event& e) { queue_.update(i, e); }
  void predictAll();
  void setUpGrid(double rmin, double rmax); // sizes the cells and lists the disks

  // What the event loop touches for a disk, in one cache line.
  struct Hot {
    double x, y, vx, vy;
    double t; // time of the last update
    double r, m;
    std::uint32_t count; // collisions so far (events record the partner's)
    std::int32_t next;   // next disk in the same cell, -1 at the end
  };
  std::vector<Hot> h_;
  mutable HardDisks d_; // ids and materials; positions and velocities copied out by disks()
  HardDiskParams p_;
  double time_ = 0.0;
  std::vector<double> lastCollision_; // for the TC model
  std::vector<Event> pairBest_;       // best pair event of each disk's last scan
  EventQueue<Event> queue_;           // the future-event list: each disk's next event
  // Cell grid with intrusive doubly linked lists.
  std::size_t nx_ = 1, ny_ = 1;
  double cellW_ = 1.0, cellH_ = 1.0;
  std::vector<std::int32_t> head_, prevInCell_;
  struct CellXY {
    std::uint32_t x, y;
  };
  std::vector<CellXY> cellOf_;
  std::vector<std::uint32_t> bigs_;
  std::vector<char> isBig_;
  std::vector<int> reach_; // rings of cells a disk scans (1 for small disks)
  double smallMax_ = 0.0;  // largest small radius (at the end of growth for compression)
  std::uint64_t pairCollisions_ = 0, wallCollisions_ = 0, cellCrossings_ = 0, stale_ = 0;
  double virial_ = 0.0;
  std::vector<EventRecord>* log_ = nullptr;
  bool watchSurface_ = false;
  double surface_ = 0.0;
  int groundMaterial_ = 0;
  std::vector<char> crossed_;
  std::vector<SurfaceCrossing> crossings_;
  int sourceMaterial_ = -1;
  std::vector<char> disturbed_;
};

} // namespace craterkit

// Soft-sphere DEM integrator (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012).
//
// Kick-drift-kick leapfrog with constant Δt (Schwartz 2012 Eq. 1; docs/physics.md §1.5):
// velocity-dependent forces use predicted velocities and spins v + Δt/2 a. Contacts come
// from a half Verlet list (pairs i < j within r_i + r_j + skin) built with a cell list and
// rebuilt only when a particle has moved more than half the skin; contact histories are
// carried across rebuilds by merging the sorted pair lists.
//
// Forces are computed in passes so that OpenMP never needs atomics: the pairs in contact are
// found and written to a compact table (dem/ContactTable.h), the contact law runs over the
// table's rows, then each particle sums its pairs in contact in index order
// (reading only the contact flags of the others) and its walls. A step is one parallel region,
// two when the list is rebuilt. Each thread takes one range of particles, and the pairs whose
// first member is in it: contact search; the rows' fill, after the threads before it have
// counted theirs; contact law; the gather of the particles no earlier thread's contact has,
// then, after the threads before it have evaluated theirs (they read these particles, which the
// gather drifts), of the others. No barrier inside the step: a thread waits for the threads
// before it only (common/ThreadChain.h). The ranges follow the threads'
// measured times (dem/WorkShares.h); which thread does an item never changes its arithmetic.
// A new run first orders the particles along a Morton curve of their cells, so that
// neighbours sit close in memory (the output keeps each particle's Id, not its input
// position). The result is bit-identical for any thread count, and a run resumed from a checkpoint
// continues bit-identically (the restored run rebuilds its list; pairs out of contact
// contribute nothing and the sums keep their order).
#pragma once

#include "common/Gravity.h"
#include "common/ParticleSet.h"
#include "common/Progress.h"
#include "common/ThreadChain.h"
#include "dem/ContactModels.h"
#include "dem/ContactTable.h"
#include "dem/PairList.h"
#include "dem/ParticleContacts.h"
#include "dem/Walls.h"
#include "dem/WorkShares.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace craterkit {

// "particle i (Id n)", for messages that name a particle (dem/DemInput.cpp).
std::string describeParticle(const ParticleSet& s, std::size_t i);

struct DemParams {
  ContactParams contact;
  std::vector<Wall> walls;
  Gravity gravity;
  double dt = 0.0;                    // s
  double skin = -1.0;                 // Verlet skin, m; < 0 means 0.2 x smallest radius
  double overlapWarning = 0.01;       // warn above this overlap / smaller radius
  double overlapAbort = 0.5;          // stop the run above this (pkdgrav's limit)
  double initialOverlapLimit = 0.05;  // refuse inputs overlapping more than this
  double minStepsPerCollision = 10.0; // refuse Δt above τ / this (unstable)
  double warnStepsPerCollision = 20.0;
  void validate() const;
};

struct DemDiagnostics {
  double time = 0.0;
  long long step = 0;
  double kineticEnergy = 0.0;       // translational, J
  double rotationalEnergy = 0.0;    // J
  double elasticEnergy = 0.0;       // springs of all active contacts, J
  double gravitationalEnergy = 0.0; // J
  double totalEnergy() const {
    return kineticEnergy + rotationalEnergy + elasticEnergy + gravitationalEnergy;
  }
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularMomentum = Eigen::Vector3d::Zero(); // about the origin, incl. spins
  double maxOverlap = 0.0;                                   // largest overlap / smaller radius
  std::size_t contacts = 0;                                  // particle-particle
  std::size_t wallContacts = 0;
  double maxSpeed = 0.0;
};

class DemSolver {
public:
  DemSolver(const ParticleSet& particles, const DemParams& params);

  void step();
  // `steps` steps; the same bits as calling step() that often, faster (the drift of each step
  // but the first is fused into the previous step's force gather).
  void advanceSteps(long long steps);
  // Steps until time() >= endTime - dt/2. If checkpointPath is set, writes a checkpoint
  // every checkpointEvery steps (atomically: a failed or aborted run keeps the last one).
  long long advanceTo(double endTime, const ProgressCallback& progress = {},
                      const std::string& checkpointPath = {}, long long checkpointEvery = 0);

  // Changes gravity from the next step on (the bed settling lowers it while it runs).
  void setGravity(const Gravity& gravity);

  double time() const { return time_; }
  long long stepCount() const { return step_; }
  const ParticleSet& particles() const { return state_; }
  const DemParams& params() const { return params_; }
  DemDiagnostics diagnostics() const;
  double collisionTime() const { return collisionTime_; }
  std::size_t neighbourBuilds() const { return builds_; }
  std::size_t overlapWarnings() const { return overlapWarningSteps_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Particle index pairs (i < j) in contact now, and (particle, wall) contacts.
  std::vector<std::pair<std::size_t, std::size_t>> contactPairs() const;

  // Removes the particles flagged non-zero (e.g. ejecta that left the domain), keeping the
  // order and the contact histories of the others. Returns how many were removed.
  std::size_t removeParticles(const std::vector<char>& remove);

  // Checkpoints (format and checks in dem/DemCheckpoint.h and common/CheckpointFormat.h, code
  // in DemCheckpoint.cpp). The file is written through writeFileAtomically: a failed or
  // aborted write keeps the last one. A damaged file throws InputError ("the checkpoint is
  // corrupt (checksum mismatch)"; with the path from the path overload); an old one without a
  // checksum reads with a warning in warnings().
  void writeCheckpoint(std::ostream& out) const;
  void writeCheckpoint(const std::string& path) const;
  static DemSolver readCheckpoint(std::istream& in, std::uint64_t available);
  static DemSolver readCheckpoint(const std::string& path);
  // The same checkpoint as bytes in memory, exactly sized (DemRun's snapshots), and back.
  std::string checkpointBytes() const;
  static DemSolver fromCheckpointBytes(const std::string& bytes);

private:
  struct Restore {};
  // The checkpoint's payload (dem/DemCheckpoint.h), and the reader of a framed checkpoint
  // whose warnings name SOURCE (the file, or empty).
  void writeCheckpointPayload(std::ostream& out) const;
  static DemSolver readCheckpoint(std::istream& in, std::uint64_t framed,
                                  const std::string& source);
  DemSolver(Restore, const ParticleSet& particles, const DemParams& params);
  void initialise(bool computeInitialForces);
  void checkInput() const;
  void sortSpatially();
  void buildNeighbourList();
  // One step; with openNext, also the next step's opening half-kick and drift (the state
  // between the two steps is then never formed: only for steps nothing observes in between).
  void advance(bool openNext);
  // computeForces opens a parallel region; the others run on every thread of one, after
  // prepareForces (serial), and the caller swaps tables_ after the region.
  void computeForces(double kick, bool openNext = false);
  void prepareForces();
  void drift();
  void forcePhases(double kick, bool openNext);
  // Finds the pairs in contact whose first member is in [lo, hi) and writes them as rows
  // [*rowBegin, *rowEnd).
  double collectContacts(std::size_t lo, std::size_t hi, std::size_t* rowBegin,
                         std::size_t* rowEnd);
  template <class Law>
  void forcePhasesWith(const Law& pairLaw, const Law& wallLaw, double kick, bool openNext);
  template <class Law> void gatherForces(const Law& wallLaw, const FrictionConstants& fc,
                                         double kick, bool openNext, double worst, std::size_t lo,
                                         std::size_t hi, const std::uint64_t* shared,
                                         bool sharedOnes);
  // The end of particle i's gather: accelerations a, b; closing half-kick; with openNext the
  // next step's opening half-kick, drift and predicted velocities. Returns the squared
  // displacement since the last build (openNext) or 0.
  double finishParticle(std::size_t i, const double* a, const double* b, double kick,
                        bool openNext);
  // Particle i's opening half-kick (accelerations a, b), drift and predicted velocities; its
  // squared displacement since the last build. Shared by drift() and the fused step.
  double driftParticle(std::size_t i, const double* a, const double* b);
  template <class Law> double elasticEnergyWith(const Law& pairLaw, const Law& wallLaw) const;
  void warn(const std::string& message);

  ParticleSet state_;
  DemParams params_;
  std::size_t n_ = 0;
  double time_ = 0.0;
  long long step_ = 0;
  double skin_ = 0.0, rmax_ = 0.0, collisionTime_ = 0.0;
  double dampingFactorN_ = 0.0; // of the clipped normal law (clippedDampingFactor)
  std::vector<double> inertia_, acc_, alpha_, vPred_, wPred_, refPos_;

  PairList pairs_;         // half Verlet list: particles, contact flags, table rows
  ContactTable tables_[2]; // the contacts of the last force evaluation, and the next
  int current_ = 0;        // tables_[current_] is the last evaluation's
  // The next table's results (ContactTable::kResultWords a row), read in the step that writes
  // them: one array for both tables.
  FreshVector<double> contactResults_;
  WallContacts wallContacts_;
  std::vector<std::uint64_t> wallNear_; // per particle: walls within r + skin at the last build
  ParticleContacts contactsOf_;         // each particle's rows of the new table
  // Per thread: the pairs it found in contact, and how many (kPad apart: one cache line each).
  std::vector<FreshVector<std::uint32_t>> touching_;
  std::vector<std::size_t> touchingCount_;
  static constexpr std::size_t kPad = 8;
  // Each thread's range of the particles (drift, and the contact search, law, index and force
  // sum of the pairs whose first member is in it), adjusted to the threads' measured times
  // (dem/WorkShares.h); a force evaluation's threads wait only for the threads before them
  // (common/ThreadChain.h), at the stages chainStage_ + 1 (counted), + 2 (rows written) and
  // + 3 (evaluated). shared_[j] == chainStage_: an earlier thread's row has j as second member.
  WorkShares particleShares_;
  ThreadChain chain_;
  std::uint64_t chainStage_ = 0;
  std::vector<std::uint64_t> shared_;
  double moved_ = 0.0; // largest squared displacement since the last build
  // The gather of the last step drifted the particles already (state_ holds the next step's
  // positions and half-step velocities; only ever true inside advanceSteps and advanceTo),
  // and movedNext_ is moved_ after that drift.
  bool drifted_ = false;
  double movedNext_ = 0.0;

  double worstOverlap_ = 0.0;
  std::size_t worstParticle_ = 0;
  std::size_t builds_ = 0;
  std::size_t overlapWarningSteps_ = 0;
  std::vector<std::string> warnings_;
};

} // namespace craterkit

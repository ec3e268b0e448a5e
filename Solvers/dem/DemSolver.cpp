#include "dem/DemSolver.h"

#include "common/Error.h"
#include "common/OpenMP.h"
#include "dem/Accelerations.h"
#include "dem/TouchingPairs.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace craterkit {

namespace {

using Vec = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

inline Vec at(const std::vector<double>& a, std::size_t i) {
  return Vec(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}

inline double seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

} // namespace

// ---------------------------------------------------------------------------------------------
DemSolver::DemSolver(const ParticleSet& particles, const DemParams& params)
    : state_(particles), params_(params) {
  initialise(true);
}

DemSolver::DemSolver(Restore, const ParticleSet& particles, const DemParams& params)
    : state_(particles), params_(params) {
  initialise(false);
}

void DemSolver::setGravity(const Gravity& gravity) {
  gravity.validate();
  params_.gravity = gravity;
}

void DemSolver::warn(const std::string& message) {
  if (warnings_.size() < 100)
    warnings_.push_back(message);
}

void DemSolver::initialise(bool computeInitialForces) {
  n_ = state_.size();
  params_.validate();
  checkInput();
  const ParticleSet& s = state_;
  const double rmin = *std::min_element(s.radius.begin(), s.radius.end());
  rmax_ = *std::max_element(s.radius.begin(), s.radius.end());
  skin_ = params_.skin < 0.0 ? 0.2 * rmin : params_.skin;
  if (computeInitialForces)
    sortSpatially(); // a restored run keeps its saved order
  inertia_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i)
    inertia_[i] = 0.4 * s.mass[i] * s.radius[i] * s.radius[i];
  acc_.assign(3 * n_, 0.0);
  alpha_.assign(3 * n_, 0.0);
  vPred_ = s.velocity;
  wPred_ = s.angularVelocity;
  tables_[0].resize(0);
  tables_[1].resize(0);
  current_ = 0;
  dampingFactorN_ = clippedDampingFactor(params_.contact.normalModel == "Hertz"
                                             ? NormalLawKind::Hertz
                                             : NormalLawKind::LinearSpringDashpot,
                                         params_.contact.restitutionN);

  // Stability: the shortest contact is the lightest pair (reduced mass m/2).
  const double mmin = *std::min_element(s.mass.begin(), s.mass.end());
  if (params_.contact.normalModel == "Hertz") {
    const double E =
        params_.contact.youngsModulus / (1.0 - std::pow(params_.contact.poissonRatio, 2));
    collisionTime_ = hertzStabilityTime(mmin, rmin, E);
  } else {
    collisionTime_ = pairCollisionTime(mmin, params_.contact.kN);
  }
  const double steps = collisionTime_ / params_.dt;
  if (steps < params_.minStepsPerCollision) {
    std::ostringstream msg;
    msg << "TimeStep " << params_.dt
        << " s is above the stability limit: the shortest contact lasts " << collisionTime_
        << " s, only " << steps << " steps; use at most " << collisionTime_ / 30.0
        << " s (30 steps per contact)";
    throw InputError(msg.str());
  }
  if (steps < params_.warnStepsPerCollision) {
    std::ostringstream msg;
    msg << "only " << steps << " steps per contact (TimeStep " << params_.dt
        << " s): pkdgrav recommends 30-50";
    warn(msg.str());
  }

  buildNeighbourList();
  // Refuse inputs that start deeply overlapped: the spring would launch them.
  std::size_t deep = 0;
  double worst = 0.0;
  std::size_t wi = 0, wj = 0;
  for (std::size_t k2 = 0; k2 < pairs_.size(); ++k2) {
    const std::size_t i = pairs_.first[k2], j = pairs_.second[k2];
    const Vec d = at(s.position, j) - at(s.position, i);
    const double f = (s.radius[i] + s.radius[j] - d.norm()) / std::min(s.radius[i], s.radius[j]);
    if (f > params_.initialOverlapLimit)
      ++deep;
    if (f > worst) {
      worst = f;
      wi = i;
      wj = j;
    }
  }
  if (deep > 0 && computeInitialForces) {
    std::ostringstream msg;
    msg << deep << " particle pairs overlap by more than " << 100 * params_.initialOverlapLimit
        << " % of the smaller radius (worst " << 100 * worst << " %, " << describeParticle(s, wi)
        << " and " << describeParticle(s, wj) << "): settle or space the input first";
    throw InputError(msg.str());
  }
  if (computeInitialForces) {
    computeForces(0.0);
    if (worstOverlap_ > params_.overlapWarning) {
      std::ostringstream msg;
      msg << "initial overlaps up to " << 100 * worstOverlap_ << " % of a radius (walls included)";
      warn(msg.str());
    }
  }
}

// ---------------------------------------------------------------------------------------------
void DemSolver::sortSpatially() {
  ParticleSet& s = state_;
  double lo[3] = {kInf, kInf, kInf};
  for (std::size_t i = 0; i < n_; ++i)
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], s.position[3 * i + k]);
  const double cell = 2.0 * rmax_;
  auto spread = [](std::uint64_t v) { // 21 bits -> every third bit
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> key(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double c = std::min((s.position[3 * i + k] - lo[k]) / cell, 2097151.0);
      code |= spread(static_cast<std::uint64_t>(c)) << k;
    }
    key[i] = {code, i};
  }
  std::sort(key.begin(), key.end()); // ties broken by the original index: deterministic
  auto permute = [&](auto& v, std::size_t width) {
    auto copy = v;
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t k = 0; k < width; ++k)
        v[i * width + k] = copy[key[i].second * width + k];
  };
  s.forEachArray(permute);
}

// ---------------------------------------------------------------------------------------------
void DemSolver::computeForces(double kick, bool openNext) {
  prepareForces();
#pragma omp parallel if (n_ >= kDemParallelMin)
  forcePhases(kick, openNext);
  current_ = 1 - current_;
  particleShares_.update();
}

// Before a parallel region that evaluates forces, so that the region needs no `single` for
// it: room for the per-thread results of as many threads as the region can have, for the
// per-particle index, and for the next table's rows: one for every listed pair, so that no
// step has to grow it in the region (the rows' pages stay untouched until a thread writes
// them, dem/ContactTable.h).
void DemSolver::prepareForces() {
#ifdef _OPENMP
  const std::size_t most = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
#else
  const std::size_t most = 1;
#endif
  if (touching_.size() < most)
    touching_.resize(most);
  touchingCount_.assign(kPad * most, 0);
  particleShares_.resize(most);
  chain_.resize(most);
  chainStage_ += 3;
  shared_.resize(n_);
  contactsOf_.resize(n_, pairs_.size());
  tables_[1 - current_].reserveRows(pairs_.size());
  growFresh(contactResults_, ContactTable::kResultWords * pairs_.size());
  worstOverlap_ = 0.0;
  movedNext_ = 0.0;
}

void DemSolver::forcePhases(double kick, bool openNext) {
  const ContactParams& c = params_.contact;
  if (c.normalModel == "Hertz") {
    const double E = c.youngsModulus / (1.0 - c.poissonRatio * c.poissonRatio);
    forcePhasesWith(Hertz{0.5 * E, dampingFactorN_, c.poissonRatio},
                    Hertz{E, dampingFactorN_, c.poissonRatio}, kick, openNext);
  } else {
    const LinearSpringDashpot law{c.kN, dampingFactorN_};
    forcePhasesWith(law, law, kick, openNext);
  }
}

// The pairs in contact now, in the order of the list, become the rows of the next table:
// each thread tests the pairs whose first member is in its range [lo, hi) of particles, a block
// of the list (dem/TouchingPairs.h), then writes its rows after those of the threads before it
// once these have counted theirs, marking the second members beyond its range as shared.
// Returns the seconds this thread worked (its wait left out).
double DemSolver::collectContacts(std::size_t lo, std::size_t hi, std::size_t* rowBegin,
                                  std::size_t* rowEnd) {
  const double start = seconds();
  const std::size_t t = static_cast<std::size_t>(threadCount()),
                    me = static_cast<std::size_t>(threadNumber());
  const ContactTable& before = tables_[current_];
  ContactTable& now = tables_[1 - current_];
  const double* x = state_.position.data();
  const double* r = state_.radius.data();
  const std::uint32_t* first = pairs_.first.data();
  const std::uint32_t* second = pairs_.second.data();
  char* active = pairs_.active.data();
  FreshVector<std::uint32_t>& mine = touching_[me];
  const std::size_t begin = pairs_.firstStart[lo], end = pairs_.firstStart[hi];
  mine.resize(end - begin + 1);
  const std::size_t found = findTouchingPairs(x, r, first, second, active, begin, end, mine.data());
  touchingCount_[kPad * me] = found;
  chain_.post(me, chainStage_ + 1);
  const double searched = seconds() - start;
  chain_.waitForEarlier(me, chainStage_ + 1);
  std::size_t c = 0;
  for (std::size_t q = 0; q < me; ++q)
    c += touchingCount_[kPad * q];
  if (me + 1 == t) // the last thread knows the total (the rows fit: one per listed pair)
    now.setRows(c + found);
  *rowBegin = c;
  *rowEnd = c + found;
  const double filling = seconds();
  std::uint32_t* row = pairs_.row.data();
  for (std::size_t q = 0; q < found; ++q) {
    const std::uint32_t k = mine[q];
    now.first[c] = first[k];
    now.second[c] = second[k];
    now.from[c] = active[k] ? row[k] : static_cast<std::uint32_t>(before.rows);
    active[k] = 1;
    row[k] = static_cast<std::uint32_t>(c++);
    if (second[k] >= hi) // a later thread's particle (two threads may mark the same one)
      __atomic_store_n(&shared_[second[k]], chainStage_, __ATOMIC_RELAXED);
  }
  chain_.post(me, chainStage_ + 2);
  return searched + (seconds() - filling);
}

// Forces and torques at the current positions; with kick > 0 the closing half-kick of the
// step (v += kick a) is applied in the gather, while the accelerations are in registers.
// Each thread evaluates the rows it wrote, then indexes and sums the particles of its range:
// first those that are the second member of none of the earlier threads' rows (all their rows
// are its own, and no other thread reads them any more), then, once the threads before it have
// evaluated theirs, the shared ones (their rows hold these particles' contacts, and their law
// reads these particles, which the gather drifts). The threads after it read nothing it
// writes (their pairs' members all come after its range). The shares follow the times worked,
// the waits left out (with the waits counted, the first thread took more pairs until the
// others waited longer for it: 2026-12-05, benchmarks/JOURNAL.md).
template <class Law> void DemSolver::forcePhasesWith(const Law& pairLaw, const Law& wallLaw,
                                                     double kick, bool openNext) {
  const std::size_t threads = static_cast<std::size_t>(threadCount());
  const std::size_t me = static_cast<std::size_t>(threadNumber());
  const std::size_t lo = particleShares_.begin(n_, me, threads),
                    hi = particleShares_.begin(n_, me + 1, threads);
  std::size_t rowBegin = 0, rowEnd = 0;
  const double collected = collectContacts(lo, hi, &rowBegin, &rowEnd);
  const double evaluating = seconds();
  const FrictionConstants fc(params_.contact);
  const ContactInputs in{state_.position.data(), state_.radius.data(), state_.mass.data(),
                         vPred_.data(), wPred_.data()};
  const double worst =
      evaluateContacts(pairLaw, fc, params_.dt, in, tables_[current_], tables_[1 - current_],
                       contactResults_.data(), rowBegin, rowEnd);
  chain_.post(me, chainStage_ + 3);
  const double evaluated = seconds() - evaluating;
  const ContactTable& now = tables_[1 - current_];
  chain_.waitForEarlier(me, chainStage_ + 2); // their marks are written
  const double own = seconds();
  // The first thread has no earlier one: none of its particles is shared (one pass, no marks).
  const std::uint64_t* marks = me == 0 ? nullptr : shared_.data();
  contactsOf_.indexOwnRows(now, pairs_.secondStart, lo, hi, rowBegin, rowEnd, marks, chainStage_);
  gatherForces(wallLaw, fc, kick, openNext, worst, lo, hi, marks, false);
  const double gathered = seconds() - own;
  chain_.waitForEarlier(me, chainStage_ + 3);
  const double start = seconds();
  if (me > 0) {
    contactsOf_.indexSharedRows(now, pairs_.secondStart, lo, hi, rowEnd, marks, chainStage_);
    gatherForces(wallLaw, fc, kick, openNext, 0.0, lo, hi, marks, true);
  }
  particleShares_.record(me, threads, collected + evaluated + gathered + (seconds() - start));
}

// Each particle sums its pairs in contact in index order, then its walls in wall order: the
// particles of [lo, hi) that are shared (shared[i] == chainStage_) or those that are not, or
// all of them if `shared` is null.
template <class Law> void DemSolver::gatherForces(const Law& wallLaw, const FrictionConstants& fc,
                                                  double kick, bool openNext, double worst,
                                                  std::size_t lo, std::size_t hi,
                                                  const std::uint64_t* shared, bool sharedOnes) {
  const ContactParams& cp = params_.contact;
  const double dt = params_.dt;
  const ParticleSet& s = state_;
  const double* x = s.position.data();
  const double* r = s.radius.data();
  const double* m = s.mass.data();
  const double* res = contactResults_.data();
  constexpr std::size_t R = ContactTable::kResultWords;
  const ParticleContacts& pc = contactsOf_;
  WallContacts& wc = wallContacts_;
  const Gravity& gravity = params_.gravity;
  const bool uniform = gravity.type == Gravity::Type::Uniform;
  double moved = 0.0;
  // The particles [lo, hi) of this thread, indexed by it (and drifted by it in the last step,
  // their data in its cache).
  for (std::size_t i = lo; i < hi; ++i) {
    if (shared != nullptr && (shared[i] == chainStage_) != sharedOnes)
      continue;
    Vec f = Vec::Zero(), t = Vec::Zero();
    // Only the pairs in contact, in the order of the pair list (dem/ParticleContacts.h).
    for (std::size_t c = pc.firstBegin[i], e = c + pc.firstCount[i]; c < e; ++c) {
      f += Vec(res[R * c], res[R * c + 1], res[R * c + 2]);
      t += Vec(res[R * c + 3], res[R * c + 4], res[R * c + 5]);
    }
    for (std::size_t q = pairs_.secondStart[i], e = q + pc.secondCount[i]; q < e; ++q) {
      const std::size_t c = pc.secondRow[q];
      f -= Vec(res[R * c], res[R * c + 1], res[R * c + 2]);
      t += Vec(res[R * c + 6], res[R * c + 7], res[R * c + 8]);
    }
    for (std::size_t e = wc.start[i]; e < wc.start[i + 1]; ++e) {
      double nv[3], lever;
      const double overlap = params_.walls[wc.wall[e]].overlap(&x[3 * i], r[i], nv, lever);
      ContactHistory& h = wc.history[e];
      if (!(overlap > 0.0)) {
        if (wc.active[e]) {
          wc.active[e] = 0;
          h.clear();
        }
        continue;
      }
      ContactState st;
      st.n = Vec(nv[0], nv[1], nv[2]);
      st.overlap = overlap;
      st.leverP = lever;
      st.leverN = kInf;
      const Vec wi = at(wPred_, i);
      st.u = -at(vPred_, i) + st.leverP * st.n.cross(wi);
      st.omegaRel = -wi;
      st.omegaSum = wi;
      st.reducedMass = m[i];
      st.reducedRadius = r[i];
      const ContactResult out = ssdemContact(wallLaw, cp, fc, st, h, dt);
      f += out.force;
      t += out.torqueP;
      wc.active[e] = 1;
      worst = std::max(worst, overlap / r[i]);
    }
    double g[3] = {gravity.vector[0], gravity.vector[1], gravity.vector[2]}, a[3], b[3];
    if (!uniform) // the common case needs no call
      gravity.acceleration(&x[3 * i], g);
    sphereAccelerations(f.data(), t.data(), m[i], inertia_[i], g, a, b);
    moved = std::max(moved, finishParticle(i, a, b, kick, openNext));
  }
#pragma omp critical(ck_dem_worst)
  {
    worstOverlap_ = std::max(worstOverlap_, worst);
    movedNext_ = std::max(movedNext_, moved);
  }
  // The end of the parallel region is the barrier; its caller then swaps the tables.
}

// Particle i's opening half-kick with accelerations a (linear) and b (angular), its drift and
// its predicted velocities for the contact law; returns its squared displacement since the
// last list build. The one place these operations are written, for the drift pass and for the
// fused step alike, so that both give the same bits.
inline double DemSolver::driftParticle(std::size_t i, const double* a, const double* b) {
  const double dt = params_.dt, h = 0.5 * dt;
  double* x = &state_.position[3 * i];
  double* v = &state_.velocity[3 * i];
  double* w = &state_.angularVelocity[3 * i];
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    v[k] += h * a[k];
    w[k] += h * b[k];
    x[k] += dt * v[k];
    const double d = x[k] - refPos_[3 * i + k];
    d2 += d * d;
    vPred_[3 * i + k] = v[k] + h * a[k];
    wPred_[3 * i + k] = w[k] + h * b[k];
  }
  return d2;
}

// Without openNext the accelerations are kept for the next step's drift pass (and the
// checkpoints); with it, that drift happens here, in drift()'s operations and order, and the
// accelerations are not needed again.
inline double DemSolver::finishParticle(std::size_t i, const double* a, const double* b,
                                        double kick, bool openNext) {
  double* v = &state_.velocity[3 * i];
  double* w = &state_.angularVelocity[3 * i];
  if (!openNext) {
    for (int k = 0; k < 3; ++k) {
      acc_[3 * i + k] = a[k];
      alpha_[3 * i + k] = b[k];
      if (kick != 0.0) {
        v[k] += kick * a[k];
        w[k] += kick * b[k];
      }
    }
    return 0.0;
  }
  for (int k = 0; k < 3; ++k) { // this step's closing half-kick
    v[k] += kick * a[k];
    w[k] += kick * b[k];
  }
  return driftParticle(i, a, b);
}

// ---------------------------------------------------------------------------------------------
// The opening half-kick and the drift, on every thread of a parallel region; moved_ gets the
// largest squared displacement since the last build.
void DemSolver::drift() {
  double moved = 0.0;
  const std::size_t threads = static_cast<std::size_t>(threadCount());
  const std::size_t me = static_cast<std::size_t>(threadNumber());
  const std::size_t hi = particleShares_.begin(n_, me + 1, threads);
  for (std::size_t i = particleShares_.begin(n_, me, threads); i < hi; ++i)
    moved = std::max(moved, driftParticle(i, &acc_[3 * i], &alpha_[3 * i]));
#pragma omp critical(ck_dem_moved)
  moved_ = std::max(moved_, moved);
#pragma omp barrier
}

void DemSolver::step() { advance(false); }

void DemSolver::advanceSteps(long long steps) {
  for (long long s = 0; s < steps; ++s)
    advance(s + 1 < steps);
}

void DemSolver::advance(bool openNext) {
  const double dt = params_.dt, h = 0.5 * dt;
  const bool drifted = drifted_;
  drifted_ = false;
  moved_ = drifted ? movedNext_ : 0.0;
  prepareForces();
  // The list holds while no particle has moved more than half the skin since its build.
  const auto listHolds = [this] {
    return std::isfinite(moved_) && std::sqrt(moved_) <= 0.5 * skin_;
  };
#pragma omp parallel if (n_ >= kDemParallelMin)
  {
    if (!drifted)
      drift();
    if (listHolds()) // the same answer on every thread: moved_ is complete after drift()
      forcePhases(h, openNext);
  }
  if (listHolds()) {
    current_ = 1 - current_; // the forces of the region above
    particleShares_.update();
  } else {
    // A non-finite position would poison the cell list: report it here.
    const std::vector<double>& x = state_.position;
    for (std::size_t i = 0; i < n_; ++i)
      for (int k = 0; k < 3; ++k)
        if (!std::isfinite(x[3 * i + k])) {
          std::ostringstream msg;
          msg << "the run blew up at step " << step_ + 1 << " (t = " << time_ + dt
              << " s): " << describeParticle(state_, i)
              << " has a non-finite position; reduce TimeStep";
          throw std::runtime_error(msg.str());
        }
    buildNeighbourList();
    computeForces(h, openNext);
  }
  drifted_ = openNext;
  time_ += dt;
  ++step_;
  if (worstOverlap_ > params_.overlapWarning) {
    if (overlapWarningSteps_ == 0) {
      std::ostringstream msg;
      msg << "overlap of " << 100 * worstOverlap_ << " % of a radius at step " << step_
          << " (limit " << 100 * params_.overlapWarning
          << " %): raise NormalStiffness or lower the speeds";
      warn(msg.str());
    }
    ++overlapWarningSteps_;
  }
  if (worstOverlap_ > params_.overlapAbort || !std::isfinite(worstOverlap_)) {
    // Find the culprit for the message.
    std::size_t culprit = 0;
    double fastest = -1.0;
    for (std::size_t i = 0; i < n_; ++i) {
      const double sp = at(state_.velocity, i).norm();
      if (!(sp <= fastest)) {
        fastest = sp;
        culprit = i;
      }
    }
    std::ostringstream msg;
    msg << "the run blew up at step " << step_ << " (t = " << time_ << " s): overlap of "
        << 100 * worstOverlap_ << " % of a radius (limit " << 100 * params_.overlapAbort
        << " %); fastest is " << describeParticle(state_, culprit) << " at " << fastest
        << " m/s. Raise NormalStiffness or reduce TimeStep";
    throw std::runtime_error(msg.str());
  }
}

long long DemSolver::advanceTo(double endTime, const ProgressCallback& progress,
                               const std::string& checkpointPath, long long checkpointEvery) {
  if (!std::isfinite(endTime))
    throw InputError("the end time must be finite");
  const double start = time_;
  const long long total =
      std::max(0LL, static_cast<long long>(std::llround((endTime - start) / params_.dt)));
  const long long report = std::max(1LL, total / 200);
  const bool checkpoints = !checkpointPath.empty() && checkpointEvery > 0;
  for (long long s = 0; s < total; ++s) {
    if (s % report == 0)
      reportProgress(progress, static_cast<double>(s) / total);
    // The next step may start inside this one unless the state is looked at in between.
    const bool checkpoint = checkpoints && (step_ + 1) % checkpointEvery == 0;
    advance(s + 1 < total && (s + 1) % report != 0 && !checkpoint);
    if (checkpoint)
      writeCheckpoint(checkpointPath);
  }
  reportProgress(progress, 1.0);
  return total;
}

// ---------------------------------------------------------------------------------------------
std::size_t DemSolver::removeParticles(const std::vector<char>& remove) {
  if (remove.size() != n_)
    throw InputError("removeParticles: one flag per particle is needed");
  std::vector<std::uint32_t> newIndex(n_);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n_; ++i)
    newIndex[i] = remove[i] ? ~0u : static_cast<std::uint32_t>(kept++);
  if (kept == n_)
    return 0;
  if (kept == 0)
    throw InputError("removeParticles: cannot remove every particle");
  auto compact = [&](auto& v, std::size_t width) {
    std::size_t o = 0;
    for (std::size_t i = 0; i < n_; ++i)
      if (!remove[i]) {
        for (std::size_t k = 0; k < width; ++k)
          v[o * width + k] = v[i * width + k];
        ++o;
      }
    v.resize(kept * width);
  };
  ParticleSet& s = state_;
  s.forEachArray(compact);
  compact(inertia_, 1);
  compact(acc_, 3);
  compact(alpha_, 3);
  compact(vPred_, 3);
  compact(wPred_, 3);
  // Renumber the contacts and pairs; the map is increasing, so the lists stay sorted.
  std::vector<std::uint32_t> newRow;
  tables_[current_].removeParticles(remove, newIndex, newRow);
  pairs_.removeParticles(remove, newIndex, newRow);
  wallContacts_.removeParticles(remove, newIndex);
  const std::size_t removed = n_ - kept;
  n_ = kept;
  rmax_ = *std::max_element(s.radius.begin(), s.radius.end());
  buildNeighbourList(); // also rebuilds the per-particle pair indices
  return removed;
}

} // namespace craterkit

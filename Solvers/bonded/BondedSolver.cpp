#include "bonded/BondedSolver.h"

#include "bonded/BondedForces.h"

#include "common/CellList.h"
#include "common/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace craterkit {
namespace {

// The kick-drift of the generic passes over particles [i0, i1): the first half kick v += h f and
// the drift x + Δt v into p.xOut, each product and sum rounded on its own (the operations
// driftAvx512 repeats); the velocities after the kick go to `spread`.
void driftGeneric(const bondedpass::DriftPass& p, std::size_t i0, std::size_t i1,
                  bondedpass::VelocitySpread& spread) {
  for (std::size_t i = i0; i < i1; ++i) {
    const double h = p.halfStep / p.m[i];
    for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
      p.v[k] += h * p.f[k];
      p.xOut[k] = p.x[k] + p.dt * p.v[k];
    }
    spread.add(p.v[3 * i], p.v[3 * i + 1], p.v[3 * i + 2]);
  }
}

// Sum of f(i) over [0, n) in chunks of fixed size, chunk sums added in chunk order: the same
// bits for any number of threads.
template <class F> double chunkedSum(std::size_t n, F&& f) {
  constexpr std::size_t kChunk = 1024;
  const long chunks = static_cast<long>((n + kChunk - 1) / kChunk);
  std::vector<double> part(static_cast<std::size_t>(chunks), 0.0);
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c) {
    const std::size_t end = std::min(n, (static_cast<std::size_t>(c) + 1) * kChunk);
    double s = 0.0;
    for (std::size_t i = static_cast<std::size_t>(c) * kChunk; i < end; ++i)
      s += f(i);
    part[static_cast<std::size_t>(c)] = s;
  }
  double total = 0.0;
  for (double p : part)
    total += p;
  return total;
}

using bondedpass::BlockPass;
using bondedpass::kBreaking;
using bondedpass::kBreakingOffset;
using bondedpass::kNoBond;
using bondedpass::kNoBondOffset;

} // namespace

void BondedSolverParams::validate() const {
  if (!(timeStep >= 0.0) || !std::isfinite(timeStep))
    throw InputError("BondedSolver: TimeStep must not be negative");
  if (!(timeStepFraction > 0.0 && timeStepFraction < 0.1))
    throw InputError("BondedSolver: TimeStepFraction must lie in (0, 0.1) of the bond period");
  if (!(skin > 0.0 && skin < 10.0))
    throw InputError("BondedSolver: Skin must lie in (0, 10) sigma");
  if (dissipation != BondedDissipation::None && dissipation != BondedDissipation::ShockViscosity)
    throw InputError("BondedSolver: Dissipation must be None (0) or ShockViscosity (1)");
  shockViscosity().validate(); // refused by name even where Dissipation is None
}

BondedSolver::BondedSolver(BondedSystem system, const BondedSolverParams& params)
    : sys_(std::move(system)), params_(params) {
  params_.validate();
  const std::size_t n = sys_.size();
  if (sys_.positions.size() != 3 * n || sys_.velocities.size() != 3 * n || sys_.body.size() != n)
    throw InputError("BondedSolver: positions, velocities, masses and bodies differ in size");
  if (n == 0)
    throw InputError("BondedSolver: no particles");
  const double mMin = *std::min_element(sys_.masses.begin(), sys_.masses.end());
  if (!(mMin > 0.0) || !(sys_.law.kappa > 0.0) || !(sys_.law.epsilon > 0.0))
    throw InputError("BondedSolver: masses, Kappa and Epsilon must be positive");
  const double period = ws2017::bondPeriod(mMin, sys_.law.kappa);
  dt_ = params_.timeStep > 0.0 ? params_.timeStep : params_.timeStepFraction * period;
  bondBroken_.assign(sys_.bonds.size(), 0);
  force_.assign(3 * n, 0.0);
  prepare();
  computeForces(false);
}

// Bond adjacency (each particle's bonds in index order) and the pair lists.
void BondedSolver::prepare() {
  const std::size_t n = sys_.size();
  if (internal_.size() != n)
    internal_.assign(n, 0.0);
  viscosity_.reset();
  if (params_.dissipation == BondedDissipation::ShockViscosity)
    viscosity_.emplace(params_.shockViscosity(), sys_.law,
                       *std::min_element(sys_.masses.begin(), sys_.masses.end()), dt_);
  for (const BondedBond& b : sys_.bonds)
    if (b.i >= n || b.j >= n || b.i == b.j)
      throw InputError("BondedSolver: a bond names a particle that does not exist");
  bondStart_.assign(n + 1, 0);
  for (const BondedBond& b : sys_.bonds) {
    ++bondStart_[b.i + 1];
    ++bondStart_[b.j + 1];
  }
  for (std::size_t i = 0; i < n; ++i)
    bondStart_[i + 1] += bondStart_[i];
  bondsOf_.resize(bondStart_[n]);
  std::vector<std::size_t> fill(bondStart_.begin(), bondStart_.end() - 1);
  for (std::size_t b = 0; b < sys_.bonds.size(); ++b) {
    bondsOf_[fill[sys_.bonds[b].i]++] = static_cast<std::uint32_t>(b);
    bondsOf_[fill[sys_.bonds[b].j]++] = static_cast<std::uint32_t>(b);
  }
  // The compact lists where r_eq + (float)(r0 − r_eq) is every bond's r0 exactly (the same bits
  // in the pass, so the same run), else the wide ones: for the lattice's nearest neighbours
  // r0 − r_eq is a few ulps. (A difference beyond the float range is not converted at all.)
  restRef_ = sys_.law.rEq();
  compact_ = std::all_of(sys_.bonds.begin(), sys_.bonds.end(), [&](const BondedBond& b) {
    if (!(std::abs(b.rest - restRef_) <= std::numeric_limits<float>::max()))
      return false;
    const float d = static_cast<float>(b.rest - restRef_);
    return std::isfinite(d) && restRef_ + static_cast<double>(d) == b.rest;
  });
  buildPairs();
}

void BondedSolver::useWideLists() {
  if (!compact_)
    return;
  rest_.resize(offset_.size());
  for (std::size_t e = 0; e < offset_.size(); ++e) // no break is marked between steps
    rest_[e] = offset_[e] == kNoBondOffset ? kNoBond : restRef_ + static_cast<double>(offset_[e]);
  std::vector<float>().swap(offset_);
  compact_ = false;
}

// Each particle's list: every particle within r_eq + skin and every intact bonded partner,
// sorted by index, a bonded pair once with its rest length.
void BondedSolver::buildPairs() {
  const std::size_t n = sys_.size(), blocks = (n + kLanes - 1) / kLanes;
  const double* x = sys_.positions.data();
  const double reach = sys_.law.rEq() + params_.skin * sys_.law.sigma, reach2 = reach * reach;
  // Cells of the reach however far the debris spreads (the sparse layout): the dense grid's
  // cells grow with the cloud's box (1.56 reach at 3.95 µs of the headline case) and so does the
  // number of candidates each particle tests.
  CellList& cells = cells_;
  cells.buildSparse(x, n, reach);
  // The candidates are tested on a copy of the positions in cell order, x, y and z apart: each
  // row of cells is then a contiguous stretch, tested eight at a time where the AVX-512 passes
  // run (the list is the same either way).
  const std::vector<std::size_t>& order = cells.sorted();
  cellX_.resize(n), cellY_.resize(n), cellZ_.resize(n), cellId_.resize(n);
#pragma omp parallel for schedule(static)
  for (long s = 0; s < static_cast<long>(n); ++s) {
    const std::size_t j = order[static_cast<std::size_t>(s)];
    cellX_[s] = x[3 * j], cellY_[s] = x[3 * j + 1], cellZ_[s] = x[3 * j + 2];
    cellId_[s] = static_cast<std::uint32_t>(j);
  }
  const bondedpass::NearScan scan{cellX_.data(), cellY_.data(), cellZ_.data(), cellId_.data(),
                                  reach2};
  const bool avx512 = avx512_;
  const auto nearCandidates =
      avx512 ? bondedpass::nearCandidatesAvx512 : bondedpass::nearCandidates;
  using Entry = std::pair<std::uint32_t, double>;
  auto collect = [&](std::size_t i, std::vector<Entry>& out, std::vector<std::uint32_t>& near) {
    std::size_t found = 0;
    cells.forEachNeighbourRange(i, [&](std::size_t begin, std::size_t end) {
      if (near.size() < found + (end - begin) + kLanes)
        near.resize(2 * (found + (end - begin) + kLanes));
      found += nearCandidates(scan, begin, end, x + 3 * i, static_cast<std::uint32_t>(i),
                              near.data() + found);
    });
    out.clear();
    for (std::size_t k = 0; k < found; ++k)
      out.emplace_back(near[k], kNoBond);
    for (std::size_t s = bondStart_[i]; s < bondStart_[i + 1]; ++s) {
      const BondedBond& b = sys_.bonds[bondsOf_[s]];
      if (!bondBroken_[bondsOf_[s]])
        out.emplace_back(b.i == i ? b.j : b.i, b.rest);
    }
    std::sort(out.begin(), out.end()); // a bonded pair's finite rest length first: kept
    out.erase(std::unique(out.begin(), out.end(),
                          [](const Entry& a, const Entry& b) { return a.first == b.first; }),
              out.end());
  };
  // One scan per particle: the lists are staged per chunk of blocks, then laid out in blocks
  // once every block's depth (its longest list) is known.
  constexpr std::size_t kChunkBlocks = 256;
  const std::size_t chunks = (blocks + kChunkBlocks - 1) / kChunkBlocks;
  // Kept from build to build with their capacity: fresh buffers here cost their page faults and
  // the staged lists' regrowth at every build.
  std::vector<std::vector<Entry>>& staged = staged_;
  staged.resize(chunks);
  for (std::vector<Entry>& s : staged)
    s.clear();
  std::vector<std::uint32_t>& count = listed_;
  count.resize(n);
  blockStart_.assign(blocks + 1, 0);
  const long nc = static_cast<long>(chunks);
#pragma omp parallel
  {
    std::vector<Entry> list, chunk;
    std::vector<std::uint32_t> near;
#pragma omp for schedule(dynamic)
    for (long c = 0; c < nc; ++c) {
      // Filled in a private vector (given the chunk's buffer): the threads' vector headers in
      // `staged` share cache lines.
      chunk.swap(staged[c]);
      const std::size_t b0 = static_cast<std::size_t>(c) * kChunkBlocks;
      for (std::size_t b = b0; b < std::min(blocks, b0 + kChunkBlocks); ++b) {
        std::size_t depth = 0;
        for (std::size_t i = b * kLanes; i < std::min(n, (b + 1) * kLanes); ++i) {
          collect(i, list, near);
          count[i] = static_cast<std::uint32_t>(list.size());
          chunk.insert(chunk.end(), list.begin(), list.end());
          depth = std::max(depth, list.size());
        }
        blockStart_[b + 1] = depth * kLanes;
      }
      staged[c].swap(chunk);
    }
  }
  for (std::size_t b = 0; b < blocks; ++b)
    blockStart_[b + 1] += blockStart_[b];
  partner_.resize(blockStart_[blocks]);
  offset_.resize(compact_ ? blockStart_[blocks] : 0);
  rest_.resize(compact_ ? 0 : blockStart_[blocks]);
#pragma omp parallel for schedule(dynamic)
  for (long c = 0; c < nc; ++c) {
    const std::size_t b0 = static_cast<std::size_t>(c) * kChunkBlocks;
    const Entry* from = staged[static_cast<std::size_t>(c)].data();
    for (std::size_t b = b0; b < std::min(blocks, b0 + kChunkBlocks); ++b)
      for (std::size_t l = 0, i = b * kLanes; l < kLanes; ++l, ++i) {
        const std::size_t listed = i < n ? count[i] : 0, self = std::min(n - 1, i);
        for (std::size_t e = blockStart_[b] + l, k = 0; e < blockStart_[b + 1]; e += kLanes, ++k) {
          partner_[e] = k < listed ? from[k].first : static_cast<std::uint32_t>(self);
          const double r0 = k < listed ? from[k].second : kNoBond;
          if (compact_) // exact (prepare)
            offset_[e] = r0 < kNoBond ? static_cast<float>(r0 - restRef_) : kNoBondOffset;
          else
            rest_[e] = r0;
        }
        from += listed;
      }
  }
  blockBreaks_.assign(blocks, 0);
  trigger_.reset(x, n, sys_.law.rEq(), reach);
  ++builds_;
}

void BondedSolver::computeForces(bool kick, bool driftNext) {
  const std::size_t n = sys_.size(), blocks = blockStart_.size() - 1;
  static_assert(kLanes == bondedpass::kLanes, "the pass and the lists' blocks must agree");
  const ws2017::Law& law = sys_.law;
  BlockPass pass;
  pass.x = sys_.positions.data();
  pass.n = n;
  pass.blockStart = blockStart_.data();
  pass.partner = partner_.data();
  pass.rest = compact_ ? nullptr : rest_.data();
  pass.offset = compact_ ? offset_.data() : nullptr;
  pass.restRef = restRef_;
  pass.breaks = blockBreaks_.data();
  pass.force = force_.data();
  const bool avx512 = avx512_;
  // The AVX-512 kick-drift does this half kick (at the next step, or here after the forces when
  // the next step's kick-drift is done here) with the same operation.
  pass.v = kick && !avx512 ? sys_.velocities.data() : nullptr;
  kickPending_ = kick && avx512 && !driftNext;
  pass.m = sys_.masses.data();
  pass.halfStep = 0.5 * dt_;
  pass.terms = {law.sigma * law.sigma, law.epsilon, law.kappa, law.rEq() * law.rEq()};
  pass.rCut2 = law.rCut * law.rCut;
  // The next step's kick-drift into the second position buffer (the pass reads every partner's
  // position from the current one): block by block inside the AVX-512 pass, on the block's
  // forces and positions still in registers; chunk by chunk after the generic pass.
  if (driftNext)
    nextX_.resize(3 * n);
  const bondedpass::DriftPass drift{sys_.positions.data(),
                                    nextX_.data(),
                                    sys_.velocities.data(),
                                    force_.data(),
                                    pass.m,
                                    dt_,
                                    0.5 * dt_,
                                    kick && avx512};
  constexpr std::size_t kChunk = 64; // blocks per call
  const long chunks = static_cast<long>((blocks + kChunk - 1) / kChunk);
  long newlyBroken = 0;
  const auto forces = avx512 ? bondedpass::blockForcesAvx512 : bondedpass::blockForces;
  bondedpass::VelocitySpread spread;
  // Dynamic: a thread that loses its core for a while leaves its chunks to the others; which
  // thread computes a particle does not change its bits (nor the spread's extremes).
#pragma omp parallel reduction(+ : newlyBroken)
  {
    bondedpass::VelocitySpread mine;
#pragma omp for schedule(dynamic) nowait
    for (long c = 0; c < chunks; ++c) {
      const std::size_t b0 = static_cast<std::size_t>(c) * kChunk,
                        b1 = std::min(blocks, (static_cast<std::size_t>(c) + 1) * kChunk);
      if (driftNext && avx512) {
        newlyBroken += bondedpass::blockForcesDriftAvx512(pass, drift, b0, b1, mine);
        continue;
      }
      newlyBroken += forces(pass, b0, b1);
      if (driftNext)
        driftGeneric(drift, b0 * kLanes, std::min(n, b1 * kLanes), mine);
    }
    if (driftNext) {
#pragma omp critical
      spread.merge(mine);
    }
  }
  if (newlyBroken > 0)
    bookBreaks(); // on the positions the pass saw
  if (driftNext) {
    sys_.positions.swap(nextX_);
    spread_ = spread;
    drifted_ = true;
  }
}

// Serial and in bond order, so the dissipated energy has the same bits for any thread count.
// The entries marked by the pass become plain neighbours; each bond is found from its lower
// particle's side (both sides broke it alike).
void BondedSolver::bookBreaks() {
  const std::size_t n = sys_.size();
  std::vector<std::uint32_t> ids;
  for (std::size_t b = 0; b < blockBreaks_.size(); ++b) {
    if (blockBreaks_[b] == 0)
      continue;
    blockBreaks_[b] = 0;
    for (std::size_t e = blockStart_[b]; e < blockStart_[b + 1]; ++e) {
      if (compact_ ? offset_[e] != kBreakingOffset : rest_[e] != kBreaking)
        continue;
      if (compact_)
        offset_[e] = kNoBondOffset;
      else
        rest_[e] = kNoBond;
      const std::size_t i = b * kLanes + (e - blockStart_[b]) % kLanes, j = partner_[e];
      if (i >= j || i >= n)
        continue;
      for (std::size_t s = bondStart_[i]; s < bondStart_[i + 1]; ++s)
        if (sys_.bonds[bondsOf_[s]].j == j)
          ids.push_back(bondsOf_[s]);
    }
  }
  std::sort(ids.begin(), ids.end());
  const double* x = sys_.positions.data();
  for (std::uint32_t b : ids) {
    const BondedBond& bond = sys_.bonds[b];
    const double dx = x[3 * bond.j] - x[3 * bond.i], dy = x[3 * bond.j + 1] - x[3 * bond.i + 1],
                 dz = x[3 * bond.j + 2] - x[3 * bond.i + 2];
    double unused;
    dissipated_ += ws2017::bondSpring(std::sqrt(dx * dx + dy * dy + dz * dz), bond.rest,
                                      sys_.law.kappa, unused);
    bondBroken_[b] = 1;
    ++broken_;
  }
}

// Velocity Verlet: half kick and drift (with the velocities' spread), the lists rebuilt if a
// pair closer than r_eq may be missing from them, then the forces and, in the same pass or
// deferred to the next kick-drift, the second half kick.
void BondedSolver::step() {
  stepDeferred(false);
  settle();
}

void BondedSolver::stepDeferred(bool driftNext) {
  // The kick-drift, unless the last force pass did it.
  const bondedpass::VelocitySpread spread = drifted_ ? spread_ : kickDrift();
  drifted_ = false;
  // The trigger bounds the particles' motion relative to each other, region by region
  // (BondedListTrigger): the cloud's fastest fragments no longer set every particle's bound.
  if (trigger_.expired(sys_.positions.data(), dt_ * spread.relativeSpeed()))
    buildPairs();
  // A pulse of the shock heating ends every interval-th step, on the whole state (without it,
  // as before: the paper's model runs the same operations).
  const bool pulse = viscosity_ && (step_ + 1) % viscosity_->interval() == 0;
  computeForces(true, driftNext && !pulse);
  ++step_;
  if (pulse)
    dissipate();
}

void BondedSolver::dissipate() {
  settle();
  pulseScratch_.resize(4 * sys_.size());
  viscosity_->pulse({sys_.size(), blockStart_.data(), partner_.data()}, sys_.positions.data(),
                    sys_.velocities.data(), sys_.masses.data(), internal_.data(),
                    pulseScratch_.data());
}

// The (pending and) first half kick and the drift; returns the velocities' spread after it.
bondedpass::VelocitySpread BondedSolver::kickDrift() {
  const long n = static_cast<long>(sys_.size());
  double* x = sys_.positions.data();
  const bondedpass::DriftPass p{
      x,         x,           sys_.velocities.data(), force_.data(), sys_.masses.data(), dt_,
      0.5 * dt_, kickPending_};
  const auto kickDriftOf = kickPending_ ? bondedpass::driftAvx512 : driftGeneric;
  bondedpass::VelocitySpread spread;
  constexpr long kChunk = 2048;
#pragma omp parallel
  {
    bondedpass::VelocitySpread mine;
#pragma omp for schedule(dynamic) nowait
    for (long c = 0; c < (n + kChunk - 1) / kChunk; ++c)
      kickDriftOf(p, static_cast<std::size_t>(c * kChunk),
                  static_cast<std::size_t>(std::min(n, (c + 1) * kChunk)), mine);
#pragma omp critical
    spread.merge(mine);
  }
  kickPending_ = false;
  return spread;
}

void BondedSolver::settle() {
  if (!kickPending_)
    return;
  const long n = static_cast<long>(sys_.size());
  const bondedpass::DriftPass p{sys_.positions.data(),
                                sys_.positions.data(),
                                sys_.velocities.data(),
                                force_.data(),
                                sys_.masses.data(),
                                dt_,
                                0.5 * dt_,
                                true};
  constexpr long kChunk = 2048;
#pragma omp parallel for schedule(dynamic)
  for (long c = 0; c < (n + kChunk - 1) / kChunk; ++c)
    bondedpass::halfKickAvx512(p, static_cast<std::size_t>(c * kChunk),
                               static_cast<std::size_t>(std::min(n, (c + 1) * kChunk)));
  kickPending_ = false;
}

void BondedSolver::advance(std::size_t steps, const ProgressCallback& progress) {
  reportProgress(progress, 0.0);
  const std::size_t every = std::max<std::size_t>(1, steps / 100);
  for (std::size_t s = 1; s <= steps; ++s) {
    // The state is whole at every report (an abort keeps it) and at the end; in between, each
    // force pass does the next step's kick-drift too.
    const bool whole = s == steps || (progress && s % every == 0);
    stepDeferred(!whole);
    if (whole) {
      settle();
      reportProgress(progress, static_cast<double>(s) / static_cast<double>(steps));
    }
  }
}

void BondedSolver::advanceTo(double t, const ProgressCallback& progress) {
  if (!std::isfinite(t))
    throw InputError("BondedSolver: the target time must be finite");
  const double target = std::ceil(t / dt_ * (1.0 - 1e-12));
  if (target > static_cast<double>(step_))
    advance(static_cast<std::size_t>(target - static_cast<double>(step_)), progress);
}

BondedEnergies BondedSolver::energies() const {
  BondedEnergies e;
  const double* x = sys_.positions.data();
  const double* v = sys_.velocities.data();
  e.kinetic = chunkedSum(sys_.size(), [&](std::size_t i) {
    const double* vi = v + 3 * i;
    return 0.5 * sys_.masses[i] * (vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
  });
  const ws2017::Law& law = sys_.law;
  const double rEq2 = law.rEq() * law.rEq(), sigma2 = law.sigma * law.sigma;
  e.repulsive = chunkedSum(sys_.size(), [&](std::size_t i) {
    double s = 0.0, unused;
    const std::size_t b = i / kLanes;
    for (std::size_t k = blockStart_[b] + i % kLanes; k < blockStart_[b + 1]; k += kLanes) {
      const std::size_t j = partner_[k];
      const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1],
                   dz = x[3 * i + 2] - x[3 * j + 2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (j > i && r2 < rEq2)
        s += ws2017::repulsion(r2, sigma2, law.epsilon, unused);
    }
    return s;
  });
  e.bond = chunkedSum(sys_.bonds.size(), [&](std::size_t b) {
    if (bondBroken_[b])
      return 0.0;
    const BondedBond& bond = sys_.bonds[b];
    const double dx = x[3 * bond.j] - x[3 * bond.i], dy = x[3 * bond.j + 1] - x[3 * bond.i + 1],
                 dz = x[3 * bond.j + 2] - x[3 * bond.i + 2];
    double unused;
    return ws2017::bondSpring(std::sqrt(dx * dx + dy * dy + dz * dz), bond.rest, law.kappa, unused);
  });
  e.dissipated = dissipated_;
  if (viscosity_)
    e.internal = chunkedSum(internal_.size(), [&](std::size_t i) { return internal_[i]; });
  return e;
}

std::array<double, 3> BondedSolver::momentum() const {
  std::array<double, 3> p{};
  for (int k = 0; k < 3; ++k)
    p[k] = chunkedSum(sys_.size(),
                      [&](std::size_t i) { return sys_.masses[i] * sys_.velocities[3 * i + k]; });
  return p;
}

} // namespace craterkit

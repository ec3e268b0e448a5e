#include "dem/ContactTable.h"

#include "common/CountingIndex.h"
#include "common/GrowFresh.h"
#include "common/SimdClones.h"
#include "dem/PairList.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace craterkit {

void ContactTable::resize(std::size_t count) {
  rows = count;
  first.resize(count, 0u);
  second.resize(count, 0u);
  from.resize(count, 0u);
  for (FreshVector<double>& h : history) {
    h.resize(count + 1, 0.0);
    h[count] = 0.0;
  }
}

void ContactTable::reserveRows(std::size_t count) {
  if (count <= first.size())
    return;
  growFresh(first, count);
  growFresh(second, count);
  growFresh(from, count);
  for (FreshVector<double>& h : history)
    growFresh(h, count + 1);
}

void ContactTable::setRows(std::size_t count) {
  rows = count;
  for (FreshVector<double>& h : history)
    h[count] = 0.0;
}

ContactHistory ContactTable::historyAt(std::size_t c) const {
  ContactHistory h;
  for (int k = 0; k < 3; ++k) {
    h.spring[k] = history[k][c];
    h.rolling[k] = history[3 + k][c];
    h.normal[k] = history[7 + k][c];
  }
  h.twisting = history[6][c];
  return h;
}

void ContactTable::setHistory(std::size_t c, const ContactHistory& h) {
  for (int k = 0; k < 3; ++k) {
    history[k][c] = h.spring[k];
    history[3 + k][c] = h.rolling[k];
    history[7 + k][c] = h.normal[k];
  }
  history[6][c] = h.twisting;
}

void ContactTable::removeParticles(const std::vector<char>& remove,
                                   const std::vector<std::uint32_t>& newIndex,
                                   std::vector<std::uint32_t>& newRow) {
  newRow.assign(rows, ~0u);
  std::size_t o = 0;
  for (std::size_t c = 0; c < rows; ++c) {
    if (remove[first[c]] || remove[second[c]])
      continue;
    first[o] = newIndex[first[c]];
    second[o] = newIndex[second[c]];
    for (FreshVector<double>& h : history)
      h[o] = h[c];
    newRow[c] = static_cast<std::uint32_t>(o++);
  }
  resize(o);
}

namespace {

// One row of evaluateContacts. The loop body is this call alone: variables declared in the
// body of an `omp simd` loop become per-lane arrays, which GCC cannot vectorise when they are
// arrays themselves (rho[3], the lane's vectors: "not suitable for scatter store"); once this
// function is inlined its arrays are plain locals that the compiler splits into scalars.
template <class Law> CK_ALWAYS_INLINE double evaluateRow(const Law& law, const FrictionConstants& f,
                                                         double dt, const ContactInputs& in,
                                                         const double* const* hb, double* const* hn,
                                                         double* res, std::size_t i, std::size_t j,
                                                         std::size_t b, std::size_t c) {
  const double *x = in.x, *r = in.r, *m = in.m, *v = in.v, *w = in.w;
  ContactLane l;
  const double rho[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1],
                         x[3 * j + 2] - x[3 * i + 2]};
  const double d2 = dot3(rho, rho), sum = r[i] + r[j];
  const double d = std::sqrt(d2);
  for (int k = 0; k < 3; ++k)
    l.n[k] = rho[k] / d;
  l.overlap = sum - d;
  l.leverP = (r[i] * r[i] - r[j] * r[j] + d2) / (2.0 * d);
  l.leverN = d - l.leverP;
  const double wi[3] = {w[3 * i], w[3 * i + 1], w[3 * i + 2]};
  const double wj[3] = {w[3 * j], w[3 * j + 1], w[3 * j + 2]};
  double ci[3], cj[3];
  cross3(l.n, wj, cj);
  cross3(l.n, wi, ci);
  // Surface velocities: p's contact point is at +l_p n from its centre, n's at -l_n n.
  for (int k = 0; k < 3; ++k) {
    l.u[k] = ((v[3 * j + k] - v[3 * i + k]) + l.leverN * cj[k]) + l.leverP * ci[k];
    l.omegaRel[k] = wj[k] - wi[k];
    l.omegaSum[k] = wi[k] + wj[k];
  }
  l.reducedMass = m[i] * m[j] / (m[i] + m[j]);
  l.reducedRadius = r[i] * r[j] / sum;
  for (int k = 0; k < 3; ++k) {
    l.spring[k] = hb[k][b];
    l.rolling[k] = hb[3 + k][b];
    l.normal[k] = hb[7 + k][b];
  }
  l.twisting = hb[6][b];
  ssdemContactLane(law, f, l, dt);
  for (int k = 0; k < 3; ++k) {
    hn[k][c] = l.spring[k];
    hn[3 + k][c] = l.rolling[k];
    hn[7 + k][c] = l.normal[k];
    res[ContactTable::kResultWords * c + k] = l.force[k];
    res[ContactTable::kResultWords * c + 3 + k] = l.torqueP[k];
    res[ContactTable::kResultWords * c + 6 + k] = l.torqueN[k];
  }
  hn[6][c] = l.twisting;
  return l.overlap / std::min(r[i], r[j]);
}

// The loop of evaluateContacts, compiled once per law and per instruction set.
template <class Law>
CK_ALWAYS_INLINE double evaluateRows(const Law& law, const FrictionConstants& fc, double dt,
                                     const ContactInputs& in, const ContactTable& before,
                                     ContactTable& now, double* res, std::size_t begin,
                                     std::size_t end) {
  const std::uint32_t *pi = now.first.data(), *pj = now.second.data(), *from = now.from.data();
  const double* hb[ContactTable::kHistoryWords];
  double* hn[ContactTable::kHistoryWords];
  for (int q = 0; q < ContactTable::kHistoryWords; ++q) {
    hb[q] = before.history[q].data();
    hn[q] = now.history[q].data();
  }
  const FrictionConstants f = fc; // a local copy: no store in the loop can change it
  double worst = 0.0;
#pragma omp simd reduction(max : worst)
  for (std::size_t c = begin; c < end; ++c)
    worst = std::max(worst, evaluateRow(law, f, dt, in, hb, hn, res, pi[c], pj[c], from[c], c));
  return worst;
}

} // namespace

CK_SIMD_CLONES double evaluateContacts(const LinearSpringDashpot& law, const FrictionConstants& fc,
                                       double dt, const ContactInputs& in,
                                       const ContactTable& before, ContactTable& now,
                                       double* result, std::size_t begin, std::size_t end) {
  return evaluateRows(law, fc, dt, in, before, now, result, begin, end);
}

CK_SIMD_CLONES double evaluateContacts(const Hertz& law, const FrictionConstants& fc, double dt,
                                       const ContactInputs& in, const ContactTable& before,
                                       ContactTable& now, double* result, std::size_t begin,
                                       std::size_t end) {
  return evaluateRows(law, fc, dt, in, before, now, result, begin, end);
}

void WallContacts::build(const std::vector<std::uint64_t>& near) {
  const std::size_t n = near.size();
  const bool carry = !particle.empty();
  if (carry && start.size() != n + 1)
    throw std::logic_error("WallContacts::build: the old entries have no per-particle index");
  std::vector<std::size_t>& nextStart = spareStart_;
  nextStart.resize(n + 1);
  nextStart[0] = 0;
  for (std::size_t i = 0; i < n; ++i)
    nextStart[i + 1] = nextStart[i] + static_cast<std::size_t>(__builtin_popcountll(near[i]));
  const std::size_t size = nextStart[n];
  spareParticle_.resize(size);
  spareWall_.resize(size);
  spareHistory_.resize(size);
  spareActive_.resize(size);
  // Each particle's entries, with the history and flag of those it had (both in wall order).
#pragma omp parallel for schedule(static) if (n >= kDemParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t c = nextStart[i];
    std::size_t o = carry ? start[i] : 0;
    const std::size_t oEnd = carry ? start[i + 1] : 0;
    for (std::uint64_t bits = near[i]; bits != 0; bits &= bits - 1, ++c) {
      const auto w = static_cast<std::uint32_t>(__builtin_ctzll(bits));
      spareParticle_[c] = static_cast<std::uint32_t>(i);
      spareWall_[c] = w;
      while (o < oEnd && wall[o] < w)
        ++o;
      const bool same = o < oEnd && wall[o] == w;
      spareHistory_[c] = same ? history[o] : ContactHistory{};
      spareActive_[c] = same ? active[o] : 0;
    }
  }
  start.swap(nextStart);
  particle.swap(spareParticle_);
  wall.swap(spareWall_);
  history.swap(spareHistory_);
  active.swap(spareActive_);
}

void WallContacts::removeParticles(const std::vector<char>& remove,
                                   const std::vector<std::uint32_t>& newIndex) {
  std::size_t o = 0;
  for (std::size_t c = 0; c < particle.size(); ++c) {
    if (remove[particle[c]])
      continue;
    particle[o] = newIndex[particle[c]];
    wall[o] = wall[c];
    history[o] = history[c];
    active[o] = active[c];
    ++o;
  }
  particle.resize(o);
  wall.resize(o);
  history.resize(o);
  active.resize(o);
  // The next build carries the histories by particle: index the renumbered entries.
  indexByKey(start, particle, o, keptCount(remove));
}

} // namespace craterkit

// Partial rebuilds of the SPH neighbour lists for the late stage's individual time steps
// (docs/physics.md §2.8; the lists: sph/NeighbourList.h).
//
// With block steps a list is asked to hold every pair at each event, and a few particles that
// move fast among others used to force a full build every few smallest steps. Here each
// particle keeps a reference: its position, h and margin at its last search. A pair (a, b) is
// listed when its references lie within grow max(h_a, h_b) + max(μ_a, μ_b), as a full build
// over the references would list it, and it stays safe while D_a + D_b < max(μ_a, μ_b), D the
// travel since each particle's own reference (valid() checks exactly this). So when some
// particles have moved, only they need new references and a new search, against everybody's
// references; the pairs they find are added to both partners' lists. No pair is dropped
// before the next full build (a dropped pair would have to be re-proven for the partner that
// kept its old reference); pairs out of reach add exact zeros to the sums.
//
// A particle with a clearance (no unlisted particle nearer than its pairs' range plus C at
// its search) is left out of the pairs' check while D_a + D_max < C. A new reference of a
// partner b may come nearer than that: the search of b lowers such clearances to what b's new
// reference leaves, so that the clearance again holds against every reference.
//
// The searches use the grids of the last full build, kept: a mover's entry takes its new
// reference in place (its cell is that of its position at the build; searches of its level
// reach as much further), or, once more than half a cell away, leaves the grids for a short
// loose list that every search tests in full. Movers get a margin of at least 2.2 times their
// motion to the next event, so that the lists are valid() after the refresh. The results are
// the same for any thread count (each mover's search is its own; the new pairs are sorted).
#include "sph/NeighbourGrids.h"
#include "sph/NeighbourList.h"
#include "sph/SphParams.h"
#include "sph/SphState.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>

namespace craterkit {

namespace {
// A particle is searched again when it has moved this share of its margin: below the half at
// which valid() starts to check its pairs, so that the particles just short of the line are
// taken along and the next event does not need a refresh of its own.
constexpr double kRefreshShare = 0.25;
// More movers than this share of the particles cost about a full build: build instead.
constexpr double kMostMovers = 0.25;
// Particles whose references have left their cells (tested by every search) before a full build.
constexpr double kMostLoose = 1.0 / 16.0;
// Growth of the listed entries (no pair is dropped before a full build) before a full build.
constexpr double kMostGrowth = 1.25;
} // namespace

// The movers: particles that have moved kRefreshShare of their margin since their reference
// (and are not left out of valid()'s pairs by their clearance), or whose h has outgrown the
// allowance. False where only a full build will do.
bool NeighbourList::pickMovers(const SphState& s, const SphParams& par,
                               const std::vector<double>& dx, const std::vector<double>& dv,
                               double dt, std::vector<char>& fresh,
                               std::vector<std::uint32_t>& movers) {
  const std::size_t n = s.size();
  if (x_.size() != s.x.size() || margin_.size() != n || par.rebuildEveryStep)
    return false;
  if (grids_ && kMostLoose * static_cast<double>(n) < static_cast<double>(looseList_.size()))
    return false; // the loose list costs more than the grids save
  if (static_cast<double>(entry_.size()) > kMostGrowth * static_cast<double>(builtEntries_))
    return false; // pairs long out of reach (kept since the build) cost the sums too much
  for (int k = 0; k < 3; ++k)
    if (par.periodic[k]) // entries carry the image codes of the build
      return false;
  // Each particle's travel since its reference, with the motion still to come (as valid()).
  std::vector<double>& D = moved_;
  D.assign(n, 0.0);
  double dAll = 0.0;
  const bool xs = !dx.empty(), as = dv.size() == s.v.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (out_[i]) {
      if (!outsideDomain(s, par, i))
        return false; // back in the domain: a full build gives it neighbours
      continue;
    }
    double moved2 = 0.0, v2 = 0.0, a2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = s.x[3 * i + k] - x_[3 * i + k];
      moved2 += d * d;
      const double w = s.v[3 * i + k] + (xs ? dx[3 * i + k] : 0.0);
      v2 += w * w;
      if (as)
        a2 += dv[3 * i + k] * dv[3 * i + k];
    }
    D[i] = std::sqrt(moved2) + 1.5 * dt * std::sqrt(v2) + dt * dt * std::sqrt(a2);
    dAll = std::max(dAll, D[i]);
  }
  fresh.assign(n, 0);
  movers.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (out_[i])
      continue;
    const bool excluded = D[i] + dAll < clearance_[i];
    if (s.h[i] > 0.98 * grow_ * h_[i] || (!excluded && D[i] >= kRefreshShare * margin_[i])) {
      fresh[i] = 1;
      movers.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return !movers.empty() &&
         static_cast<double>(movers.size()) <= kMostMovers * static_cast<double>(n);
}

bool NeighbourList::refresh(const SphState& s, const SphParams& par, const std::vector<double>& dx,
                            const std::vector<double>& dv, double dt) {
  const std::size_t n = s.size();
  std::vector<char> fresh;
  std::vector<std::uint32_t> movers;
  if (!pickMovers(s, par, dx, dv, dt, fresh, movers))
    return false;
  const bool xs = !dx.empty(), as = dv.size() == s.v.size();
  // New references; a mover's margin at least twice its motion to come, so that valid() holds
  // for it after the refresh (a particle crossing a fair share of its h in one event is
  // searched again at each; a full build would have to be made at each).
  for (std::uint32_t i : movers) {
    double v2 = 0.0, a2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double w = s.v[3 * i + k] + (xs ? dx[3 * i + k] : 0.0);
      v2 += w * w;
      if (as)
        a2 += dv[3 * i + k] * dv[3 * i + k];
    }
    const double ahead = 1.5 * dt * std::sqrt(v2) + dt * dt * std::sqrt(a2);
    std::memcpy(&x_[3 * i], &s.x[3 * i], 3 * sizeof(double));
    h_[i] = s.h[i];
    margin_[i] = marginOf(s, par, dx, dt, i);
    margin_[i] = std::max(margin_[i], 2.2 * ahead);
  }

  // The grids of the references: those of the last full build with the movers' entries
  // updated (the first time, grids made anew from the references).
  if (!grids_ || !keepGrids_) {
    keepGrids_ = true;
    std::vector<double> pos;
    std::vector<std::uint32_t> id;
    pos.reserve(3 * n), id.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      if (!out_[i]) {
        pos.insert(pos.end(), &x_[3 * i], &x_[3 * i] + 3);
        id.push_back(static_cast<std::uint32_t>(i * 32 + kNoShift));
      }
    keepGrids(
        std::make_shared<Grids>(h_, pos, id, level_, static_cast<int>(levels_), margin_, grow_));
  } else {
    if (grids_.use_count() > 1) // shared with a copy of this list
      grids_ = std::make_shared<Grids>(*grids_);
    moveReferences(movers);
  }
  const Grids& g = *grids_;
  std::vector<double> levelC(levels_, 0.0); // each level's largest clearance (of those kept)
  for (std::size_t i = 0; i < n; ++i)
    if (!out_[i] && !fresh[i])
      levelC[level_[i]] = std::max(levelC[level_[i]], clearance_[i]);
  const std::size_t m = movers.size();
  std::vector<std::vector<std::uint32_t>> found(m);
  std::vector<double> clear(m);
  const int threads = m >= 64 ? omp_get_max_threads() : 1;
  std::vector<std::vector<Lowered>> lowered(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    std::vector<Lowered>& low = lowered[static_cast<std::size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 8)
    for (std::size_t q = 0; q < m; ++q)
      clear[q] = searchFresh(g, movers[q], levelC, fresh, found[q], low);
  }
  for (const std::vector<Lowered>& low : lowered) // a minimum: the same for any thread count
    for (const Lowered& l : low)
      clearance_[l.to] = std::min(clearance_[l.to], l.clearance);
  // The pairs found that a mover's list does not hold yet (lists are symmetric).
  std::vector<std::uint32_t> seen(n, std::numeric_limits<std::uint32_t>::max());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::size_t q = 0; q < m; ++q) {
    const std::uint32_t a = movers[q];
    clearance_[a] = clear[q];
    for (std::uint32_t e = start_[a]; e < start_[a + 1]; ++e)
      seen[entry_[e] / 32] = static_cast<std::uint32_t>(q);
    for (std::uint32_t e : found[q])
      if (seen[e / 32] != q) {
        const std::uint32_t b = e / 32;
        pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
  }
  addPairs(pairs);
  ++refreshes_;
  for (std::uint32_t i : changed_)
    stamp_[i] = version();
  return true;
}

void NeighbourList::keepGrids(std::shared_ptr<Grids> g) {
  grids_ = std::move(g);
  gridX_ = x_;
  slack_.assign(static_cast<std::size_t>(grids_->levels), 0.0);
  slot_.assign(x_.size() / 3, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t r = 0; r < grids_->sid.size(); ++r)
    if (grids_->sid[r] % 32 == kNoShift)
      slot_[grids_->sid[r] / 32] = static_cast<std::uint32_t>(r);
  loose_.assign(x_.size() / 3, 0);
  looseList_.clear();
}

// The movers' entries in the kept grids take their new references. One within half a cell of
// its position at the build stays in that cell (the searches of its level reach as much
// further); one beyond leaves the grids for the loose list, which every search tests in full.
void NeighbourList::moveReferences(const std::vector<std::uint32_t>& movers) {
  Grids& g = *grids_;
  for (std::uint32_t i : movers) {
    const std::size_t l = level_[i];
    g.levelH[l] = std::max(g.levelH[l], h_[i]);
    g.levelMu[l] = std::max(g.levelMu[l], margin_[i]);
    if (loose_[i])
      continue;
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k)
      d2 += (x_[3 * i + k] - gridX_[3 * i + k]) * (x_[3 * i + k] - gridX_[3 * i + k]);
    const double d = std::sqrt(d2) * (1.0 + 1e-12);
    if (d > 0.5 * g.cellSize[l]) {
      loose_[i] = 1;
      looseList_.push_back(i);
      continue;
    }
    const std::uint32_t r = slot_[i];
    g.spx[r] = x_[3 * i], g.spy[r] = x_[3 * i + 1], g.spz[r] = x_[3 * i + 2];
    g.sh[r] = h_[i], g.smu[r] = margin_[i];
    slack_[l] = std::max(slack_[l], d);
  }
}

double NeighbourList::searchFresh(const Grids& g, std::size_t a, const std::vector<double>& levelC,
                                  const std::vector<char>& fresh, std::vector<std::uint32_t>& found,
                                  std::vector<Lowered>& lowered) const {
  const double grow = g.grow;
  const double* xa = &x_[3 * a];
  const double ha = h_[a], ma = margin_[a];
  const int la = level_[a];
  double spare = INFINITY;
  bool nearMiss = false;
  // Per level: how far a's clearance is searched (Rc; 0: a level too fine to search that far,
  // every unlisted pair has a's margin to spare) and how far anything is (R: the pairs, their
  // near misses, a's clearance and the others' clearances, their range plus the level's largest).
  double Rc[kMaxGridLevels] = {}, R[kMaxGridLevels] = {};
  for (int l = 0; l < g.levels; ++l) {
    const std::size_t L = static_cast<std::size_t>(l);
    const double range = grow * std::max(ha, g.levelH[L]), ml = std::max(ma, g.levelMu[L]);
    Rc[L] = l <= la ? 2.0 * (range + ml) : range + 3.0 * ml;
    if (Rc[L] > 8.0 * g.cellSize[L]) {
      spare = std::min(spare, ma);
      Rc[L] = 0.0;
    } else {
      spare = std::min(spare, Rc[L] - range);
    }
    R[L] = std::max({range + 2.0 * ml, Rc[L], range + levelC[L]});
  }
  const auto consider = [&](std::size_t b, const double* xb, double hb, double mb, std::size_t L,
                            std::uint32_t e) {
    const double ex = xa[0] - xb[0], ey = xa[1] - xb[1], ez = xa[2] - xb[2];
    const double d2 = ex * ex + ey * ey + ez * ez;
    const double pairMu = std::max(ma, mb), pairRange = grow * std::max(ha, hb);
    const double cut = pairRange + pairMu;
    if (d2 < cut * cut) {
      found.push_back(e);
      return;
    }
    nearMiss = nearMiss || d2 < (cut + pairMu) * (cut + pairMu);
    if (d2 >= R[L] * R[L])
      return;
    const double spareOf = std::sqrt(d2) - pairRange;
    if (spareOf < Rc[L] - pairRange)
      spare = std::min(spare, spareOf);
    if (!fresh[b] && spareOf < clearance_[b])
      lowered.push_back({static_cast<std::uint32_t>(b), spareOf});
  };
  for (int l = 0; l < g.levels; ++l) {
    const std::size_t L = static_cast<std::size_t>(l);
    const double cells = R[L] + slack_[L]; // entries sit in the cells of their build positions
    g.forCells(xa, cells, cells, l, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t r = begin; r < end; ++r) {
        const std::size_t b = g.sid[r] / 32;
        if (b != a && !loose_[b]) {
          const double xb[3] = {g.spx[r], g.spy[r], g.spz[r]};
          consider(b, xb, g.sh[r], g.smu[r], L, g.sid[r]);
        }
      }
    });
  }
  for (std::uint32_t b : looseList_) // far from their cells: each one tested
    if (b != a)
      consider(b, &x_[3 * b], h_[b], margin_[b], level_[b],
               static_cast<std::uint32_t>(b * 32 + kNoShift));
  return nearMiss ? 0.0 : std::max(spare, ma);
}

// Appends each new pair (a < b) to both lists, in the pairs' order, moving the lists in place
// (from the back: each moves by the entries added before it).
void NeighbourList::addPairs(std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  changed_.clear();
  if (pairs.empty())
    return;
  const std::size_t n = start_.size() - 1;
  std::vector<std::uint32_t> added(n, 0);
  for (const auto& p : pairs)
    ++added[p.first], ++added[p.second];
  std::vector<std::uint32_t> shift(n + 1, 0); // entries added before each list
  for (std::size_t i = 0; i < n; ++i) {
    shift[i + 1] = shift[i] + added[i];
    if (added[i])
      changed_.push_back(static_cast<std::uint32_t>(i));
  }
  entry_.resize(entry_.size() + shift[n]);
  for (std::size_t i = n; i-- > 0;) {
    if (shift[i] == 0)
      break; // the lists before the first change stay where they are
    std::memmove(&entry_[start_[i] + shift[i]], &entry_[start_[i]],
                 (start_[i + 1] - start_[i]) * sizeof(std::uint32_t));
  }
  std::vector<std::uint32_t> fill(n);
  for (std::size_t i = 0; i < n; ++i)
    fill[i] = start_[i + 1] + shift[i]; // the old list's end at its new place
  for (std::size_t i = 0; i <= n; ++i)
    start_[i] += shift[i];
  for (const auto& p : pairs) {
    entry_[fill[p.first]++] = p.second * 32 + kNoShift;
    entry_[fill[p.second]++] = p.first * 32 + kNoShift;
  }
}

} // namespace craterkit

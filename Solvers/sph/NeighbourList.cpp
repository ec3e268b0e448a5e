#include "sph/NeighbourList.h"

#include "common/SimdClones.h"
#include "sph/NeighbourGrids.h"
#include "sph/SphSolver.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

namespace craterkit {

namespace {

constexpr int kMaxLevels = kMaxGridLevels;

// A run of candidate partners of one particle, in the neighbour grid's sorted order.
struct CandidateRange {
  const double *x, *y, *z, *h, *margin;
  const std::uint32_t* entry; // index * 32 + image code
  std::uint32_t count;
};

// Which candidates particle a (at xa, with h and margin ha, ma; `self` its own entry) lists:
// those within grow max(h_a, h_b) plus the larger margin. keep[k] is 1 for those; returns true
// if one not listed lies within twice the margin (a near miss). One vector pass, no branches.
CK_SIMD_CLONES bool listCandidates(const CandidateRange& c, const double* xa, double ha, double ma,
                                   double grow, std::uint32_t self, std::uint8_t* keep) {
  const double x0 = xa[0], x1 = xa[1], x2 = xa[2];
  int nearMiss = 0;
#pragma omp simd reduction(| : nearMiss)
  for (std::uint32_t k = 0; k < c.count; ++k) {
    const double pairMu = std::max(ma, c.margin[k]);
    const double cut = grow * std::max(ha, c.h[k]) + pairMu;
    const double dx = x0 - c.x[k], dy = x1 - c.y[k], dz = x2 - c.z[k];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const bool other = c.entry[k] != self;
    const bool listed = (r2 < cut * cut) & other;
    keep[k] = listed;
    nearMiss |= !listed & other & (r2 < (cut + pairMu) * (cut + pairMu));
  }
  return nearMiss != 0;
}

// The particles inside the domain, then their periodic images within `reach` of the box:
// positions (3 each) and entries (index * 32 + image code).
void gatherCandidates(const SphState& s, const SphParams& par, const std::vector<char>& out,
                      double reach, std::vector<double>& pos, std::vector<std::uint32_t>& id) {
  const std::size_t n = s.size();
  pos.reserve(3 * n);
  id.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!out[i]) {
      pos.insert(pos.end(), &s.x[3 * i], &s.x[3 * i] + 3);
      id.push_back(static_cast<std::uint32_t>(i * 32 + kNoShift));
    }
  for (int sx = -1; sx <= 1; ++sx)
    for (int sy = -1; sy <= 1; ++sy)
      for (int sz = -1; sz <= 1; ++sz) {
        const int shift[3] = {sx, sy, sz};
        bool ok = sx || sy || sz;
        for (int k = 0; k < 3 && ok; ++k)
          ok = shift[k] == 0 || par.periodic[k];
        if (!ok)
          continue;
        const std::uint32_t code =
            static_cast<std::uint32_t>((sx + 1) + 3 * (sy + 1) + 9 * (sz + 1));
        for (std::size_t i = 0; i < n; ++i) {
          if (out[i])
            continue;
          double y[3];
          bool near = true;
          for (int k = 0; k < 3 && near; ++k) {
            y[k] = s.x[3 * i + k] + shift[k] * (par.boxHi[k] - par.boxLo[k]);
            near =
                !par.periodic[k] || (y[k] >= par.boxLo[k] - reach && y[k] <= par.boxHi[k] + reach);
          }
          if (!near)
            continue;
          pos.insert(pos.end(), y, y + 3);
          id.push_back(static_cast<std::uint32_t>(i * 32 + code));
        }
      }
}

} // namespace

bool outsideDomain(const SphState& s, const SphParams& par, std::size_t i) {
  if (par.domainRadius <= 0.0)
    return false;
  const double* x = &s.x[3 * i];
  const double dx = x[0] - par.domainCentre[0], dy = x[1] - par.domainCentre[1],
               dz = x[2] - par.domainCentre[2];
  return dx * dx + dy * dy + dz * dz > par.domainRadius * par.domainRadius;
}

bool NeighbourList::valid(const SphState& s, const SphParams& par, const std::vector<double>& dx,
                          const std::vector<double>& dv, double dt) const {
  // Valid while no pair can have come within its listing range without being listed. A pair
  // closes in by at most the sum of its two particles' displacements D (since each one's last
  // search, plus 1.5 dt |v| for the motion still to come in this step). An unlisted pair had at
  // least the larger of its two margins to spare; but a particle with a clearance C (no unlisted
  // particle within twice the margin at the build: ejecta in flight, alone or in small clumps)
  // had C to spare against everybody and needs only D + D_max < C. Such particles are left out
  // of the pairs' check, so that a few fast fragments do not force a new list for all. And no
  // h has grown past the allowance.
  const std::size_t n = s.size();
  if (x_.size() != s.x.size() || par.rebuildEveryStep)
    return false;
  const bool xs = !dx.empty();
  std::vector<double>& D = moved_;
  D.assign(n, 0.0);
  double dAll = 0.0;
  bool hOk = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (out_[i]) {
      if (!outsideDomain(s, par, i))
        return false; // back in the domain: it needs neighbours
      continue;
    }
    double moved2 = 0.0, v2 = 0.0, a2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double d = s.x[3 * i + k] - x_[3 * i + k];
      // A particle wrapped through a periodic face since the build: its listed pairs carry
      // the image codes of the old side.
      if (par.periodic[k] && std::abs(d) > 0.5 * (par.boxHi[k] - par.boxLo[k]))
        return false;
      moved2 += d * d;
      const double w = s.v[3 * i + k] + (xs ? dx[3 * i + k] : 0.0);
      v2 += w * w;
      if (dv.size() == s.v.size())
        a2 += dv[3 * i + k] * dv[3 * i + k];
    }
    // Motion still to come in the step: speed, with a margin, and what the acceleration adds.
    D[i] = std::sqrt(moved2) + 1.5 * dt * std::sqrt(v2) + dt * dt * std::sqrt(a2);
    dAll = std::max(dAll, D[i]);
    hOk = hOk && s.h[i] <= 0.98 * grow_ * h_[i]; // room for the growth within this step
  }
  if (!hOk)
    return false;
  // A pair (a, b) is safe while D_a + D_b stays below the larger of their margins: so if both
  // have moved less than half their own. Those that have not are checked against every level
  // of h (its two largest D and smallest margin): against the largest D but their own. With
  // one margin for all this is "the two largest D below the margin".
  const std::size_t L = levels_;
  std::array<double, kMaxLevels> d1{}, d2{}, muMin;
  std::array<std::size_t, kMaxLevels> top;
  muMin.fill(INFINITY);
  top.fill(n);
  auto excluded = [&](std::size_t i) { return out_[i] || D[i] + dAll < clearance_[i]; };
  for (std::size_t i = 0; i < n; ++i) {
    if (excluded(i))
      continue;
    const std::size_t l = level_[i];
    if (D[i] > d1[l]) {
      d2[l] = d1[l], d1[l] = D[i], top[l] = i;
    } else if (D[i] > d2[l]) {
      d2[l] = D[i];
    }
    muMin[l] = std::min(muMin[l], margin_[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (excluded(i) || D[i] < 0.5 * margin_[i])
      continue;
    for (std::size_t l = 0; l < L; ++l)
      if (muMin[l] < INFINITY &&
          D[i] + (top[l] == i ? d2[l] : d1[l]) >= std::max(margin_[i], muMin[l]))
        return false;
  }
  return true;
}

void NeighbourList::build(const SphState& s, const SphParams& par, const std::vector<double>& dx,
                          double dt, bool margins) {
  double hmax = 0.0, hmin = INFINITY, muMax = 0.0;
  setMargins(s, par, dx, dt, margins, hmax, hmin, muMax);
  const double grow = 1.05; // h may grow this much before the list misses a pair
  const double reach = grow * hmax + muMax;
  x_ = s.x;
  h_ = s.h;
  grow_ = grow;
  std::vector<double> pos;
  std::vector<std::uint32_t> id;
  gatherCandidates(s, par, out_, reach, pos, id);
  setLevels(s, hmax, hmin);
  auto grids =
      std::make_shared<Grids>(s.h, pos, id, level_, static_cast<int>(levels_), margin_, grow);
  listAll(*grids, s, par, reach, margins);
  builtEntries_ = entry_.size();
  if (keepGrids_)
    keepGrids(std::move(grids));
  else
    grids_.reset();
}

void NeighbourList::setMargins(const SphState& s, const SphParams& par,
                               const std::vector<double>& dx, double dt, bool margins, double& hmax,
                               double& hmin, double& muMax) {
  const std::size_t n = s.size();
  out_.assign(n, 0);
  margin_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    out_[i] = outsideDomain(s, par, i);
    if (!out_[i]) {
      hmax = std::max(hmax, s.h[i]);
      hmin = std::min(hmin, s.h[i]);
      // Each particle's own: skin h, or for a fast one 16 steps of its motion (at most h/2), so
      // that its list lasts about 6 steps. In a graded target a coarse particle's list then
      // lasts as long as a fine one's, and a few fast ones do not force new lists for all.
      // (One margin for all, set by the finest h and the fastest particle, made every list of
      // a late-stage graded run last a step.)
      if (margins)
        margin_[i] = marginOf(s, par, dx, dt, i);
      muMax = std::max(muMax, margin_[i]);
    }
  }
}

double NeighbourList::marginOf(const SphState& s, const SphParams& par,
                               const std::vector<double>& dx, double dt, std::size_t i) const {
  double w2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double w = s.v[3 * i + k] + (dx.size() == s.v.size() ? dx[3 * i + k] : 0.0);
    w2 += w * w;
  }
  return std::max(par.skin * s.h[i], std::min(16.0 * dt * std::sqrt(w2), 0.5 * s.h[i]));
}

// Levels of smoothing length, a factor of √2 apart (level 0 holds the largest h). With one
// grid sized by the largest h, a graded target (h ten times larger at its edge than at the
// impact point) or a spray of expanded ejecta would make every fine particle scan a thousand
// times its own neighbourhood. Each level has its own grid; a particle scans its own level
// and the coarser ones (cells sized for them, so a few per axis), and the pairs with finer
// particles reach it from their side: the finer partner lists the pair and hands it over.
// The pairs are those of one grid: r below grow max(h_a, h_b) plus the larger margin.
void NeighbourList::setLevels(const SphState& s, double hmax, double hmin) {
  const std::size_t n = s.size();
  int levels = 1;
  if (hmax > std::sqrt(2.0) * hmin)
    levels = std::min(kMaxLevels, 1 + static_cast<int>(std::floor(2.0 * std::log2(hmax / hmin))));
  auto levelOf = [&](double h) {
    return levels == 1
               ? 0
               : std::clamp(static_cast<int>(std::floor(2.0 * std::log2(hmax / h))), 0, levels - 1);
  };
  levels_ = static_cast<std::size_t>(levels);
  level_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    level_[i] = static_cast<std::uint8_t>(levelOf(s.h[i]));
}

// Lists a's neighbours in its own and the coarser levels (the pairs with coarser ones also
// into `handed`, as entries of the partner's list); true if an unlisted particle came within
// twice the margin.
bool NeighbourList::visit(const Grids& g, const SphState& s, std::size_t a,
                          std::vector<std::uint32_t>& out, std::vector<Handed>& handed,
                          std::vector<std::uint8_t>& keep) const {
  bool nearMiss = false;
  const double grow = g.grow;
  const double* xa = &s.x[3 * a];
  const double ha = s.h[a], ma = margin_[a];
  const int la = level_[a];
  const std::uint32_t self = static_cast<std::uint32_t>(a * 32 + kNoShift);
  for (int l = 0; l <= la; ++l) {
    const double R = grow * std::max(ha, g.levelH[static_cast<std::size_t>(l)]) +
                     std::max(ma, g.levelMu[static_cast<std::size_t>(l)]);
    // Listed and near-missed pairs lie within R plus the larger margin.
    const double ball = R + std::max(ma, g.levelMu[static_cast<std::size_t>(l)]);
    g.forCells(xa, R, ball, l, [&](std::uint32_t begin, std::uint32_t end) {
      // The candidates' tests in one vector pass, then the list advances past those in
      // range (branch-free: every candidate is written).
      const std::uint32_t count = end - begin;
      if (keep.size() < count)
        keep.resize(count);
      const CandidateRange cr{g.spx.data() + begin,
                              g.spy.data() + begin,
                              g.spz.data() + begin,
                              g.sh.data() + begin,
                              g.smu.data() + begin,
                              g.sid.data() + begin,
                              count};
      nearMiss |= listCandidates(cr, xa, ha, ma, grow, self, keep.data());
      std::size_t at = out.size();
      out.resize(at + count);
      std::uint32_t* o = out.data();
      for (std::uint32_t k = 0; k < count; ++k) {
        o[at] = g.sid[begin + k];
        at += keep[k];
      }
      out.resize(at);
      if (l < la) // b's image at the opposite shift is near a
        for (std::uint32_t k = 0; k < count; ++k)
          if (keep[k]) {
            const std::uint32_t e = g.sid[begin + k];
            handed.push_back({e / 32, static_cast<std::uint32_t>(a * 32 + (26 - e % 32))});
          }
    });
  }
  return nearMiss;
}

// A particle with no unlisted particle within twice the margin gets its clearance: how far
// the nearest unlisted particle is beyond the pair's listing range without the margin. Each
// level is searched to twice its reach from a (the finer ones to three margins beyond a's
// own range, unless that spans too many of their cells); anybody farther has at least that
// search radius minus the level's largest range to spare.
double NeighbourList::clearanceOf(const Grids& g, const SphState& s, const SphParams& par,
                                  std::size_t a, double far) const {
  const double grow = g.grow;
  const double* xa = &s.x[3 * a];
  for (int k = 0; k < 3; ++k) // periodic images are listed only within one reach of the box
    if (par.periodic[k] && (xa[k] < par.boxLo[k] + far || xa[k] > par.boxHi[k] - far))
      return 0.0;
  const double ha = s.h[a], ma = margin_[a];
  const int la = level_[a];
  double spare = INFINITY;
  for (int l = 0; l < g.levels; ++l) {
    if (g.empty(l))
      continue;
    const double range = grow * std::max(ha, g.levelH[static_cast<std::size_t>(l)]);
    const double ml = std::max(ma, g.levelMu[static_cast<std::size_t>(l)]);
    const double R = l <= la ? 2.0 * (range + ml) : range + 3.0 * ml;
    if (R >
        8.0 * g.cellSize[static_cast<std::size_t>(l)]) { // a level far finer than a: too many cells
      spare = std::min(spare, ma); // to search; every unlisted pair has a's margin
      continue;
    }
    spare = std::min(spare, R - range);
    // Beyond R nobody is nearer than R - range: the ball of radius R holds all that counts.
    g.forCells(xa, R, R, l, [&](std::uint32_t begin, std::uint32_t end) {
      for (std::uint32_t r = begin; r < end; ++r) {
        const std::uint32_t e = g.sid[r];
        if (e / 32 == a && e % 32 == kNoShift)
          continue;
        const double d = std::sqrt((xa[0] - g.spx[r]) * (xa[0] - g.spx[r]) +
                                   (xa[1] - g.spy[r]) * (xa[1] - g.spy[r]) +
                                   (xa[2] - g.spz[r]) * (xa[2] - g.spz[r]));
        const double pairRange = grow * std::max(ha, g.sh[r]);
        if (d >= pairRange + std::max(ma, g.smu[r])) // listed ones are not spare
          spare = std::min(spare, d - pairRange);
      }
    });
  }
  return std::max(spare, ma); // unlisted: at least a's margin
}

// One pass: each thread lists a contiguous block of particles into its own buffer (in the
// grids' order, the same for any thread count), then the blocks are copied into place and
// the pairs handed over from finer particles are appended to their partners' lists, in the
// order of the finer particles (again the same for any thread count).
void NeighbourList::listAll(const Grids& g, const SphState& s, const SphParams& par, double reach,
                            bool margins) {
  const std::size_t n = s.size();
  const double far = 4.0 * reach;
  ++builds_;
  stamp_.assign(n, version());
  start_.assign(n + 1, 0);
  clearance_.assign(n, 0.0);
  const int threads = n >= 1024 ? omp_get_max_threads() : 1;
  if (work_.size() < static_cast<std::size_t>(threads))
    work_.resize(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num()),
                      nt = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t a0 = n * t / nt, a1 = n * (t + 1) / nt;
    std::vector<std::uint32_t>& out = work_[t].out;
    std::vector<Handed>& handed = work_[t].handed;
    std::vector<std::uint8_t>& keep = work_[t].keep;
    out.clear();
    handed.clear();
    for (std::size_t a = a0; a < a1; ++a) {
      const std::size_t before = out.size();
      if (!out_[a]) {
        if (!visit(g, s, a, out, handed, keep) &&
            margins) // with no margin the list is rebuilt at once anyway
          clearance_[a] = clearanceOf(g, s, par, a, far);
      }
      start_[a + 1] = static_cast<std::uint32_t>(out.size() - before);
    }
  }
  std::size_t total = 0;
  for (std::size_t t = 0; t < static_cast<std::size_t>(threads); ++t)
    total += work_[t].out.size() + work_[t].handed.size();
  if (total > 0xF0000000u)
    throw std::runtime_error(
        "SPH: too many neighbour pairs (the smoothing lengths have grown too large)");
  std::vector<std::uint32_t> own(start_.begin() + 1, start_.end());
  for (std::size_t t = 0; t < static_cast<std::size_t>(threads); ++t)
    for (const Handed& p : work_[t].handed)
      ++start_[p.to + 1];
  for (std::size_t a = 0; a < n; ++a)
    start_[a + 1] += start_[a];
  entry_.resize(total);
  // Own entries: the buffers, read in thread order, hold them in ascending a. Then `own`
  // counts on as each list's fill.
  std::size_t bi = 0, k = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (own[a] == 0)
      continue;
    while (k == work_[bi].out.size())
      ++bi, k = 0;
    std::copy(work_[bi].out.begin() + static_cast<std::ptrdiff_t>(k),
              work_[bi].out.begin() + static_cast<std::ptrdiff_t>(k + own[a]),
              entry_.begin() + static_cast<std::ptrdiff_t>(start_[a]));
    k += own[a];
  }
  for (std::size_t t = 0; t < static_cast<std::size_t>(threads); ++t)
    for (const Handed& p : work_[t].handed)
      entry_[start_[p.to] + own[p.to]++] = p.entry;
}

std::vector<std::uint32_t> NeighbourList::sortedOf(std::size_t a) const {
  std::vector<std::uint32_t> list(entry_.begin() + start_[a], entry_.begin() + start_[a + 1]);
  std::sort(list.begin(), list.end());
  return list;
}

} // namespace craterkit

#include "sph/ClusterPairs.h"

#include "sph/Kernels.h"
#include "sph/SupportList.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace craterkit {

namespace {
// Spreads the low 21 bits of v to every third bit (a Morton key's one axis).
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  return (v | v << 2) & 0x1249249249249249ULL;
}
constexpr std::size_t kMinSlabs = 4;
} // namespace

bool ClusterPairs::follow(const PairPosition* X, std::size_t n, const SupportList& list) {
  if (!formed_ || draw_ != list.draws() || slot_.size() != n)
    form(X, n, list);
  return usable_;
}

void ClusterPairs::form(const PairPosition* X, std::size_t n, const SupportList& list) {
  formed_ = true, usable_ = false, draw_ = list.draws();
  if (n == 0)
    return;
  double lo[3], hi[3], hmax = 0.0, hmin = X[0].h;
  for (int k = 0; k < 3; ++k)
    lo[k] = hi[k] = X[0].x[k];
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k)
      lo[k] = std::min(lo[k], X[i].x[k]), hi[k] = std::max(hi[k], X[i].x[k]);
    hmax = std::max(hmax, X[i].h), hmin = std::min(hmin, X[i].h);
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    axis = hi[k] - lo[k] > hi[axis] - lo[axis] ? k : axis;
  // Every listed pair was within (1 + skin) h̄ ≤ (1 + skin) h_max at the draw.
  const double width = (1.0 + kSupportSkin) * hmax * (1.0 + 1e-9);
  if (!(hmin > 0.0) || !(hi[axis] - lo[axis] >= kMinSlabs * width))
    return;
  // Morton cells of an eighth of the smallest h: a cluster is a few of them each way,
  // and the slabs are whole pairs of cells thick so that they do not cut those blocks.
  const double cell = 0.125 * hmin;
  const double cellsPerSlab = 2.0 * std::ceil(width / (2.0 * cell));
  const double slabs = std::floor((hi[axis] - lo[axis]) / (cellsPerSlab * cell));
  if (!(slabs >= kMinSlabs) || cellsPerSlab > 1e6)
    return;
  const auto S = static_cast<std::size_t>(std::min(slabs, 1e6));
  const auto per = static_cast<std::uint64_t>(cellsPerSlab);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> key(n);
  std::vector<std::uint32_t> slabOf(n), count(S, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t c[3], m = 0;
    for (int k = 0; k < 3; ++k)
      c[k] = static_cast<std::uint64_t>(std::min((X[i].x[k] - lo[k]) / cell, 2e9));
    slabOf[i] = static_cast<std::uint32_t>(std::min<std::uint64_t>(S - 1, c[axis] / per));
    for (int k = 0; k < 3; ++k)
      m |= spread(c[k]) << k;
    key[i] = {m, static_cast<std::uint32_t>(i)};
    ++count[slabOf[i]];
  }
  std::sort(key.begin(), key.end(), [&](const auto& a, const auto& b) {
    return slabOf[a.second] != slabOf[b.second] ? slabOf[a.second] < slabOf[b.second] : a < b;
  });
  slabStart_.assign(S + 1, 0);
  for (std::size_t s = 0; s < S; ++s)
    slabStart_[s + 1] = slabStart_[s] + (count[s] + 7) / 8;
  const std::size_t clusters = slabStart_[S];
  member_.assign(8 * clusters, -1);
  slot_.resize(n);
  for (std::size_t s = 0, k = 0; s < S; ++s)
    for (std::uint32_t j = 0; j < count[s]; ++j, ++k) {
      const std::uint32_t slot = 8 * slabStart_[s] + j, i = key[k].second;
      member_[slot] = i, slot_[i] = slot;
    }
  // Each cluster's partners: the clusters at or after it that hold its particles' entries.
  std::vector<std::uint32_t> clusterSlab(clusters);
  for (std::size_t s = 0; s < S; ++s)
    std::fill(clusterSlab.begin() + slabStart_[s], clusterSlab.begin() + slabStart_[s + 1], s);
  std::vector<char> mark(clusters, 0);
  std::vector<std::uint32_t> got;
  start_.assign(clusters + 1, 0);
  partner_.clear();
  for (std::uint32_t I = 0; I < clusters; ++I) {
    got.clear();
    for (std::uint32_t l = 0; l < 8; ++l) {
      const std::int64_t a = member_[8 * I + l];
      if (a < 0)
        continue;
      const std::uint32_t* e = list.entries(static_cast<std::size_t>(a));
      for (std::uint32_t k = 0; k < list.count(static_cast<std::size_t>(a)); ++k) {
        const std::uint32_t J = slot_[e[k] >> 5] / 8;
        if (J >= I && !mark[J])
          mark[J] = 1, got.push_back(J);
      }
    }
    std::sort(got.begin(), got.end());
    for (std::uint32_t J : got) {
      mark[J] = 0;
      if (clusterSlab[J] > clusterSlab[I] + 1)
        return; // a partner beyond the next slab (cannot happen with the width above)
      partner_.push_back(J);
    }
    start_[I + 1] = static_cast<std::uint32_t>(partner_.size());
  }
  // Each phase's slabs, the most listed cluster pairs first (for the threads' balance).
  for (std::size_t parity = 0; parity < 2; ++parity) {
    phase_[parity].clear();
    for (std::size_t s = parity; s < S; s += 2)
      if (slabStart_[s + 1] > slabStart_[s])
        phase_[parity].push_back(static_cast<std::uint32_t>(s));
    auto work = [&](std::uint32_t s) { return start_[slabStart_[s + 1]] - start_[slabStart_[s]]; };
    std::stable_sort(phase_[parity].begin(), phase_[parity].end(),
                     [&](std::uint32_t a, std::uint32_t b) { return work(a) > work(b); });
  }
  block_.resize(clusters);
  sums_.resize(clusters);
  out_.resize(n);
  usable_ = true;
}

void ClusterPairs::pack(const PairRecord* P, const PairPosition* X) {
  const std::size_t clusters = block_.size();
#pragma omp parallel for schedule(static) if (clusters >= 512)
  for (std::size_t c = 0; c < clusters; ++c) {
    ClusterBlock& b = block_[c];
    for (std::size_t l = 0; l < 8; ++l) {
      const std::int64_t m = member_[8 * c + l];
      if (m < 0) { // far from everything and from every other padding lane, no mass
        for (auto& row : b.f)
          row[l] = 0.0;
        b.f[kCx][l] = 1e12 * static_cast<double>(8 * c + l + 1);
        b.f[kCh][l] = b.f[kCrho][l] = 1.0;
        continue;
      }
      const PairPosition& x = X[m];
      const PairRecord& r = P[m];
      b.f[kCx][l] = x.x[0], b.f[kCy][l] = x.x[1], b.f[kCz][l] = x.x[2], b.f[kCh][l] = r.h;
      b.f[kCvx][l] = r.v[0], b.f[kCvy][l] = r.v[1], b.f[kCvz][l] = r.v[2];
      b.f[kCrho][l] = r.rho, b.f[kCm][l] = r.m, b.f[kCvol][l] = r.vol;
      b.f[kCpr][l] = r.pr, b.f[kCc][l] = r.c;
      for (int k = 0; k < 6; ++k)
        b.f[kCs0 + k][l] = r.s[k];
    }
    std::memset(&sums_[c], 0, sizeof(ClusterSums));
  }
}

template <class K, bool Xsph>
void ClusterPairs::evaluate(const PairRecord* P, const PairPosition* X, const PairConstants& pc) {
  pack(P, X);
  for (const std::vector<std::uint32_t>& slabs : phase_) {
    const std::size_t m = slabs.size();
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < m; ++k)
      clusterPairSums<K, Xsph>(block_.data(), start_.data(), partner_.data(), slabStart_[slabs[k]],
                               slabStart_[slabs[k] + 1], sums_.data(), pc);
  }
  // Unpacked per particle (reading a lane's 18 rows per particle touched 18 cache lines).
  const std::size_t clusters = sums_.size();
#pragma omp parallel for schedule(static) if (clusters >= 512)
  for (std::size_t c = 0; c < clusters; ++c)
    for (std::size_t l = 0; l < 8; ++l) {
      const std::int64_t a = member_[8 * c + l];
      if (a < 0)
        continue;
      const ClusterSums& from = sums_[c];
      PairSums& r = out_[static_cast<std::size_t>(a)];
      for (int k = 0; k < 3; ++k)
        r.acc[k] = from.a[k][l], r.xs[k] = from.a[14 + k][l];
      r.dr = from.a[3][l], r.de = from.a[4][l], r.sig = from.a[17][l];
      for (int k = 0; k < 9; ++k)
        r.grad[k] = from.a[5 + k][l];
    }
}

template void ClusterPairs::evaluate<CubicSpline, false>(const PairRecord*, const PairPosition*,
                                                         const PairConstants&);
template void ClusterPairs::evaluate<CubicSpline, true>(const PairRecord*, const PairPosition*,
                                                        const PairConstants&);
template void ClusterPairs::evaluate<WendlandC2, false>(const PairRecord*, const PairPosition*,
                                                        const PairConstants&);
template void ClusterPairs::evaluate<WendlandC2, true>(const PairRecord*, const PairPosition*,
                                                       const PairConstants&);

} // namespace craterkit

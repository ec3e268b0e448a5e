#include "sph/ClusterList.h"

#include "sph/NeighbourList.h"
#include "sph/SphState.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace craterkit {

namespace {
// The 21 low bits of v spread to every third bit (the Morton interleave of one axis).
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
} // namespace

// The particles inside the domain along a Morton curve on cells of a quarter of the smallest h
// (so eight consecutive ones are a compact clump of a lattice), padded to whole clusters; then
// those outside the domain (no neighbours, listed by nobody), in their own clusters. Ties
// are broken by index: the same clusters for any thread count.
void ClusterList::sortIntoClusters(const SphState& s, const NeighbourList& nb) {
  const std::size_t n = s.size();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hmin = INFINITY;
  for (std::size_t i = 0; i < n; ++i)
    if (!nb.outside(i)) {
      for (int k = 0; k < 3; ++k)
        lo[k] = std::min(lo[k], s.x[3 * i + k]);
      hmin = std::min(hmin, s.h[i]);
    }
  const double cell = 0.25 * hmin, top = static_cast<double>(0x1fffff);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> key;
  key.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!nb.outside(i)) {
      std::uint64_t m = 0;
      for (int k = 0; k < 3; ++k) {
        const double c = std::clamp(std::floor((s.x[3 * i + k] - lo[k]) / cell), 0.0, top);
        m |= spreadBits(static_cast<std::uint64_t>(c)) << k;
      }
      key.push_back({m, static_cast<std::uint32_t>(i)});
    }
  std::sort(key.begin(), key.end());
  const auto empty = static_cast<std::uint32_t>(n);
  member_.clear();
  member_.reserve(n + 2 * kLanes);
  for (const auto& k : key)
    member_.push_back(k.second);
  member_.resize((member_.size() + kLanes - 1) / kLanes * kLanes, empty);
  insideLanes_ = member_.size();
  for (std::size_t i = 0; i < n; ++i)
    if (nb.outside(i))
      member_.push_back(static_cast<std::uint32_t>(i));
  member_.resize((member_.size() + kLanes - 1) / kLanes * kLanes, empty);
  slot_.assign(n, 0);
  for (std::size_t q = 0; q < member_.size(); ++q)
    if (member_[q] != empty)
      slot_[member_[q]] = static_cast<std::uint32_t>(q);
}

// The mean over the clusters of their bounding boxes' diagonals (a fixed order: the same
// bits for any thread count).
double ClusterList::spread(const SphState& s) const {
  const std::size_t n = s.size(), nc = clusters();
  double sum = 0.0;
  for (std::size_t q = 0; q < nc; ++q) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t k = 0; k < kLanes; ++k) {
      const std::size_t i = member_[q * kLanes + k];
      if (i != n)
        for (int j = 0; j < 3; ++j)
          lo[j] = std::min(lo[j], s.x[3 * i + j]), hi[j] = std::max(hi[j], s.x[3 * i + j]);
    }
    double d2 = 0.0;
    for (int j = 0; j < 3; ++j)
      d2 += (hi[j] - lo[j]) * (hi[j] - lo[j]);
    sum += std::sqrt(d2);
  }
  return nc > 0 ? sum / static_cast<double>(nc) : 0.0;
}

void ClusterList::build(const SphState& s, const NeighbourList& nb) {
  const std::size_t n = s.size();
  // The clusters are kept while they stay compact (the lists are right for any clusters; the
  // pair loop's cost grows with their size). Kept clusters also keep the pair sums' order: a
  // lane outside the support adds an exact zero, so the rates do not depend on which extra
  // clusters a list holds, and kept lists give the same bits as lists built every step.
  bool stale = slot_.size() != n;
  for (std::size_t a = 0; a < n && !stale; ++a)
    stale = nb.outside(a) != (slot_[a] >= insideLanes_);
  if (stale || !(spread(s) <= 1.25 * formedSpread_)) {
    sortIntoClusters(s, nb);
    formedSpread_ = spread(s);
  }
  const std::vector<std::uint32_t>& ns = nb.start();
  const std::vector<std::uint32_t>& ne = nb.entry();
  // Each particle's clusters, unique and ascending, written first where its neighbours'
  // entries sit (never more of them), then packed. Each particle's own work: any thread
  // count gives the same lists. Unshifted clusters are marked as seen with the particle's
  // index (no sort of the ~90 entries); periodic images, rare, are searched for.
  const std::size_t nc = clusters();
  std::vector<std::uint32_t> scratch(ne.size());
  start_.assign(n + 1, 0);
#pragma omp parallel if (n >= 2048)
  {
    std::vector<std::uint32_t> seen(nc, ~0u);
#pragma omp for schedule(dynamic, 256)
    for (std::size_t a = 0; a < n; ++a) {
      std::uint32_t* out = scratch.data() + ns[a];
      std::uint32_t m = 0;
      for (std::uint32_t k = ns[a]; k < ns[a + 1]; ++k) {
        const std::uint32_t e = ne[k], cl = static_cast<std::uint32_t>(slot_[e >> 5] / kLanes);
        const std::uint32_t v = cl << 5 | (e & 31u);
        if ((e & 31u) == kNoShift) {
          if (seen[cl] == a)
            continue;
          seen[cl] = static_cast<std::uint32_t>(a);
        } else if (std::find(out, out + m, v) != out + m) {
          continue;
        }
        out[m++] = v;
      }
      std::sort(out, out + m); // partners in memory order
      start_[a + 1] = m;
    }
  }
  for (std::size_t a = 0; a < n; ++a)
    start_[a + 1] += start_[a];
  entry_.resize(start_[n]);
  for (std::size_t a = 0; a < n; ++a)
    std::copy(scratch.begin() + ns[a], scratch.begin() + ns[a] + (start_[a + 1] - start_[a]),
              entry_.begin() + start_[a]);
}

} // namespace craterkit

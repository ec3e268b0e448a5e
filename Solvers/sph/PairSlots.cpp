#include "sph/PairSlots.h"

#include <algorithm>

namespace craterkit {

void PairSlots::build(const std::vector<std::uint32_t>& start,
                      const std::vector<std::uint32_t>& entry, std::uint32_t kSelf) {
  const std::size_t n = start.empty() ? 0 : start.size() - 1;
  const std::size_t nb = (n + kBlock - 1) / kBlock;
  auto kept = [kSelf](std::size_t a, std::uint32_t e) {
    const std::size_t b = e / 32;
    return b > a || (b == a && e % 32 < kSelf);
  };
  // The half list: counts per particle, offsets, then the entries in the full list's order.
  start_.assign(n + 1, 0);
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t a = 0; a < n; ++a) {
    std::uint32_t c = 0;
    for (std::uint32_t k = start[a]; k < start[a + 1]; ++k)
      c += kept(a, entry[k]);
    start_[a + 1] = c;
  }
  for (std::size_t a = 0; a < n; ++a)
    start_[a + 1] += start_[a];
  entry_.resize(start_[n]);
  slot_.resize(start_[n]);
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (std::size_t a = 0; a < n; ++a) {
    std::uint32_t at = start_[a];
    for (std::uint32_t k = start[a]; k < start[a + 1]; ++k)
      if (kept(a, entry[k]))
        entry_[at++] = entry[k];
  }
  // Each block's partners beyond its last particle (the owners' partners are never before the
  // block: b >= a), found with a mark per particle (a thread's own array, left clear), then
  // the partner's slot of each kept entry: its own in the block, or its place among the
  // block's outside partners.
  constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  outside_.resize(nb);
  blockBase_.assign(nb + 1, 0);
  const bool parallel = nb >= 4;
#pragma omp parallel if (parallel)
  {
    std::vector<std::uint32_t> local(n, kNone);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t p = 0; p < nb; ++p) {
      const std::size_t p1 = std::min(n, (p + 1) * kBlock);
      std::vector<std::uint32_t>& out = outside_[p];
      out.clear();
      for (std::uint32_t k = start_[p * kBlock]; k < start_[p1]; ++k) {
        const std::uint32_t b = entry_[k] / 32;
        if (b >= p1 && local[b] == kNone)
          local[b] = 0, out.push_back(b);
      }
      for (std::uint32_t b : out)
        local[b] = kNone;
      std::sort(out.begin(), out.end());
      blockBase_[p + 1] = static_cast<std::uint32_t>(p1 - p * kBlock + out.size());
    }
#pragma omp single
    for (std::size_t p = 0; p < nb; ++p)
      blockBase_[p + 1] += blockBase_[p];
#pragma omp for schedule(dynamic, 1)
    for (std::size_t p = 0; p < nb; ++p) {
      const std::size_t p0 = p * kBlock, p1 = std::min(n, p0 + kBlock);
      const std::vector<std::uint32_t>& out = outside_[p];
      for (std::size_t k = 0; k < out.size(); ++k)
        local[out[k]] = static_cast<std::uint32_t>(blockBase_[p + 1] - out.size() + k);
      for (std::uint32_t k = start_[p0]; k < start_[p1]; ++k) {
        const std::uint32_t b = entry_[k] / 32;
        slot_[k] = b < p1 ? static_cast<std::uint32_t>(blockBase_[p] + b - p0) : local[b];
      }
      for (std::uint32_t b : out)
        local[b] = kNone;
    }
  }
  // Each particle's slots: those in earlier blocks (ascending), then its own.
  sumStart_.assign(n + 1, 0);
  for (std::size_t a = 0; a < n; ++a)
    sumStart_[a + 1] = 1;
  for (std::size_t p = 0; p < nb; ++p)
    for (std::uint32_t b : outside_[p])
      ++sumStart_[b + 1];
  for (std::size_t a = 0; a < n; ++a)
    sumStart_[a + 1] += sumStart_[a];
  sumSlot_.resize(sumStart_[n]);
  std::vector<std::uint32_t> fill(sumStart_.begin(), sumStart_.end() - 1);
  for (std::size_t p = 0; p < nb; ++p) {
    const std::size_t own = std::min(n, (p + 1) * kBlock) - p * kBlock;
    for (std::size_t k = 0; k < outside_[p].size(); ++k)
      sumSlot_[fill[outside_[p][k]]++] = static_cast<std::uint32_t>(blockBase_[p] + own + k);
  }
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t p = a / kBlock;
    sumSlot_[fill[a]++] = static_cast<std::uint32_t>(blockBase_[p] + a - p * kBlock);
  }
}

} // namespace craterkit

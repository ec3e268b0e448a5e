// The pair-once layout of the SPH neighbour list (docs/physics.md §2.2): each pair of the
// Verlet list once, and where its partner's share of the pair terms is summed.
//
// The symmetric pair terms of §2.2–2.3 (kernel gradient, artificial viscosity, the stress
// terms) are the same for (a, b) and (b, a) up to sign and the partner's mass, so each pair
// is evaluated once, from the particle of lower index (the owner). The owner sums its own
// share in registers; the partner's share is added into a slot. The particles are cut into
// fixed blocks of kBlock consecutive indices (independent of the thread count); each block
// has one slot for each of its particles and one for each outside partner of its owners, and
// is worked by one thread in index and list order. A particle's total is then its slots
// summed in a fixed order (the earlier blocks', ascending, then its own block's), so the rates
// are the same bits for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

class PairSlots {
public:
  static constexpr std::size_t kBlock = 256; // owners per block (fixed: the bits depend on it)

  // From a full list (CSR start, entries index * 32 + image code, each pair in both lists).
  // Keeps (a, b) in a's list when b > a, and of a particle's pairs with its own periodic images
  // the half with the image code below kSelf (the other half is the same pair seen from b).
  void build(const std::vector<std::uint32_t>& start, const std::vector<std::uint32_t>& entry,
             std::uint32_t kSelf);

  const std::vector<std::uint32_t>& start() const { return start_; } // CSR, size n+1
  const std::vector<std::uint32_t>& entry() const { return entry_; } // index * 32 + image code
  const std::vector<std::uint32_t>& slot() const { return slot_; }   // the partner's slot
  std::size_t blocks() const { return blockBase_.empty() ? 0 : blockBase_.size() - 1; }
  // The slots of block p: [blockBase(p), blockBase(p + 1)).
  std::uint32_t blockBase(std::size_t p) const { return blockBase_[p]; }
  std::size_t slots() const { return blockBase_.empty() ? 0 : blockBase_.back(); }
  // Particle a's slots in summing order, the last its own block's.
  const std::vector<std::uint32_t>& sumStart() const { return sumStart_; }
  const std::vector<std::uint32_t>& sumSlot() const { return sumSlot_; }
  std::uint32_t ownSlot(std::size_t a) const { return sumSlot_[sumStart_[a + 1] - 1]; }

private:
  std::vector<std::uint32_t> start_, entry_, slot_;
  std::vector<std::uint32_t> blockBase_;
  std::vector<std::uint32_t> sumStart_, sumSlot_;
  std::vector<std::vector<std::uint32_t>> outside_; // each block's partners beyond it, ascending
};

} // namespace craterkit

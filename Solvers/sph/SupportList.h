// The support list: each particle's Verlet-list entries (sph/NeighbourList.h) that lie within
// (1 + kSupportSkin) times their pair's support, drawn again only when they may no longer hold
// every pair inside the support. The pair terms' support pass (SphSolver.cpp) tests each entry
// it visits at every rate evaluation; the Verlet list's margin for motion and growth of h (a
// skin of 0.15 h or more, so about 1.7 listed entries per pair inside the support) is kept
// over many steps, the support list's thin skin over a few. Its entries are a subset of the
// Verlet list's in the same order and hold every pair inside the support, so the support pass
// keeps the same pairs in the same order: the rates are the same bits with or without it.
#pragma once

#include "sph/PairTerms.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace craterkit {

// The skin, as a fraction of the pair's support (benchmarks/JOURNAL.md, "Each pair once").
constexpr double kSupportSkin = 0.1;
constexpr std::size_t kSupportLife = 12, kSupportRest = 48; // rate evaluations

class SupportList {
public:
  // a's Verlet entries (index * 32 + image code) and their number.
  using Source =
      std::function<void(std::size_t a, const std::uint32_t*& entries, std::uint32_t& count)>;
  // Brings the list up to date for a rate evaluation at positions X: draws it again from
  // `source` where it was drawn from another Verlet list (`version` differs) or for other
  // particles, or where a particle has moved or its h has grown so far since the last draw that
  // an unlisted pair could be inside the support. `period`: the box lengths of the periodic
  // axes (0 where not periodic). Returns whether the pair terms are to use it: a list that had
  // to be drawn again after fewer than kSupportLife evaluations is not worth its draws (fast
  // particles, or Verlet lists rebuilt often), so the list then rests for kSupportRest
  // evaluations, in which the pair terms use the Verlet list.
  bool follow(const PairPosition* X, std::size_t n, std::size_t version, const double period[3],
              const Source& source);
  const std::uint32_t* entries(std::size_t a) const { return entry_.data() + start_[a]; }
  std::uint32_t count(std::size_t a) const { return count_[a]; }
  std::size_t draws() const { return draws_; }

private:
  bool holds(const PairPosition* X, std::size_t n) const;
  void draw(const PairPosition* X, std::size_t n, const double period[3], const Source& source);

  std::vector<std::size_t> start_; // each particle's first entry (room for all its Verlet entries)
  std::vector<std::uint32_t> count_, entry_;
  std::vector<PairPosition> ref_; // positions and h at the last draw
  std::size_t version_ = 0, draws_ = 0;
  std::size_t life_ = 0, rest_ = 0; // evaluations on the present draw; left to rest
  bool drawn_ = false;
};

} // namespace craterkit

// The DEM's half Verlet list (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012, §2.1:
// contacts are found among neighbours within a skin).
//
// Pairs i < j within r_i + r_j + skin, found with a cell list whose cells fit the ordinary
// particles (the few large ones, an impactor, searched apart), sorted by (i, j). A pair
// slot holds only its particles, a contact flag and, for a pair in contact, its row in the
// contact table (dem/ContactTable.h), which keeps the histories and results of the few pairs
// in contact: the pass that tests every listed pair reads 9 bytes a pair. The flags and rows
// are carried across rebuilds by merging each particle's old and new pairs (both sorted), so a
// rebuild never resets a spring. Each particle finds its pairs through firstStart (pairs where
// it is i, in order of j); secondStart counts the pairs where it is j and gives it slots for
// its rows as second member (dem/ParticleContacts.h), so that the force gather sums every
// particle's pairs in index order with no atomics: bit-identical for any thread count. Every
// pass of a build but two prefix sums over the particles runs on all threads.
#pragma once

#include "common/CellList.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

// Below this many particles a step is too short to amortise OpenMP's barriers (with more
// threads than cores they cost a time slice each): run serially. Results do not depend on it.
constexpr std::size_t kDemParallelMin = 512;

// Walks two pair lists sorted by (i, j) and calls same(a, b) for each pair in both; returns
// how many there were.
template <class Same> std::size_t forCommonPairs(const std::vector<std::uint32_t>& ai,
                                                 const std::vector<std::uint32_t>& aj,
                                                 const std::vector<std::uint32_t>& bi,
                                                 const std::vector<std::uint32_t>& bj,
                                                 Same&& same) {
  std::size_t found = 0;
  for (std::size_t a = 0, b = 0; a < ai.size() && b < bi.size();) {
    const auto ka = (static_cast<std::uint64_t>(ai[a]) << 32) | aj[a];
    const auto kb = (static_cast<std::uint64_t>(bi[b]) << 32) | bj[b];
    if (ka < kb) {
      ++a;
    } else if (kb < ka) {
      ++b;
    } else {
      same(a++, b++);
      ++found;
    }
  }
  return found;
}

struct PairList {
  std::vector<std::uint32_t> first, second; // the pair's particles, first < second
  std::vector<char> active;                 // in contact at the last force evaluation
  std::vector<std::uint32_t> row;           // of an active pair: its row in the contact table
  std::vector<std::size_t> firstStart;  // n + 1: pairs firstStart[i] .. firstStart[i+1]-1 have i
  std::vector<std::size_t> secondStart; // n + 1: prefix sums of the pairs where i is second

  std::size_t size() const { return first.size(); }

  // Rebuilds the list for n particles (positions x, radii r, largest radius rmax), keeping
  // the contact flag and table row of every pair that stays; new pairs start apart.
  void build(const double* x, const double* r, std::size_t n, double rmax, double skin);

  // Drops the pairs of removed particles and renumbers the rest (newIndex is increasing,
  // so the list stays sorted) and their table rows (newRow). secondStart needs a build()
  // afterwards.
  void removeParticles(const std::vector<char>& remove, const std::vector<std::uint32_t>& newIndex,
                       const std::vector<std::uint32_t>& newRow);

private:
  static constexpr std::size_t kChunk = 256; // particles a thread takes at a time
  bool placeChunks(std::size_t n, std::size_t team);
  void fillChunks(std::size_t chunks, std::size_t n);
  // The previous build's arrays, reused by the next one.
  std::vector<std::uint32_t> spareFirst_, spareSecond_;
  std::vector<char> spareActive_;
  std::vector<std::uint32_t> spareRow_;
  std::vector<std::size_t> spareStart_;
  CellList cells_, largeCells_; // every particle on cells of the ordinary ones; the many large
  // Per thread: the second members it found, and how often each particle was one.
  std::vector<std::vector<std::uint32_t>> found_, secondCounts_;
  // Per chunk of kChunk particles: the thread that searched it and where in its buffer.
  std::vector<std::uint32_t> chunkThread_;
  std::vector<std::size_t> chunkOffset_;
};

} // namespace craterkit

#include "dem/PairList.h"

#include "common/CountingIndex.h"
#include "common/GrowFresh.h"
#include "common/OpenMP.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace craterkit {

void PairList::build(const double* x, const double* r, std::size_t n, double rmax, double skin) {
  // Cells fit the ordinary particles (common/CellList.h, sizeClasses); each particle finds its
  // ordinary neighbours on them (reach r_i + the largest ordinary radius + skin) and tests the
  // few large ones (an impactor) itself, or, beyond kDirectLarge of them, finds them on cells
  // of their own (reach r_i + rmax + skin): one big sphere makes no cell, and no other
  // particle's search, larger. Every pair i < j within reach is found by i, as before.
  constexpr std::size_t kDirectLarge = 64;
  const SizeClasses sizes = sizeClasses(r, n);
  const double rsmall = sizes.large ? sizes.ordinaryMax : rmax;
  std::vector<std::uint32_t> large;
  std::vector<char> isLarge(sizes.large ? n : 0, 0);
  if (sizes.large) {
    large.reserve(sizes.large);
    for (std::size_t i = 0; i < n; ++i)
      if (sizes.isLarge(r[i])) {
        large.push_back(static_cast<std::uint32_t>(i));
        isLarge[i] = 1;
      }
  }
  const bool largeOnCells = large.size() > kDirectLarge;
  if (largeOnCells) {
    std::vector<double> at(3 * large.size());
    for (std::size_t k = 0; k < large.size(); ++k)
      for (int a = 0; a < 3; ++a)
        at[3 * k + a] = x[3 * large[k] + a];
    largeCells_.build(at.data(), large.size(), 2.0 * rmax + skin);
  }
  CellList& cells = cells_; // kept: its arrays keep their memory from build to build
  cells.build(x, n, 2.0 * rsmall + skin);
  // Calls f(j) for every j > i within reach of i.
  auto forEachNeighbour = [&](std::size_t i, auto&& f) {
    auto test = [&](std::size_t j) {
      const double reach = r[i] + r[j] + skin;
      const double d0 = x[3 * j] - x[3 * i], d1 = x[3 * j + 1] - x[3 * i + 1],
                   d2 = x[3 * j + 2] - x[3 * i + 2];
      if (d0 * d0 + d1 * d1 + d2 * d2 < reach * reach)
        f(j);
    };
    if (large.empty()) {
      cells.forEachCandidate(&x[3 * i], r[i] + rmax + skin, [&](std::size_t j) {
        if (j > i)
          test(j);
      });
      return;
    }
    cells.forEachCandidate(&x[3 * i], r[i] + rsmall + skin, [&](std::size_t j) {
      if (j > i && !isLarge[j])
        test(j);
    });
    if (!largeOnCells) {
      for (std::uint32_t b : large)
        if (b > i)
          test(b);
      return;
    }
    largeCells_.forEachCandidate(&x[3 * i], r[i] + rmax + skin, [&](std::size_t k) {
      if (large[k] > i)
        test(large[k]);
    });
  };
  // One search per particle (no counting pass): each thread appends the pairs of the chunks
  // it takes to its own buffer and counts each particle's second members; then the counts
  // become the offsets (serially, one pass over the particles) and every chunk is copied to
  // its place and merged with the old list's pairs of the same first members.
  const bool parallel = n >= kDemParallelMin;
#ifdef _OPENMP
  const std::size_t most =
      parallel ? static_cast<std::size_t>(std::max(1, omp_get_max_threads())) : 1;
#else
  const std::size_t most = 1;
#endif
  if (found_.size() < most) {
    found_.resize(most);
    secondCounts_.resize(most);
  }
  if (!first.empty() && firstStart.size() != n + 1)
    throw std::logic_error("PairList::build: the old list has no per-particle index");
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  chunkThread_.resize(chunks);
  chunkOffset_.resize(chunks);
  std::vector<std::size_t>& start = spareStart_;
  start.resize(n + 1);
  start[0] = 0;
  secondStart.resize(n + 1);
  secondStart[0] = 0;
  bool tooMany = false;
#pragma omp parallel if (parallel)
  {
    const std::size_t me = static_cast<std::size_t>(threadNumber());
    const std::size_t team = static_cast<std::size_t>(threadCount());
    std::vector<std::uint32_t>& buffer = found_[me];
    std::vector<std::uint32_t>& seconds = secondCounts_[me];
    buffer.clear();
    seconds.assign(n, 0);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t c = 0; c < chunks; ++c) {
      chunkThread_[c] = static_cast<std::uint32_t>(me);
      chunkOffset_[c] = buffer.size();
      for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
        const std::size_t b = buffer.size();
        forEachNeighbour(i, [&](std::size_t j) {
          buffer.push_back(static_cast<std::uint32_t>(j));
          ++seconds[j];
        });
        std::sort(buffer.begin() + b, buffer.end());
        start[i + 1] = buffer.size() - b;
      }
    }
#pragma omp single
    tooMany = !placeChunks(n, team);
    if (!tooMany)
      fillChunks(chunks, n);
  }
  if (tooMany)
    throw std::runtime_error("the DEM neighbour list has more than 2^32 - 1 pairs");
  first.swap(spareFirst_);
  second.swap(spareSecond_);
  active.swap(spareActive_);
  row.swap(spareRow_);
  firstStart.swap(start);
}

// Serially, after the search: each particle's first pair and its slots as second member
// (prefix sums of the counts), and the new list's buffers sized. False if the list has more
// pairs than a row number can hold.
bool PairList::placeChunks(std::size_t n, std::size_t team) {
  std::vector<std::size_t>& start = spareStart_;
  for (std::size_t i = 0; i < n; ++i) {
    start[i + 1] += start[i];
    std::size_t s = 0;
    for (std::size_t t = 0; t < team; ++t)
      s += secondCounts_[t][i];
    secondStart[i + 1] = secondStart[i] + s;
  }
  if (start[n] > std::numeric_limits<std::uint32_t>::max()) // secondRow and the table rows
    return false;
  // The new list goes into the spare buffers of the last build, which keep their memory:
  // fresh allocations of this size would cost a page fault per 4 kB at every rebuild.
  growFresh(spareFirst_, start[n]);
  growFresh(spareSecond_, start[n]);
  growFresh(spareActive_, start[n]);
  growFresh(spareRow_, start[n]);
  return true;
}

// Copies each chunk's pairs from its thread's buffer to their place in the new list and
// carries the contact flags and table rows of the pairs that stay (each particle's old and
// new pairs are both sorted by second member): the histories stay in the table. Every other
// slot starts apart. On every thread of the build's team.
void PairList::fillChunks(std::size_t chunks, std::size_t n) {
  const std::vector<std::size_t>& start = spareStart_;
  const bool carry = !first.empty();
#pragma omp for schedule(dynamic, 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::uint32_t* from = found_[chunkThread_[c]].data() + chunkOffset_[c];
    for (std::size_t i = c * kChunk, e = std::min(n, i + kChunk); i < e; ++i) {
      std::size_t o = carry ? firstStart[i] : 0;
      const std::size_t oEnd = carry ? firstStart[i + 1] : 0;
      for (std::size_t k = start[i]; k < start[i + 1]; ++k) {
        const std::uint32_t j = *from++;
        spareFirst_[k] = static_cast<std::uint32_t>(i);
        spareSecond_[k] = j;
        while (o < oEnd && second[o] < j)
          ++o;
        const bool same = o < oEnd && second[o] == j;
        spareActive_[k] = same ? active[o] : 0;
        spareRow_[k] = same ? row[o] : 0;
      }
    }
  }
}

void PairList::removeParticles(const std::vector<char>& remove,
                               const std::vector<std::uint32_t>& newIndex,
                               const std::vector<std::uint32_t>& newRow) {
  std::size_t o = 0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    if (remove[first[k]] || remove[second[k]])
      continue;
    first[o] = newIndex[first[k]];
    second[o] = newIndex[second[k]];
    active[o] = active[k];
    row[o] = active[k] ? newRow[row[k]] : 0;
    ++o;
  }
  first.resize(o);
  second.resize(o);
  active.resize(o);
  row.resize(o);
  // The next build carries the flags by first member: index the renumbered list.
  indexByKey(firstStart, first, o, keptCount(remove));
}

} // namespace craterkit

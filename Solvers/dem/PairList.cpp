#include "dem/PairList.h"

#include "common/CellList.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace craterkit {

void PairList::build(const double* x, const double* r, std::size_t n, double rmax, double skin) {
  // Cells fit the ordinary particles; a few much larger ones (an impactor) search a wider
  // range themselves and every other particle checks them directly, so one big sphere does
  // not make every cell (and every search) eight times larger.
  const double rmin = n ? *std::min_element(r, r + n) : 0.0;
  std::vector<std::uint32_t> large;
  double rsmall = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (r[i] > 1.5 * rmin)
      large.push_back(static_cast<std::uint32_t>(i));
    else
      rsmall = std::max(rsmall, r[i]);
  }
  if (large.size() > 64) {
    large.clear();
    rsmall = rmax;
  }
  std::vector<char> isLarge(large.empty() ? 0 : n, 0);
  for (std::uint32_t b : large)
    isLarge[b] = 1;
  CellList cells;
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
    for (std::uint32_t b : large)
      if (b > i)
        test(b);
  };
  std::vector<std::size_t> count(n + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) if (n >= kDemParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t c = 0;
    forEachNeighbour(i, [&](std::size_t) { ++c; });
    count[i + 1] = c;
  }
  std::vector<std::size_t> start(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
    start[i + 1] = start[i] + count[i + 1];
  const std::size_t pairs = start[n];
  if (pairs > std::numeric_limits<std::uint32_t>::max()) // secondPair and the table rows
    throw std::runtime_error("the DEM neighbour list has more than 2^32 - 1 pairs");
  // The new list goes into the spare buffers of the last build, which keep their memory:
  // fresh allocations of this size would cost a page fault per 4 kB at every rebuild.
  std::vector<std::uint32_t>&newI = spareFirst_, &newJ = spareSecond_;
  newI.resize(pairs);
  newJ.resize(pairs);
#pragma omp parallel if (n >= kDemParallelMin)
  {
    std::vector<std::uint32_t> buffer;
#pragma omp for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
      buffer.clear();
      forEachNeighbour(i, [&](std::size_t j) { buffer.push_back(static_cast<std::uint32_t>(j)); });
      std::sort(buffer.begin(), buffer.end());
      std::copy(buffer.begin(), buffer.end(), newJ.begin() + start[i]);
      std::fill(newI.begin() + start[i], newI.begin() + start[i + 1],
                static_cast<std::uint32_t>(i));
    }
  }
  // Carry the contact flags and table rows of pairs that stay in the list (both lists sorted
  // by (i, j)): the histories stay in the table. Every other slot starts apart. Each new slot
  // is written once.
  std::vector<char>& newActive = spareActive_;
  std::vector<std::uint32_t>& newRow = spareRow_;
  newActive.resize(pairs);
  newRow.resize(pairs);
  std::size_t b = 0;
  forCommonPairs(first, second, newI, newJ, [&](std::size_t a, std::size_t same) {
    for (; b < same; ++b)
      newActive[b] = 0;
    newActive[b] = active[a];
    newRow[b] = row[a];
    ++b;
  });
  for (; b < pairs; ++b)
    newActive[b] = 0;
  first.swap(newI);
  second.swap(newJ);
  active.swap(newActive);
  row.swap(newRow);
  firstStart.swap(start);
  // Pairs in which each particle is the second member, in increasing order of the first.
  secondStart.assign(n + 1, 0);
  for (std::size_t k = 0; k < pairs; ++k)
    ++secondStart[second[k] + 1];
  for (std::size_t i = 0; i < n; ++i)
    secondStart[i + 1] += secondStart[i];
  secondPair.resize(pairs);
  std::vector<std::size_t> fill(secondStart.begin(), secondStart.end() - 1);
  for (std::size_t k = 0; k < pairs; ++k)
    secondPair[fill[second[k]]++] = static_cast<std::uint32_t>(k);
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
}

} // namespace craterkit

// The index of a list whose entries are sorted by a key (a particle's number): a counting sort's
// prefix sums, so that entries start[k] .. start[k+1]-1 are those with key k. CraterKit's DEM
// tables rebuild theirs this way after grains are removed and the rest renumbered.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace craterkit {

// The number of items a removal mask keeps (its zero entries).
inline std::size_t keptCount(const std::vector<char>& remove) {
  return static_cast<std::size_t>(std::count(remove.begin(), remove.end(), 0));
}

// start (keys + 1 entries) indexes the first `entries` items of `key`, each below `keys`.
template <class Keys> void indexByKey(std::vector<std::size_t>& start, const Keys& key,
                                      std::size_t entries, std::size_t keys) {
  start.assign(keys + 1, 0);
  for (std::size_t e = 0; e < entries; ++e)
    ++start[key[e] + 1];
  for (std::size_t k = 0; k < keys; ++k)
    start[k + 1] += start[k];
}

} // namespace craterkit

// Brute-force oracle shared by the fragment tests: the connected components of n items under a
// pair predicate, by breadth-first search over all pairs (O(n²): small test sets only). Each
// component is numbered in the order of its first member.
#pragma once

#include <cstddef>
#include <queue>
#include <vector>

template <class Linked> std::vector<int> componentsOracle(std::size_t n, Linked&& linked) {
  std::vector<int> comp(n, -1);
  int next = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (comp[s] >= 0)
      continue;
    std::queue<std::size_t> q;
    q.push(s);
    comp[s] = next;
    while (!q.empty()) {
      const std::size_t a = q.front();
      q.pop();
      for (std::size_t b = 0; b < n; ++b)
        if (comp[b] < 0 && linked(a, b))
          comp[b] = next, q.push(b);
    }
    ++next;
  }
  return comp;
}

#include "dem/ParticleContacts.h"

#include <algorithm>

namespace craterkit {

void ParticleContacts::resize(std::size_t n, std::size_t pairs) {
  firstBegin.resize(n);
  firstCount.resize(n);
  secondCount.resize(n);
  secondRow.resize(pairs);
}

void ParticleContacts::index(const ContactTable& table, const std::vector<std::size_t>& secondStart,
                             std::size_t lo, std::size_t hi, std::size_t rows) {
  std::fill(firstCount.begin() + lo, firstCount.begin() + hi, 0u);
  std::fill(secondCount.begin() + lo, secondCount.begin() + hi, 0u);
  const std::uint32_t *first = table.first.data(), *second = table.second.data();
  // The table is sorted by first member: the range's first members are one block of rows.
  const std::size_t begin = static_cast<std::size_t>(
      std::lower_bound(first, first + rows, static_cast<std::uint32_t>(lo)) - first);
  const std::size_t end = static_cast<std::size_t>(
      std::lower_bound(first, first + rows, static_cast<std::uint32_t>(hi)) - first);
  for (std::size_t c = begin; c < end; ++c)
    if (firstCount[first[c]]++ == 0)
      firstBegin[first[c]] = static_cast<std::uint32_t>(c);
  // The second members are in any order (though mostly near the first): the rows are looked
  // at in increasing order, so that each particle's list is in the order of its first members.
  // A second member of the range has a first member below hi: no row from `end` on has one.
  for (std::size_t c = 0; c < end; ++c) {
    const std::uint32_t j = second[c];
    if (j >= lo && j < hi)
      secondRow[secondStart[j] + secondCount[j]++] = static_cast<std::uint32_t>(c);
  }
}

} // namespace craterkit

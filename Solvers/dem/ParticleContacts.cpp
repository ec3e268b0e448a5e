#include "dem/ParticleContacts.h"

#include <algorithm>

namespace craterkit {

void ParticleContacts::resize(std::size_t n, std::size_t pairs) {
  firstBegin.resize(n);
  firstCount.resize(n);
  secondCount.resize(n);
  secondRow.resize(pairs);
}

void ParticleContacts::indexOwnRows(const ContactTable& table,
                                    const std::vector<std::size_t>& secondStart, std::size_t lo,
                                    std::size_t hi, std::size_t rowBegin, std::size_t rowEnd,
                                    const std::uint64_t* shared, std::uint64_t stamp) {
  std::fill(firstCount.begin() + lo, firstCount.begin() + hi, 0u);
  std::fill(secondCount.begin() + lo, secondCount.begin() + hi, 0u);
  const std::uint32_t *first = table.first.data(), *second = table.second.data();
  for (std::size_t c = rowBegin; c < rowEnd; ++c) {
    if (firstCount[first[c]]++ == 0)
      firstBegin[first[c]] = static_cast<std::uint32_t>(c);
    const std::uint32_t j = second[c];
    if (j < hi && (!shared || shared[j] != stamp)) // j > first[c] >= lo
      secondRow[secondStart[j] + secondCount[j]++] = static_cast<std::uint32_t>(c);
  }
}

void ParticleContacts::indexSharedRows(const ContactTable& table,
                                       const std::vector<std::size_t>& secondStart, std::size_t lo,
                                       std::size_t hi, std::size_t rowEnd,
                                       const std::uint64_t* shared, std::uint64_t stamp) {
  const std::uint32_t* second = table.second.data();
  for (std::size_t c = 0; c < rowEnd; ++c) { // in row order, as indexOwnRows does
    const std::uint32_t j = second[c];
    if (j >= lo && j < hi && shared[j] == stamp)
      secondRow[secondStart[j] + secondCount[j]++] = static_cast<std::uint32_t>(c);
  }
}

} // namespace craterkit

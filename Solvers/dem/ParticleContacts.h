// Each particle's rows of the DEM's contact table (dem/ContactTable.h), rebuilt every step, so
// that the force gather (pkdgrav SSDEM; Schwartz, Richardson & Michel 2012, §2.3: F_i is the
// sum over i's contacts) visits only the pairs in contact.
//
// A bed lists about ten pairs per particle and has about one in contact: walking the pair
// list and skipping the others cost a load and a hard-to-predict branch per listed pair.
// The rows where i is the first member are contiguous (the table is in the order of the pair
// list); those where it is the second are collected in the slots the pair list keeps for i's
// pairs as second member (PairList::secondStart), in the order of the table, that is of the
// first member. Both orders are those of the pair list, so the sums are bit for bit the same.
#pragma once

#include "dem/ContactTable.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace craterkit {

struct ParticleContacts {
  // Rows firstBegin[i] .. firstBegin[i] + firstCount[i] - 1 have i as first member; rows
  // secondRow[secondStart[i] + q], q < secondCount[i], have it as second.
  std::vector<std::uint32_t> firstBegin, firstCount, secondCount, secondRow;

  // Sizes the arrays for n particles and a pair list of `pairs` slots (once, before indexing).
  void resize(std::size_t n, std::size_t pairs);
  // Indexes the rows of `table` for the particles [lo, hi), in two parts: called by every
  // thread of a team for its own range (the one it then gathers), the ranges together covering
  // all particles. The threads write their rows in thread order, each the rows of the first
  // members of its range: rows [rowBegin, rowEnd). A particle of the range that is the second
  // member of a row written by an earlier thread is shared (shared[j] == stamp; a superset will
  // do; the first thread passes no marks: it has no earlier thread). indexOwnRows indexes every
  // first member and the second members that are not shared (all their rows are the thread's own)
  // as soon as the thread has written its rows; indexSharedRows then the shared ones, from all rows
  // below rowEnd, once the earlier threads have written theirs.
  void indexOwnRows(const ContactTable& table, const std::vector<std::size_t>& secondStart,
                    std::size_t lo, std::size_t hi, std::size_t rowBegin, std::size_t rowEnd,
                    const std::uint64_t* shared, std::uint64_t stamp);
  void indexSharedRows(const ContactTable& table, const std::vector<std::size_t>& secondStart,
                       std::size_t lo, std::size_t hi, std::size_t rowEnd,
                       const std::uint64_t* shared, std::uint64_t stamp);
};

} // namespace craterkit

// Sizing a buffer that is about to be overwritten whole (CraterKit's DEM contact table and pair
// list): no copy of the old contents, and room for a quarter more.
#pragma once

#include <cstddef>
#include <vector>

namespace craterkit {

// Grows v to count items without copying its contents (the items are written afterwards), with
// room for a quarter more: the contacts of an impact grow step by step, a growing vector copies
// itself, and the buffer is sized by one thread while the others wait, each fresh page costing
// a fault.
template <class T> void growFresh(std::vector<T>& v, std::size_t count) {
  if (v.capacity() < count) {
    v.clear();
    v.reserve(count + count / 4);
  }
  v.resize(count);
}

} // namespace craterkit

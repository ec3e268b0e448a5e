// Sizing a buffer that is about to be overwritten whole (CraterKit's DEM contact table and pair
// list): no copy of the old contents, and room for a quarter more; and a vector whose new items
// are left unwritten (FreshVector), so that the threads that fill it touch its pages first.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace craterkit {

// Grows v to count items without copying its contents (the items are written afterwards), with
// room for a quarter more: the contacts of an impact grow step by step, a growing vector copies
// itself, and the buffer is sized by one thread while the others wait, each fresh page costing
// a fault.
template <class T, class A> void growFresh(std::vector<T, A>& v, std::size_t count) {
  if (v.capacity() < count) {
    v.clear();
    v.reserve(count + count / 4);
  }
  v.resize(count);
}

// An allocator whose value-initialisation (resize(n), the growth of growFresh) is a default
// initialisation: a new double or integer is left unwritten instead of zeroed. A buffer sized by
// one thread and filled by all is then neither zeroed by that thread while the others wait nor
// paged in by it: the first write to a fresh page faults it in on the thread that writes it
// (Linux maps anonymous memory on first touch), in the parallel fill. resize(n, value) and
// assign still write what they are given.
template <class T> struct FreshAllocator : std::allocator<T> {
  template <class U> struct rebind { using other = FreshAllocator<U>; };
  FreshAllocator() = default;
  template <class U> FreshAllocator(const FreshAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args> void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T> using FreshVector = std::vector<T, FreshAllocator<T>>;

} // namespace craterkit

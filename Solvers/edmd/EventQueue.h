// Future-event queue for event-driven MD: at most one pending event per disk, earliest first.
//
// A bounded priority queue after Paul (2007, J. Comput. Phys. 221:615), as DynamO uses it:
// time is cut into buckets of equal width; a ring of buckets covering the near future holds
// unsorted lists, later events wait in an overflow list, and only the current bucket is kept
// sorted, in a small binary heap. The bucket width adapts: it is quartered or quadrupled
// whenever a turn of the ring sees far more or far fewer events than buckets.
//
// The lists hold the events themselves, not disk indices, and nothing is ever unlinked: a
// disk's new event is appended with the disk's next generation number, and an entry whose
// generation is no longer the disk's is dropped when it is reached. Scheduling is an append,
// draining a bucket a sequential read, and the heap compares times it holds, so the queue
// touches no other disk's record (the doubly linked lists it replaced missed the cache on
// both neighbours of every disk they moved).
//
// Ordering is exact: the earliest time wins, ties go to the lower disk index. Payload is any
// event type with a member `double t`.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace craterkit {

template <class Payload> class EventQueue {
public:
  struct Item {
    Payload event;
    std::uint32_t disk, gen;
  };

  // n disks without events at time `now`.
  void reset(std::size_t n, double now) {
    gen_.assign(n, 0);
    buckets_ = 64;
    while (buckets_ < n)
      buckets_ *= 2;
    head_.assign(buckets_, -1);
    pool_.clear();
    free_ = -1;
    waiting_.clear();
    heap_.clear();
    listed_ = 0;
    width_ = 1.0;
    current_ = bucketOf(now);
    turnStart_ = current_;
    popped_ = 0;
  }

  // Sizes the buckets from the pending events: about two per bucket over their mean horizon.
  void tune(double now) {
    double sum = 0.0;
    std::size_t count = 0;
    forEachValid([&](const Item& it) {
      sum += it.event.t - now;
      ++count;
    });
    const double horizon = count ? std::max(sum / static_cast<double>(count), 1e-300) * 4.0 : 1.0;
    rebuild(horizon / static_cast<double>(buckets_), now);
  }

  // Disk i's next event is e (e.t infinite: none); its previous one is void.
  void update(std::size_t i, const Payload& e) {
    const std::uint32_t g = ++gen_[i];
    if (e.t < kInf)
      insert(Item{e, static_cast<std::uint32_t>(i), g});
  }

  // The earliest event, or nullptr if there is none. Valid until the next call of any member.
  const Item* top() {
    while (true) {
      while (!heap_.empty()) {
        if (valid(heap_.front()))
          return &heap_.front();
        heapPop();
      }
      if (listed_ == 0) {
        // Nothing in the ring: jump to the earliest waiting event, if any is still valid.
        double tmin = kInf;
        for (const Item& it : waiting_)
          if (valid(it))
            tmin = std::min(tmin, it.event.t);
        if (!(tmin < kInf)) {
          waiting_.clear();
          return nullptr;
        }
        current_ = bucketOf(tmin) - 1;
        turnStart_ = current_;
        refill();
        continue;
      }
      ++current_;
      if (current_ - turnStart_ >= static_cast<std::int64_t>(buckets_)) {
        // A full turn of the ring: adapt the width, let waiting events in.
        const std::uint64_t seen = popped_;
        popped_ = 0;
        turnStart_ = current_;
        if (seen > 16 * buckets_ || seen * 8 < buckets_) {
          rebuild(width_ * (seen > 16 * buckets_ ? 0.25 : 4.0), static_cast<double>(current_) * width_);
          continue;
        }
        refill();
      }
      // The current bucket's valid events go into the heap.
      std::int32_t& head = head_[slotOf(current_)];
      for (std::int32_t k = head; k >= 0;) {
        Node& node = pool_[static_cast<std::size_t>(k)];
        const std::int32_t following = node.next;
        if (valid(node.item))
          heapPush(node.item);
        node.next = free_;
        free_ = k;
        --listed_;
        k = following;
      }
      head = -1;
    }
  }

  // Removes the event top() returned.
  void pop() {
    heapPop();
    ++popped_;
  }

private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  bool valid(const Item& it) const { return gen_[it.disk] == it.gen; }

  std::int64_t bucketOf(double t) const {
    const double b = std::floor(t / width_);
    return b > 4e18 ? std::numeric_limits<std::int64_t>::max() / 2 : static_cast<std::int64_t>(b);
  }
  std::size_t slotOf(std::int64_t b) const {
    return static_cast<std::size_t>(b & static_cast<std::int64_t>(buckets_ - 1)); // buckets_ is a power of 2
  }

  template <class F> void forEachValid(F&& f) const {
    for (const Item& it : heap_)
      if (valid(it))
        f(it);
    for (std::int32_t h : head_)
      for (std::int32_t k = h; k >= 0; k = pool_[static_cast<std::size_t>(k)].next)
        if (valid(pool_[static_cast<std::size_t>(k)].item))
          f(pool_[static_cast<std::size_t>(k)].item);
    for (const Item& it : waiting_)
      if (valid(it))
        f(it);
  }

  void rebuild(double width, double now) {
    std::vector<Item> all;
    forEachValid([&](const Item& it) { all.push_back(it); });
    width_ = width;
    current_ = bucketOf(now);
    turnStart_ = current_;
    popped_ = 0;
    head_.assign(buckets_, -1);
    pool_.clear();
    free_ = -1;
    waiting_.clear();
    heap_.clear();
    listed_ = 0;
    for (const Item& it : all)
      insert(it);
  }

  // Waiting events that are now within the ring move into it; void ones are dropped.
  void refill() {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < waiting_.size(); ++k) {
      const Item it = waiting_[k];
      if (!valid(it))
        continue;
      if (bucketOf(it.event.t) < current_ + static_cast<std::int64_t>(buckets_))
        insert(it);
      else
        waiting_[kept++] = it;
    }
    waiting_.resize(kept);
  }

  void insert(const Item& it) {
    const std::int64_t b = bucketOf(it.event.t);
    if (b <= current_) {
      heapPush(it);
    } else if (b < current_ + static_cast<std::int64_t>(buckets_)) {
      std::int32_t k = free_;
      if (k >= 0) {
        free_ = pool_[static_cast<std::size_t>(k)].next;
      } else {
        k = static_cast<std::int32_t>(pool_.size());
        pool_.emplace_back();
      }
      std::int32_t& head = head_[slotOf(b)];
      pool_[static_cast<std::size_t>(k)] = Node{it, head};
      head = k;
      ++listed_;
    } else {
      waiting_.push_back(it);
    }
  }

  // A min-heap on (time, disk).
  static bool later(const Item& a, const Item& b) {
    return a.event.t > b.event.t || (a.event.t == b.event.t && a.disk > b.disk);
  }
  void heapPush(const Item& it) {
    heap_.push_back(it);
    std::push_heap(heap_.begin(), heap_.end(), later);
  }
  void heapPop() {
    std::pop_heap(heap_.begin(), heap_.end(), later);
    heap_.pop_back();
  }

  std::size_t buckets_ = 64, listed_ = 0;
  double width_ = 1.0;
  std::int64_t current_ = 0, turnStart_ = 0;
  std::uint64_t popped_ = 0;
  std::vector<std::uint32_t> gen_;
  // The ring's lists: singly linked nodes in a pool with a free list (recently freed nodes,
  // still in cache, are reused first).
  struct Node {
    Item item;
    std::int32_t next;
  };
  std::vector<Node> pool_;
  std::int32_t free_ = -1;
  std::vector<std::int32_t> head_;
  std::vector<Item> waiting_; // beyond the ring
  std::vector<Item> heap_;
};

} // namespace craterkit

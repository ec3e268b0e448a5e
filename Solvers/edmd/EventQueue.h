// Future-event queue for event-driven MD: one pending event time per disk, the earliest first.
//
// A bounded priority queue after Paul (2007, J. Comput. Phys. 221:615), as DynamO uses it:
// time is cut into buckets of equal width; a ring of buckets covering the near future holds
// unsorted doubly linked lists, later events wait in an overflow list, and only the current
// bucket is kept sorted, in a small binary heap. Scheduling an event is O(1) and touches a
// few cache lines, where a binary tree over all disks walks log2 N of them. The bucket width
// adapts: it is halved or doubled whenever a turn of the ring sees far more or far fewer
// events than buckets.
//
// Ordering is exact: the earliest time wins, ties go to the lower disk index.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace craterkit {

class EventQueue {
public:
  // n disks, their event times (infinity: none), and the current time.
  void reset(std::size_t n, const double* times, double now) {
    n_ = n;
    e_.assign(n, Entry{});
    for (std::size_t i = 0; i < n; ++i)
      e_[i].key = times[i];
    // Width: events spread over their mean horizon, about two per bucket.
    double sum = 0.0;
    std::size_t finite = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (e_[i].key < kInf) {
        sum += e_[i].key - now;
        ++finite;
      }
    buckets_ = 64;
    while (buckets_ < n)
      buckets_ *= 2;
    const double horizon = finite ? std::max(sum / finite, 1e-300) * 4.0 : 1.0;
    rebuild(horizon / buckets_, now);
  }

  // Disk i's event moved to time t.
  void update(std::size_t i, double t) {
    remove(i);
    e_[i].key = t;
    insert(i);
  }

  // The disk with the earliest event, or n if there is none.
  std::size_t top() {
    while (heap_.empty()) {
      if (listed_ == 0) {
        if (overflow_ == 0)
          return n_;
        // Nothing in the ring: jump to the earliest waiting event.
        double tmin = kInf;
        for (std::int32_t k = head_[buckets_]; k >= 0; k = e_[k].next)
          tmin = std::min(tmin, e_[k].key);
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
          const double factor = seen > 16 * buckets_ ? 0.25 : 4.0;
          rebuild(width_ * factor, static_cast<double>(current_) * width_);
          continue;
        }
        refill();
      }
      // Move the current bucket's list into the heap.
      const std::size_t slot = static_cast<std::size_t>(current_ % static_cast<std::int64_t>(buckets_));
      for (std::int32_t k = head_[slot]; k >= 0;) {
        const std::int32_t following = e_[k].next;
        e_[k].where = kNowhere;
        --listed_;
        heapPush(static_cast<std::size_t>(k));
        k = following;
      }
      head_[slot] = -1;
    }
    return heap_[0];
  }

  // Call after the event of top() has been taken (for the width adaptation).
  void countPop() { ++popped_; }

private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr std::int32_t kNowhere = -3, kHeap = -2;

  std::int64_t bucketOf(double t) const {
    const double b = std::floor(t / width_);
    return b > 4e18 ? std::numeric_limits<std::int64_t>::max() / 2 : static_cast<std::int64_t>(b);
  }

  void rebuild(double width, double now) {
    width_ = width;
    current_ = bucketOf(now);
    turnStart_ = current_;
    popped_ = 0;
    head_.assign(buckets_ + 1, -1); // the last list is the overflow
    heap_.clear();
    listed_ = overflow_ = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      e_[i].where = kNowhere;
      e_[i].heapPos = -1;
    }
    for (std::size_t i = 0; i < n_; ++i)
      insert(i);
  }

  // Waiting events that are now within the ring move into it.
  void refill() {
    for (std::int32_t k = head_[buckets_]; k >= 0;) {
      const std::int32_t following = e_[k].next;
      if (bucketOf(e_[k].key) < current_ + static_cast<std::int64_t>(buckets_)) {
        unlink(static_cast<std::size_t>(k));
        --overflow_;
        insert(static_cast<std::size_t>(k));
      }
      k = following;
    }
  }

  void insert(std::size_t i) {
    const double t = e_[i].key;
    if (!(t < kInf))
      return;
    const std::int64_t b = bucketOf(t);
    if (b <= current_) {
      heapPush(i);
    } else if (b < current_ + static_cast<std::int64_t>(buckets_)) {
      link(i, static_cast<std::size_t>(b % static_cast<std::int64_t>(buckets_)));
      ++listed_;
    } else {
      link(i, buckets_);
      ++overflow_;
    }
  }

  void remove(std::size_t i) {
    const std::int32_t w = e_[i].where;
    if (w == kNowhere)
      return;
    if (w == kHeap) {
      heapErase(i);
      return;
    }
    unlink(i);
    if (static_cast<std::size_t>(w) == buckets_)
      --overflow_;
    else
      --listed_;
  }

  void link(std::size_t i, std::size_t slot) {
    e_[i].where = static_cast<std::int32_t>(slot);
    e_[i].prev = -1;
    e_[i].next = head_[slot];
    if (head_[slot] >= 0)
      e_[head_[slot]].prev = static_cast<std::int32_t>(i);
    head_[slot] = static_cast<std::int32_t>(i);
  }

  void unlink(std::size_t i) {
    const std::int32_t p = e_[i].prev, q = e_[i].next;
    if (p >= 0)
      e_[p].next = q;
    else
      head_[static_cast<std::size_t>(e_[i].where)] = q;
    if (q >= 0)
      e_[q].prev = p;
    e_[i].where = kNowhere;
  }

  bool before(std::uint32_t a, std::uint32_t b) const {
    return e_[a].key < e_[b].key || (e_[a].key == e_[b].key && a < b);
  }
  void place(std::size_t pos, std::uint32_t i) {
    heap_[pos] = i;
    e_[i].heapPos = static_cast<std::int32_t>(pos);
  }
  void heapPush(std::size_t i) {
    e_[i].where = kHeap;
    heap_.push_back(static_cast<std::uint32_t>(i));
    siftUp(heap_.size() - 1);
  }
  void heapErase(std::size_t i) {
    const std::size_t pos = static_cast<std::size_t>(e_[i].heapPos);
    const std::uint32_t last = heap_.back();
    heap_.pop_back();
    e_[i].where = kNowhere;
    e_[i].heapPos = -1;
    if (pos < heap_.size()) {
      place(pos, last);
      siftUp(pos);
      siftDown(static_cast<std::size_t>(e_[last].heapPos));
    }
  }
  void siftUp(std::size_t pos) {
    const std::uint32_t i = heap_[pos];
    while (pos > 0) {
      const std::size_t parent = (pos - 1) / 2;
      if (!before(i, heap_[parent]))
        break;
      place(pos, heap_[parent]);
      pos = parent;
    }
    place(pos, i);
  }
  void siftDown(std::size_t pos) {
    const std::uint32_t i = heap_[pos];
    const std::size_t size = heap_.size();
    while (true) {
      std::size_t child = 2 * pos + 1;
      if (child >= size)
        break;
      if (child + 1 < size && before(heap_[child + 1], heap_[child]))
        ++child;
      if (!before(heap_[child], i))
        break;
      place(pos, heap_[child]);
      pos = child;
    }
    place(pos, i);
  }

  std::size_t n_ = 0, buckets_ = 64;
  double width_ = 1.0;
  std::int64_t current_ = 0, turnStart_ = 0;
  std::uint64_t popped_ = 0;
  std::size_t listed_ = 0, overflow_ = 0;
  // Everything the queue keeps per disk, in one place (one cache miss per disk touched).
  struct Entry {
    double key = kInf;
    std::int32_t prev = -1, next = -1, where = kNowhere, heapPos = -1;
  };
  std::vector<Entry> e_;
  std::vector<std::int32_t> head_;
  std::vector<std::uint32_t> heap_;
};

} // namespace craterkit

// Future-event queue for event-driven MD: at most one pending event per disk, earliest first.
//
// A bounded priority queue after Paul (2007, J. Comput. Phys. 221:615), as DynamO uses it:
// time is cut into buckets of equal width; a ring of buckets covering the near future holds
// unsorted events, later events wait in an overflow list, and only the current bucket is kept
// sorted, in a small binary heap. The bucket width adapts: it is quartered or quadrupled
// whenever a turn of the ring sees far more or far fewer events than it has buckets for.
//
// A bucket is a list of chunks of kChunk events, not of single events: scheduling writes the
// event into the bucket's open chunk, and draining a bucket reads its chunks front to back, so
// the walk costs one cache miss per chunk instead of one per event. From kManyDisks disks on
// the ring has kChunk times fewer buckets than disks (a bucket near the present then holds a
// few chunks at the tuned width); below, as many buckets as disks, as before chunks. The
// bucket table (open chunk and its fill) stays in cache; freed chunks are reused first.
//
// Nothing is ever unlinked: a disk's new event is appended with the disk's next generation
// number, and an entry whose generation is no longer the disk's is dropped when it is reached.
// Scheduling is an append, draining a sequential read, and the heap compares times it holds,
// so the queue touches no other disk's record.
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

  // n disks without events at time `now`; the ring has about n / perBucket buckets (0: kChunk
  // from kManyDisks disks on, else 1).
  void reset(std::size_t n, double now, std::size_t perBucket = 0) {
    gen_.assign(n, 0);
    // Fewer, fuller buckets where the events do not fit in cache (one miss per chunk, not per
    // event); where they do, emptier ones keep the current bucket's heap small.
    perBucket_ = perBucket > 0 ? perBucket : n >= kManyDisks ? kChunk : 1;
    buckets_ = 64;
    while (buckets_ * perBucket_ < n)
      buckets_ *= 2;
    width_ = 1.0;
    clear(now);
  }

  // Sizes the buckets from the pending events: the ring spans four times their mean horizon.
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
    while (!heap_.empty()) {
      if (valid(heap_.front()))
        return &heap_.front();
      heapPop();
    }
    return advance();
  }

  // Removes the event top() returned.
  void pop() {
    heapPop();
    ++popped_;
  }

  // For tests: the number of valid pending events (at most one per disk), after checking the
  // ring's bookkeeping (the count of listed entries, every chunk but a bucket's open one full,
  // each entry in the bucket of its time); -1 if that is broken.
  long long checkedPending() const {
    std::size_t listed = 0;
    for (std::size_t slot = 0; slot < table_.size(); ++slot) {
      const Bucket& b = table_[slot];
      if ((b.open < 0) != (b.fill == 0) || b.fill > kChunk)
        return -1;
      std::uint32_t fill = b.fill;
      for (std::int32_t k = b.open; k >= 0;
           k = chunks_[static_cast<std::size_t>(k)].next, fill = kChunk)
        for (std::uint32_t e = 0; e < fill; ++e) {
          const std::int64_t bucket =
              bucketOf(chunks_[static_cast<std::size_t>(k)].items[e].event.t);
          if (slotOf(bucket) != slot || bucket <= current_ ||
              bucket >= current_ + static_cast<std::int64_t>(buckets_))
            return -1;
          ++listed;
        }
    }
    if (listed != listed_)
      return -1;
    std::vector<char> seen(gen_.size(), 0);
    long long pending = 0;
    bool twice = false;
    forEachValid([&](const Item& it) {
      twice = twice || seen[it.disk];
      seen[it.disk] = 1;
      ++pending;
    });
    return twice ? -1 : pending;
  }

  // Turns and width changes so far (tests check that they ran).
  std::uint64_t turns() const { return turns_; }
  std::uint64_t rebuilds() const { return rebuilds_; }

private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr std::uint32_t kChunk =
      7; // events per chunk: 7 x 32 bytes + the link, 4 cache lines
  static constexpr std::size_t kManyDisks =
      32768; // from this many disks, kChunk times fewer buckets

  // The current bucket is used up: move on to the next one with events (out of line, so that
  // top() stays small enough to inline).
  __attribute__((noinline)) const Item* advance() {
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
        ++turns_;
        const bool crowded = seen > 8 * perBucket_ * buckets_, sparse = seen * 8 < buckets_;
        if (crowded || sparse) {
          rebuild(width_ * (crowded ? 0.25 : 4.0), static_cast<double>(current_) * width_);
          continue;
        }
        refill();
      }
      // The current bucket's valid events go into the heap.
      Bucket& b = table_[slotOf(current_)];
      std::uint32_t fill = b.fill;
      for (std::int32_t k = b.open; k >= 0; fill = kChunk) {
        Chunk& chunk = chunks_[static_cast<std::size_t>(k)];
        for (std::uint32_t e = 0; e < fill; ++e)
          if (valid(chunk.items[e]))
            heapPush(chunk.items[e]);
        listed_ -= fill;
        const std::int32_t following = chunk.next;
        chunk.next = free_;
        free_ = k;
        k = following;
      }
      b = Bucket{};
    }
  }

  bool valid(const Item& it) const { return gen_[it.disk] == it.gen; }

  std::int64_t bucketOf(double t) const {
    const double b = std::floor(t / width_);
    return b > 4e18 ? std::numeric_limits<std::int64_t>::max() / 2 : static_cast<std::int64_t>(b);
  }
  std::size_t slotOf(std::int64_t b) const {
    return static_cast<std::size_t>(
        b & static_cast<std::int64_t>(buckets_ - 1)); // buckets_ is a power of 2
  }

  template <class F> void forEachValid(F&& f) const {
    for (const Item& it : heap_)
      if (valid(it))
        f(it);
    for (const Bucket& b : table_) {
      std::uint32_t fill = b.fill;
      for (std::int32_t k = b.open; k >= 0;
           k = chunks_[static_cast<std::size_t>(k)].next, fill = kChunk)
        for (std::uint32_t e = 0; e < fill; ++e)
          if (valid(chunks_[static_cast<std::size_t>(k)].items[e]))
            f(chunks_[static_cast<std::size_t>(k)].items[e]);
    }
    for (const Item& it : waiting_)
      if (valid(it))
        f(it);
  }

  void clear(double now) {
    current_ = bucketOf(now);
    turnStart_ = current_;
    popped_ = 0;
    table_.assign(buckets_, Bucket{});
    chunks_.clear();
    free_ = -1;
    waiting_.clear();
    heap_.clear();
    listed_ = 0;
  }

  void rebuild(double width, double now) {
    ++rebuilds_;
    std::vector<Item> all;
    forEachValid([&](const Item& it) { all.push_back(it); });
    width_ = width;
    clear(now);
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
      Bucket& bucket = table_[slotOf(b)];
      if (bucket.open < 0 || bucket.fill == kChunk) {
        std::int32_t k = free_;
        if (k >= 0) {
          free_ = chunks_[static_cast<std::size_t>(k)].next;
        } else {
          k = static_cast<std::int32_t>(chunks_.size());
          chunks_.emplace_back();
        }
        chunks_[static_cast<std::size_t>(k)].next = bucket.open;
        bucket.open = k;
        bucket.fill = 0;
      }
      chunks_[static_cast<std::size_t>(bucket.open)].items[bucket.fill++] = it;
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

  std::size_t buckets_ = 64, listed_ = 0, perBucket_ = 2;
  double width_ = 1.0;
  std::int64_t current_ = 0, turnStart_ = 0;
  std::uint64_t popped_ = 0, turns_ = 0, rebuilds_ = 0;
  std::vector<std::uint32_t> gen_;
  // The ring: per bucket its open chunk (the one being filled, at the head of the bucket's
  // list of chunks; the others are full) and how many events that one holds.
  struct Bucket {
    std::int32_t open = -1;
    std::uint32_t fill = 0;
  };
  struct alignas(64) Chunk {
    Item items[kChunk];
    std::int32_t next = -1;
  };
  std::vector<Bucket> table_;
  std::vector<Chunk> chunks_;
  std::int32_t free_ = -1;    // free chunks, most recently freed first
  std::vector<Item> waiting_; // beyond the ring
  std::vector<Item> heap_;
};

} // namespace craterkit

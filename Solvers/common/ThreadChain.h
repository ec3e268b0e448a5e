// Waits between the threads of an OpenMP team that split an ordered sequence into contiguous
// ranges in thread order (CraterKit's DEM step: the contact rows of thread t follow those of
// threads 0 .. t-1, and thread t's particles come after theirs).
//
// A barrier makes every thread wait for the slowest; when a thread needs only what the threads
// before it have done (the number of rows they wrote, the end of their reads of its particles),
// it need wait for those alone: thread 0 never waits, and a thread that is late delays only the
// threads after it. Each thread posts the stage it has reached (a number that only grows, from
// one region to the next); post is a release, the wait an acquire, so whatever thread q wrote
// before posting is visible to the threads that waited for it. The wait spins briefly, then
// yields: with more threads than processors the thread waited for may need the processor.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <utility>

namespace craterkit {

class ThreadChain {
public:
  ThreadChain() = default;
  // The state means something only inside a region: a copy starts afresh.
  ThreadChain(const ThreadChain& other) { resize(other.size_); }
  ThreadChain& operator=(const ThreadChain& other) {
    if (this != &other) {
      flags_.reset(), size_ = 0; // fresh flags: stages carried over would release waits early
      resize(other.size_);
    }
    return *this;
  }
  ThreadChain(ThreadChain&& other) noexcept
      : flags_(std::move(other.flags_)), size_(std::exchange(other.size_, 0)) {}
  ThreadChain& operator=(ThreadChain&& other) noexcept {
    flags_ = std::move(other.flags_), size_ = std::exchange(other.size_, 0);
    return *this;
  }

  // Room for `threads` threads (serially, outside a region); keeps the stages if it has it.
  void resize(std::size_t threads) {
    if (threads <= size_)
      return;
    flags_.reset(new Flag[threads]);
    size_ = threads;
  }
  // Thread t has reached `stage`.
  void post(std::size_t t, std::uint64_t stage) {
    flags_[t].stage.store(stage, std::memory_order_release);
  }
  // Returns once every thread before t has posted `stage` or a later one.
  void waitForEarlier(std::size_t t, std::uint64_t stage) const {
    for (std::size_t q = 0; q < t; ++q)
      for (int spins = 0; flags_[q].stage.load(std::memory_order_acquire) < stage; ++spins) {
        if (spins < kSpins) {
#if defined(__x86_64__) || defined(__i386__)
          __builtin_ia32_pause();
#endif
        } else {
          std::this_thread::yield();
        }
      }
  }

private:
  struct alignas(64) Flag { // one cache line each: a post does not disturb the other flags
    std::atomic<std::uint64_t> stage{0};
  };
  static constexpr int kSpins = 4000; // about the cost of a barrier on this kind of machine
  std::unique_ptr<Flag[]> flags_;
  std::size_t size_ = 0;
};

} // namespace craterkit

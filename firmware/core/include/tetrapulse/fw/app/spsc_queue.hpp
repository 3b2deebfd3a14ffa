#pragma once
// A single-producer single-consumer ring for handing events from an interrupt (sync
// edge captures, received CAN frames) to the main loop without locks: the producer
// only writes head_, the consumer only tail_. Capacity N - 1 items; N a power of two.
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace tetrapulse::fw {

template <typename T, size_t N>
class SpscQueue {
  static_assert(N >= 2 && (N & (N - 1)) == 0, "N must be a power of two");

 public:
  // Producer side. False (item dropped) when full.
  bool push(const T& item) {
    const uint32_t head = head_.load(std::memory_order_relaxed);
    const uint32_t next = (head + 1) & (N - 1);
    if (next == tail_.load(std::memory_order_acquire)) return false;
    items_[head] = item;
    head_.store(next, std::memory_order_release);
    return true;
  }
  // Consumer side. False when empty.
  bool pop(T* item) {
    const uint32_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    *item = items_[tail];
    tail_.store((tail + 1) & (N - 1), std::memory_order_release);
    return true;
  }
  bool empty() const { return tail_.load(std::memory_order_acquire) == head_.load(std::memory_order_acquire); }

 private:
  T items_[N] = {};
  std::atomic<uint32_t> head_{0};
  std::atomic<uint32_t> tail_{0};
};

}  // namespace tetrapulse::fw

#pragma once
// A single-producer single-consumer byte queue between an interrupt and the main loop.
#include <cstddef>
#include <cstdint>

namespace tetrapulse::stm32f405 {

template <size_t kCapacity>
class ByteRing {
  static_assert((kCapacity & (kCapacity - 1)) == 0, "capacity must be a power of two");

 public:
  bool push(uint8_t b) {
    const uint32_t head = head_;
    if (head - tail_ == kCapacity) return false;
    data_[head % kCapacity] = b;
    head_ = head + 1;
    return true;
  }
  bool pop(uint8_t* b) {
    const uint32_t tail = tail_;
    if (head_ == tail) return false;
    *b = data_[tail % kCapacity];
    tail_ = tail + 1;
    return true;
  }
  size_t size() const { return head_ - tail_; }
  size_t space() const { return kCapacity - size(); }
  bool empty() const { return head_ == tail_; }

 private:
  uint8_t data_[kCapacity] = {};
  volatile uint32_t head_ = 0;  // written by the producer only
  volatile uint32_t tail_ = 0;  // written by the consumer only
};

}  // namespace tetrapulse::stm32f405

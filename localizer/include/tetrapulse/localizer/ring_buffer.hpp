#pragma once
// A fixed-capacity ring buffer that keeps the newest N values; no allocation.
#include <array>
#include <cstddef>

namespace tetrapulse {

template <typename T, size_t N>
class RingBuffer {
  static_assert(N > 0, "RingBuffer needs a capacity");

 public:
  static constexpr size_t capacity() { return N; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  // Appends `value`, dropping the oldest one when full.
  void push(const T& value) {
    items_[(start_ + size_) % N] = value;
    if (size_ < N) {
      ++size_;
    } else {
      start_ = (start_ + 1) % N;
    }
  }

  // i = 0 is the oldest value kept, size() - 1 the newest. Precondition: i < size().
  const T& operator[](size_t i) const { return items_[(start_ + i) % N]; }
  T& operator[](size_t i) { return items_[(start_ + i) % N]; }
  const T& newest() const { return (*this)[size_ - 1]; }

  void clear() {
    start_ = 0;
    size_ = 0;
  }

 private:
  std::array<T, N> items_{};
  size_t start_ = 0;
  size_t size_ = 0;
};

}  // namespace tetrapulse

#pragma once
// Memory-mapped register access. Every register block below is a struct laid out as in
// RM0090 (STM32F405 reference manual); each layout is checked with static_assert so that a
// missing reserved word cannot shift the registers after it.
#include <cstddef>
#include <cstdint>

namespace tetrapulse::stm32f405 {

using Reg = volatile uint32_t;

// The register block of type T at `base`.
template <class T>
inline T& block(uintptr_t base) {
  return *reinterpret_cast<T*>(base);
}

// Bit field helpers: a field of `width` bits at bit `pos`.
constexpr uint32_t bit(unsigned pos) { return 1u << pos; }
constexpr uint32_t field(uint32_t value, unsigned pos) { return value << pos; }
constexpr uint32_t mask(unsigned width, unsigned pos) { return ((1u << width) - 1u) << pos; }

}  // namespace tetrapulse::stm32f405

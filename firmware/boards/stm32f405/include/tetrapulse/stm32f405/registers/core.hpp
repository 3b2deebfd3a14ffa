#pragma once
// Cortex-M4 core registers used by the board: SCB, NVIC, SysTick (ARMv7-M ARM, B3).
#include "tetrapulse/stm32f405/registers/mmio.hpp"

namespace tetrapulse::stm32f405::scb {

inline Reg& VTOR() { return *reinterpret_cast<Reg*>(0xE000ED08); }
inline Reg& AIRCR() { return *reinterpret_cast<Reg*>(0xE000ED0C); }
inline Reg& CPACR() { return *reinterpret_cast<Reg*>(0xE000ED88); }
constexpr uint32_t kAircrSysResetReq = (0x05FAu << 16) | bit(2);
constexpr uint32_t kCpacrFpuFull = (3u << 20) | (3u << 22);  // CP10, CP11 full access

}  // namespace tetrapulse::stm32f405::scb

namespace tetrapulse::stm32f405::nvic {

inline Reg& ISER(unsigned n) { return *reinterpret_cast<Reg*>(0xE000E100 + 4 * n); }
inline Reg& ICER(unsigned n) { return *reinterpret_cast<Reg*>(0xE000E180 + 4 * n); }
inline volatile uint8_t& IPR(unsigned irq) { return *reinterpret_cast<volatile uint8_t*>(0xE000E400 + irq); }

// Interrupt numbers (RM0090 table 61, vector position)
constexpr unsigned kCan1Tx = 19;
constexpr unsigned kCan1Rx0 = 20;
constexpr unsigned kCan1Rx1 = 21;
constexpr unsigned kCan1Sce = 22;
constexpr unsigned kTim8Up = 44;  // TIM8_UP_TIM13
constexpr unsigned kTim2 = 28;
constexpr unsigned kUsart1 = 37;
constexpr unsigned kOtgFs = 67;
constexpr unsigned kVectorCount = 82;  // interrupt vectors after the 16 system ones

inline void enable(unsigned irq, uint8_t priority) {
  IPR(irq) = static_cast<uint8_t>(priority << 4);  // 4 priority bits, in the high nibble
  ISER(irq / 32) = 1u << (irq % 32);
}
inline void disable(unsigned irq) { ICER(irq / 32) = 1u << (irq % 32); }

}  // namespace tetrapulse::stm32f405::nvic

namespace tetrapulse::stm32f405 {

// 96-bit unique device id (RM0090 §39.1), 12 bytes at 0x1FFF7A10.
constexpr uintptr_t kUniqueIdAddress = 0x1FFF7A10;

inline uint32_t disable_interrupts() {
  uint32_t primask;
  __asm volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
  return primask;
}
inline void restore_interrupts(uint32_t primask) {
  __asm volatile("msr primask, %0" ::"r"(primask) : "memory");
}
// Masks interrupts for the lifetime of the object.
class InterruptLock {
 public:
  InterruptLock() : primask_(disable_interrupts()) {}
  ~InterruptLock() { restore_interrupts(primask_); }
  InterruptLock(const InterruptLock&) = delete;
  InterruptLock& operator=(const InterruptLock&) = delete;

 private:
  uint32_t primask_;
};

inline void data_sync_barrier() { __asm volatile("dsb 0xF" ::: "memory"); }
inline void instruction_sync_barrier() { __asm volatile("isb 0xF" ::: "memory"); }

}  // namespace tetrapulse::stm32f405

#include "tetrapulse/stm32f405/system.hpp"

#include "tetrapulse/stm32f405/registers/core.hpp"
#include "tetrapulse/stm32f405/registers/rcc.hpp"

namespace tetrapulse::stm32f405 {

std::array<uint8_t, 12> unique_id() {
  std::array<uint8_t, 12> id{};
  const volatile uint8_t* src = reinterpret_cast<const volatile uint8_t*>(kUniqueIdAddress);
  for (size_t i = 0; i < id.size(); ++i) id[i] = src[i];
  return id;
}

void unique_id_hex(char (&out)[25]) {
  constexpr char kDigits[] = "0123456789ABCDEF";
  const std::array<uint8_t, 12> id = unique_id();
  for (size_t i = 0; i < id.size(); ++i) {
    out[2 * i] = kDigits[id[i] >> 4];
    out[2 * i + 1] = kDigits[id[i] & 0x0F];
  }
  out[24] = '\0';
}

ResetCause take_reset_cause() {
  rcc::Registers& r = rcc::regs();
  const uint32_t csr = r.CSR;
  r.CSR = r.CSR | rcc::kCsrRmvf;
  ResetCause c;
  c.watchdog = (csr & rcc::kCsrIwdgRst) != 0;
  c.software = (csr & rcc::kCsrSftRst) != 0;
  c.power_on = (csr & rcc::kCsrPorRst) != 0;
  c.pin = (csr & rcc::kCsrPinRst) != 0;
  return c;
}

void system_reset() {
  data_sync_barrier();
  scb::AIRCR() = scb::kAircrSysResetReq;
  data_sync_barrier();
  for (;;) {
  }
}

void start_image(uint32_t vector_table) {
  disable_interrupts();
  for (unsigned i = 0; i < 3; ++i) nvic::ICER(i) = 0xFFFFFFFFu;
  // SysTick off: the image starts from a clean core state.
  *reinterpret_cast<Reg*>(0xE000E010) = 0;
  scb::VTOR() = vector_table;
  data_sync_barrier();
  instruction_sync_barrier();
  const uint32_t stack = *reinterpret_cast<const volatile uint32_t*>(vector_table);
  const uint32_t entry = *reinterpret_cast<const volatile uint32_t*>(vector_table + 4);
  __asm volatile(
      "msr msp, %0\n"
      "cpsie i\n"
      "bx %1\n" ::"r"(stack),
      "r"(entry)
      : "memory");
  __builtin_unreachable();
}

}  // namespace tetrapulse::stm32f405

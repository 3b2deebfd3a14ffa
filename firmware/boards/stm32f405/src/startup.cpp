// Reset handler and vector table, shared by the bootloader and the application. The linker
// script (linker/sections.ld) places .isr_vector first in FLASH and defines the symbols
// below; the table holds 16 system vectors and the STM32F405's 82 interrupts.
#include <cstdint>

#include "tetrapulse/stm32f405/interrupt_handlers.hpp"
#include "tetrapulse/stm32f405/registers/core.hpp"

extern "C" {
extern uint32_t __stack_top;
extern uint32_t __data_load;
extern uint32_t __data_start;
extern uint32_t __data_end;
extern uint32_t __bss_start;
extern uint32_t __bss_end;
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();
extern uint32_t __vector_table;

// The program's main(), under another C++ name: ISO C++ does not let code call main.
int program_main() __asm__("main");

void Reset_Handler();
void Default_Handler();
#define TP_WEAK_HANDLER __attribute__((weak, alias("Default_Handler")))
void NMI_Handler() TP_WEAK_HANDLER;
void HardFault_Handler() TP_WEAK_HANDLER;
void MemManage_Handler() TP_WEAK_HANDLER;
void BusFault_Handler() TP_WEAK_HANDLER;
void UsageFault_Handler() TP_WEAK_HANDLER;
void SVC_Handler() TP_WEAK_HANDLER;
void DebugMon_Handler() TP_WEAK_HANDLER;
void PendSV_Handler() TP_WEAK_HANDLER;
void SysTick_Handler() TP_WEAK_HANDLER;
void CAN1_TX_IRQHandler() TP_WEAK_HANDLER;
void CAN1_RX0_IRQHandler() TP_WEAK_HANDLER;
void CAN1_RX1_IRQHandler() TP_WEAK_HANDLER;
void CAN1_SCE_IRQHandler() TP_WEAK_HANDLER;
void TIM2_IRQHandler() TP_WEAK_HANDLER;
void USART1_IRQHandler() TP_WEAK_HANDLER;
void TIM8_UP_TIM13_IRQHandler() TP_WEAK_HANDLER;
void OTG_FS_IRQHandler() TP_WEAK_HANDLER;
#undef TP_WEAK_HANDLER
}

namespace {

using Vector = void (*)();
constexpr unsigned kSystemVectors = 16;
constexpr unsigned kTableSize = kSystemVectors + tetrapulse::stm32f405::nvic::kVectorCount;

struct VectorTable {
  uint32_t* stack_top;
  Vector vectors[kTableSize - 1];
};

constexpr unsigned irq(unsigned n) { return kSystemVectors - 1 + n; }

constexpr VectorTable make_table() {
  VectorTable t{&__stack_top, {}};
  for (Vector& v : t.vectors) v = Default_Handler;
  t.vectors[0] = Reset_Handler;
  t.vectors[1] = NMI_Handler;
  t.vectors[2] = HardFault_Handler;
  t.vectors[3] = MemManage_Handler;
  t.vectors[4] = BusFault_Handler;
  t.vectors[5] = UsageFault_Handler;
  t.vectors[10] = SVC_Handler;
  t.vectors[11] = DebugMon_Handler;
  t.vectors[13] = PendSV_Handler;
  t.vectors[14] = SysTick_Handler;
  namespace nvic = tetrapulse::stm32f405::nvic;
  t.vectors[irq(nvic::kCan1Tx)] = CAN1_TX_IRQHandler;
  t.vectors[irq(nvic::kCan1Rx0)] = CAN1_RX0_IRQHandler;
  t.vectors[irq(nvic::kCan1Rx1)] = CAN1_RX1_IRQHandler;
  t.vectors[irq(nvic::kCan1Sce)] = CAN1_SCE_IRQHandler;
  t.vectors[irq(nvic::kTim2)] = TIM2_IRQHandler;
  t.vectors[irq(nvic::kUsart1)] = USART1_IRQHandler;
  t.vectors[irq(nvic::kTim8Up)] = TIM8_UP_TIM13_IRQHandler;
  t.vectors[irq(nvic::kOtgFs)] = OTG_FS_IRQHandler;
  return t;
}

}  // namespace

extern "C" {

__attribute__((section(".isr_vector"), used)) constexpr VectorTable g_vector_table = make_table();

void Default_Handler() {
  // An interrupt nobody handles, or a fault: stop here; the watchdog (when running)
  // resets the board.
  for (;;) {
  }
}

void Reset_Handler() {
  namespace t = tetrapulse::stm32f405;
  // The FPU first: compiled code may use its registers anywhere after this point.
  t::scb::CPACR() = t::scb::CPACR() | t::scb::kCpacrFpuFull;
  t::data_sync_barrier();
  t::instruction_sync_barrier();
  // This image may have been started by the bootloader (or an emulator) with VTOR elsewhere.
  t::scb::VTOR() = reinterpret_cast<uint32_t>(&__vector_table);

  const uint32_t* src = &__data_load;
  for (uint32_t* dst = &__data_start; dst < &__data_end;) *dst++ = *src++;
  for (uint32_t* dst = &__bss_start; dst < &__bss_end;) *dst++ = 0;
  for (void (**init)() = __init_array_start; init < __init_array_end; ++init) (*init)();

  program_main();
  for (;;) {
  }
}

}  // extern "C"

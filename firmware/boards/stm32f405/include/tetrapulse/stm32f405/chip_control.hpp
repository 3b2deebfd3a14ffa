#pragma once
// fw::SystemControl for the STM32F405: resets through the bootloader handoff, the chip's
// unique id, the board revision, the independent watchdog.
#include "tetrapulse/fw/app/system_control.hpp"
#include "tetrapulse/stm32f405/system.hpp"
#include "tetrapulse/stm32f405/usart1.hpp"

namespace tetrapulse::stm32f405 {

class ChipControl final : public fw::SystemControl {
 public:
  // Reads the handoff the bootloader left, the reset cause and the unique id (call once
  // at start). `has_system_memory` is false under an emulator that maps no system memory
  // at 0x1FFF7A10 (QEMU's netduinoplus2, where a read faults): the id then reads as zeros.
  void start(const ResetCause& cause, bool has_system_memory);
  // The slot the bootloader said it started; kNoSlot when started some other way.
  uint8_t booted_slot() const { return booted_slot_; }
  // Runs before every reset this class makes, after USART1 has drained: the application
  // lets an answer queued on USB leave (SPEC §2.3 Reboot: the Ack goes out first).
  void set_before_reset(void (*hook)(void* context), void* context) {
    before_reset_ = hook;
    before_reset_context_ = context;
  }

 private:
  void do_reboot(protocol::RebootMode mode) override;
  std::array<uint8_t, protocol::kSerialSize> do_unique_id() const override { return unique_id_; }
  protocol::HwModel do_hw_model() const override { return protocol::HwModel::kStm32f405Reference; }
  uint8_t do_hw_revision() const override;
  uint32_t do_bootloader_version() const override { return bootloader_version_; }
  void do_kick_watchdog() override;
  uint16_t do_watchdog_resets() const override { return watchdog_resets_; }

  std::array<uint8_t, protocol::kSerialSize> unique_id_{};
  uint32_t bootloader_version_ = 0;
  uint8_t booted_slot_ = 0xFF;
  uint16_t watchdog_resets_ = 0;
  void (*before_reset_)(void*) = nullptr;
  void* before_reset_context_ = nullptr;
};

}  // namespace tetrapulse::stm32f405

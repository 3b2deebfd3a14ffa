// Linked bare-metal in the firmware build (core/CMakeLists.txt): the whole firmware core
// behind do-nothing seams, so check_freestanding.cmake can show that none of it pulls in
// the heap, exceptions, RTTI or abort().
#include "tetrapulse/fw/app/firmware.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/boot/image_check.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/uart_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"

using namespace tetrapulse;
using namespace tetrapulse::fw;

namespace {

volatile uint32_t g_sink;

class NullClock final : public LocalClock {
  Tick do_now() const override { return g_sink; }
  uint32_t do_tick_hz() const override { return 84'000'000; }
};

class NullLeds final : public LedDriver {
  protocol::Status do_schedule(uint8_t, uint16_t duty, Tick) override { g_sink = duty; return {}; }
  size_t do_pending(uint8_t) const override { return g_sink; }
  void do_cancel() override {}
  void do_set_now(uint8_t, uint16_t duty) override { g_sink = duty; }
  uint32_t do_lead_ticks() const override { return 100; }
  size_t do_queue_depth() const override { return 1; }
  uint16_t do_full_scale_ma() const override { return 700; }
};

class NullFlash final : public Flash {
  protocol::Result<FlashRegion> do_sector_at(uint32_t address) const override {
    return FlashRegion{address & ~0x3FFFu, 0x4000};
  }
  protocol::Status do_erase_sector(uint32_t) override { return {}; }
  protocol::Status do_program(uint32_t, protocol::ByteView data) override { g_sink = data.size; return {}; }
  protocol::Status do_read(uint32_t, uint8_t* out, size_t size) const override {
    for (size_t i = 0; i < size; ++i) out[i] = static_cast<uint8_t>(g_sink);
    return {};
  }
};

class NullSystem final : public SystemControl {
  void do_reboot(protocol::RebootMode mode) override { g_sink = static_cast<uint32_t>(mode); }
  std::array<uint8_t, protocol::kSerialSize> do_unique_id() const override { return {}; }
  protocol::HwModel do_hw_model() const override { return protocol::HwModel::kStm32f405Reference; }
  uint8_t do_hw_revision() const override { return 1; }
  uint32_t do_bootloader_version() const override { return 0; }
  void do_kick_watchdog() override {}
  uint16_t do_watchdog_resets() const override { return 0; }
};

class NullSync final : public SyncInput {
  void do_configure(bool enabled, protocol::GpioEdge) override { g_sink = enabled; }
};

class NullCan final : public CanBus {
  protocol::Status do_send(const protocol::CanFrame& frame) override { g_sink = frame.id; return {}; }
  void do_set_filters(const protocol::CanNodeFilters& f) override { g_sink = f.addressed.id; }
  uint16_t do_error_count() const override { return 0; }
  bool do_bus_off() const override { return false; }
};

class NullSerial final : public SerialPort {
  protocol::Status do_write(protocol::ByteView bytes) override { g_sink = bytes.size; return {}; }
};

class NullUsb final : public UsbPipe {
  protocol::Status do_send_bulk(protocol::ByteView bytes) override { g_sink = bytes.size; return {}; }
};

NullClock g_clock;
NullLeds g_leds;
NullFlash g_flash;
NullSystem g_system;
NullSync g_sync;
NullCan g_can_bus;
NullSerial g_serial;
NullUsb g_usb;
uint8_t g_bytes[64];

}  // namespace

int main() {
  static CanLink can(g_can_bus, g_clock.tick_hz(), 1);
  static UartLink uart(g_serial);
  static UsbLink usb(g_usb);
  FirmwareParts parts;
  parts.clock = &g_clock;
  parts.leds = &g_leds;
  parts.flash = &g_flash;
  parts.system = &g_system;
  parts.sync_input = &g_sync;
  parts.can = &can;
  static Firmware firmware(parts);
  firmware.start();
  firmware.on_sync_edge(g_sink);
  protocol::CanFrame frame;
  can.on_frame(frame, g_sink, firmware);
  uart.on_bytes(protocol::ByteView{g_bytes, sizeof(g_bytes)}, g_sink, firmware);
  usb.on_bulk_transfer(protocol::ByteView{g_bytes, sizeof(g_bytes)}, g_sink, firmware);
  firmware.poll();
  const std::array<SlotCheck, kSlotCount> slots{};
  const BootDecision d = select_boot(load_boot_state(firmware.board().store()), slots, false);
  g_sink = d.slot;
  return static_cast<int>(g_sink);
}

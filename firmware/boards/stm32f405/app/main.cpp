// The application on the STM32F405 reference board: brings the chip up, builds the
// hardware seams and hands them to the firmware core, then runs the main loop.
#include <cstdint>

#include "tetrapulse/fw/app/firmware.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/fw/links/uart_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"
#include "tetrapulse/fw/usb/usb_message_function.hpp"
#include "tetrapulse/protocol/response_messages.hpp"
#include "tetrapulse/protocol/usb_device.hpp"
#include "tetrapulse/stm32f405/board_identity.hpp"
#include "tetrapulse/stm32f405/bx_can.hpp"
#include "tetrapulse/stm32f405/chip_control.hpp"
#include "tetrapulse/stm32f405/clock_tree.hpp"
#include "tetrapulse/stm32f405/internal_flash.hpp"
#include "tetrapulse/stm32f405/led_timer.hpp"
#include "tetrapulse/stm32f405/local_timer.hpp"
#include "tetrapulse/stm32f405/sync_capture.hpp"
#include "tetrapulse/stm32f405/system.hpp"
#include "tetrapulse/stm32f405/usart1.hpp"
#include "tetrapulse/stm32f405/usb_otg_fs.hpp"
#include "tetrapulse/stm32f405/watchdog.hpp"

extern "C" uint32_t __vector_table;  // linker script: where this image's vectors are

namespace {

namespace tp = tetrapulse::protocol;
namespace fw = tetrapulse::fw;
using namespace tetrapulse::stm32f405;

constexpr uint32_t kUartBaud = 115200;
constexpr uint32_t kWatchdogMs = 4000;  // above the longest sector erase (internal_flash.hpp)
constexpr uint32_t kUsbFlushMs = 50;    // a host polls MESSAGE_IN at least every few ms (SPEC §5.5)
constexpr uint32_t kDetachMs = 20;      // disconnected this long before the reset: the host sees it

uint8_t running_slot() {
  const int slot = slot_of_address(reinterpret_cast<uint32_t>(&__vector_table));
  return slot < 0 ? 0 : static_cast<uint8_t>(slot);
}

uint32_t now_ms(const LocalTimer& clock) { return static_cast<uint32_t>(clock.read() / (clock.tick_hz() / 1000u)); }

// Keeps USB running for `ms`, and on until a bulk IN answer has left (bounded by `ms` twice).
void serve_usb(UsbOtgFs& usb, const LocalTimer& clock, uint32_t ms) {
  const uint32_t start = now_ms(clock);
  while (now_ms(clock) - start < ms || (usb.bulk_in_busy() && now_ms(clock) - start < 2 * ms)) usb.poll();
}

// DFU_DETACH (bitWillDetach): off the bus, then a reset into the bootloader, which stays
// in DFU mode (boot handoff) and enumerates as 1209:0002.
class DetachToBootloader final : public fw::DfuRuntimeTarget {
 public:
  DetachToBootloader(UsbOtgFs& usb, ChipControl& chip, const LocalTimer& clock) : usb_(usb), chip_(chip), clock_(clock) {}

 private:
  void do_detach() override {
    usb_.disconnect();
    const uint32_t start = now_ms(clock_);
    while (now_ms(clock_) - start < kDetachMs) {
    }
    chip_.reboot(tp::RebootMode::kBootloader);
  }
  UsbOtgFs& usb_;
  ChipControl& chip_;
  const LocalTimer& clock_;
};

// The firmware core on this board's seams. Out of line (as the two helpers below) so that
// its locals are off the stack by the time messages are handled in the main loop: the
// deepest path (a request that compacts the record store) needs most of the 5 KB stack.
struct Application {
  fw::Firmware& firmware;
  SyncCapture& sync;
  fw::CanLink& can;
};

__attribute__((noinline)) Application start_firmware(LocalTimer& clock, ChipControl& chip, bool can_up,
                                                     bool usb_possible) {
  static InternalFlash flash;
  static SyncCapture sync(clock);
  static fw::CanLink can_link(bx_can(), clock.tick_hz(), tp::kCanFirstBoardNode);
  fw::FirmwareParts parts;
  parts.clock = &clock;
  parts.leds = &led_timer();
  parts.flash = &flash;
  parts.system = &chip;
  parts.sync_input = &sync;
  parts.can = &can_link;
  parts.layout = flash_layout();
  parts.board.fw_version = TETRAPULSE_FW_VERSION;
  parts.board.active_slot = running_slot();
  parts.board.capabilities = tp::capability::kUart | tp::capability::kGpioSyncInput | tp::capability::kTwoLevel |
                             (usb_possible ? tp::capability::kUsb | tp::capability::kDfu : 0) |
                             (can_up ? tp::capability::kCan | tp::capability::kCanUpdate : 0);
  static fw::Firmware firmware(parts);
  firmware.start();
  return Application{firmware, sync, can_link};
}

__attribute__((noinline)) void serve_uart(fw::UartLink& link, fw::MessageSink& sink, const LocalTimer& clock) {
  uint8_t bytes[64];
  size_t n = 0;
  while (n < sizeof(bytes) && usart1().read(&bytes[n])) ++n;
  if (n != 0) link.on_bytes(tp::ByteView{bytes, n}, clock.read(), sink);
}

__attribute__((noinline)) void serve_can(fw::CanLink& link, fw::MessageSink& sink) {
  ReceivedFrame frame;
  while (bx_can().receive(&frame)) link.on_frame(frame.frame, frame.rx, sink);
}

}  // namespace

int main() {
  const Clocks clocks = configure_clocks();
  const ResetCause cause = take_reset_cause();
  LocalTimer& clock = local_timer();
  clock.start(clocks.apb1_timer_hz);
  start_watchdog(kWatchdogMs);
  usart1().start(clocks.apb2_hz, kUartBaud);
  led_timer().start(clocks.apb2_timer_hz, clock);
  const bool can_up = bx_can().start(clocks.apb1_hz, BxCan::kDefaultBitrate, clock);

  static ChipControl chip;
  const bool real_chip = clocks.source != ClockSource::kUnreadable;  // QEMU: no system memory, no USB
  chip.start(cause, real_chip);
  // USB needs the 48 MHz clock of the PLL (not under QEMU, which models no OTG core).
  const bool usb_possible = clocks.usb_clock_ok && real_chip;
  const Application app = start_firmware(clock, chip, can_up, usb_possible);
  fw::Firmware& firmware = app.firmware;
  static fw::UartLink uart_link(usart1());

  // USB: interface 0 messages (control requests and bulk), interface 1 DFU run-time.
  static char serial[25] = "000000000000000000000000";
  if (real_chip) unique_id_hex(serial);
  static const tp::UsbDeviceParams usb_params = usb_device_params(tp::UsbMode::kApplication, TETRAPULSE_FW_VERSION);
  static UsbOtgFs usb;
  static uint8_t usb_answers[tp::kMaxMessageSize];  // descriptors, PROTOCOL_INFO, MESSAGE_IN/OUT
  static fw::UsbControl usb_control(usb_params, serial, usb, usb_answers, sizeof(usb_answers));
  static fw::UsbEndpointZero usb_ep0(usb_control);
  static fw::UsbLink usb_link(usb);
  firmware.board().set_message_links(&uart_link, &usb_link);
  static fw::UsbMessageFunction usb_messages(usb_link, firmware, clock,
                                             tp::kUsbCapabilityBulkMessages | tp::kUsbCapabilityControlMessages |
                                                 tp::kUsbCapabilityDfuRuntime);
  static DetachToBootloader detach(usb, chip, clock);
  static fw::DfuDevice dfu(detach, usb_params);
  usb_control.set_function(tp::kUsbMessageInterface, usb_messages);
  usb_control.set_function(tp::kUsbDfuRuntimeInterface, dfu);
  if (usb_possible && usb.start(usb_ep0, usb_control, &usb_messages, clock)) {
    chip.set_before_reset([](void*) { serve_usb(usb, local_timer(), kUsbFlushMs); }, nullptr);
  }

  for (;;) {
    fw::Tick edge;
    while (app.sync.next_edge(&edge)) firmware.on_sync_edge(edge);
    serve_uart(uart_link, firmware, clock);
    serve_can(app.can, firmware);
    usb.poll();
    dfu.poll(now_ms(clock));
    led_timer().apply_overdue();
    firmware.poll();
  }
}

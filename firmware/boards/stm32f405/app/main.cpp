// The application on the STM32F405 reference board: brings the chip up, builds the
// hardware seams and hands them to the firmware core, then runs the main loop.
#include <cstdint>

#include "tetrapulse/fw/can_link.hpp"
#include "tetrapulse/fw/firmware.hpp"
#include "tetrapulse/fw/uart_link.hpp"
#include "tetrapulse/protocol/response_messages.hpp"
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
#include "tetrapulse/stm32f405/watchdog.hpp"

extern "C" uint32_t __vector_table;  // linker script: where this image's vectors are

namespace {

namespace tp = tetrapulse::protocol;
namespace fw = tetrapulse::fw;
using namespace tetrapulse::stm32f405;

constexpr uint32_t kUartBaud = 115200;
constexpr uint32_t kWatchdogMs = 4000;  // above the longest sector erase (internal_flash.hpp)

uint8_t running_slot() {
  const int slot = slot_of_address(reinterpret_cast<uint32_t>(&__vector_table));
  return slot < 0 ? 0 : static_cast<uint8_t>(slot);
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
  chip.start(cause, clocks.source != ClockSource::kUnreadable);
  static InternalFlash flash;
  static SyncCapture sync(clock);
  static fw::CanLink can_link(bx_can(), clock.tick_hz(), tp::kCanFirstBoardNode);
  static fw::UartLink uart_link(usart1());

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
                             tp::capability::kDfu | (can_up ? tp::capability::kCan | tp::capability::kCanUpdate : 0);
  static fw::Firmware firmware(parts);
  firmware.start();

  for (;;) {
    fw::Tick edge;
    while (sync.next_edge(&edge)) firmware.on_sync_edge(edge);

    uint8_t bytes[64];
    size_t n = 0;
    while (n < sizeof(bytes) && usart1().read(&bytes[n])) ++n;
    if (n != 0) uart_link.on_bytes(tp::ByteView{bytes, n}, clock.now(), firmware);

    ReceivedFrame frame;
    while (bx_can().receive(&frame)) can_link.on_frame(frame.frame, frame.rx, firmware);

    led_timer().apply_overdue();
    firmware.poll();
  }
}

#pragma once
// The OTG FS core as a full-speed USB device (RM0090 §34): the register-level half of the
// USB device, behind the core's seams. It moves packets; fw::UsbEndpointZero turns them
// into control transfers for fw::UsbControl, and bulk OUT packets go to the message
// interface's framing (fw::UsbMessageFunction).
//
//   fw::UsbDeviceController   SET_ADDRESS (DCFG.DAD, applied by the core after the status
//                             stage), SET_CONFIGURATION (opens EP1 bulk IN/OUT), halts
//   fw::UsbPipe               one bulk IN transfer written whole into the bulk IN TX FIFO
//                             (up to 322 bytes fit its 128 words), and a ZLP after it when
//                             its size is a multiple of 64; kBusy until the host took it
// The bulk endpoints are the ones the descriptors name (UsbControl::params(): EP1 OUT
// 0x01, EP1 IN 0x81 by default).
//
// Polled from the main loop (poll()), no interrupt: every message the USB carries is then
// handled in the same context as the rest of the firmware. The core reports through
// GINTSTS whether or not its interrupt line is enabled.
//
// FIFO RAM and packet arithmetic: usb_fifo_plan.hpp (host-tested). Pins PA11/PA12 (pinout.hpp), VBUS sensing off (the board is bus powered and sees
// the bus whenever it runs). QEMU does not model the OTG core: this driver is compiled,
// never run, in this project's tests; the logic above it is host-tested in firmware/core.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_device_controller.hpp"
#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"
#include "tetrapulse/fw/usb/usb_message_function.hpp"
#include "tetrapulse/stm32f405/usb_fifo_plan.hpp"

namespace tetrapulse::stm32f405 {

class UsbOtgFs final : public fw::UsbDeviceController, public fw::UsbPipe {
 public:
  // Not constexpr on purpose: a constant-initialised object with a vtable lands in .data
  // and costs its whole size in flash as well (its copy there); this one is built at first
  // use in zeroed RAM (.bss) instead.
  UsbOtgFs();
  // Starts the core in device mode and connects to the bus (D+ pull-up). The 48 MHz USB
  // clock must run (Clocks::usb_clock_ok). `bulk`: where bulk OUT packets go (null in the
  // bootloader, which has no bulk endpoints). False when the descriptors' bulk addresses
  // name no endpoint of this core, or the core does not come out of reset or device mode;
  // then nothing is connected.
  bool start(fw::UsbEndpointZero& ep0, fw::UsbControl& control, fw::UsbMessageFunction* bulk,
             const fw::LocalClock& clock);
  bool running() const { return running_; }

  // Main loop: handles every event the core has pending.
  void poll();
  // Soft disconnect: the host sees the device unplugged (DFU detach, before a reset).
  void disconnect();
  bool suspended() const { return suspended_; }
  // A bulk IN transfer (or its ZLP) the host has not taken yet.
  bool bulk_in_busy() const { return bulk_in_busy_ || zlp_pending_; }

 private:
  void do_set_address(uint8_t address) override;
  void do_set_configured(bool configured) override;
  void do_set_endpoint_halt(uint8_t endpoint, bool halted) override;
  protocol::Status do_send_bulk(protocol::ByteView transfer) override;

  void on_bus_reset();
  void on_enumeration_done();
  void on_receive_fifo();
  void on_in_endpoints();
  void on_out_endpoints();
  void act(fw::UsbEndpointZero::Action action);
  void arm_ep0_out(bool enable);
  void arm_bulk_out();
  void load_in(unsigned ep, protocol::ByteView data);
  void wait_ms(uint32_t ms) const;

  fw::UsbEndpointZero* ep0_ = nullptr;
  fw::UsbControl* control_ = nullptr;
  fw::UsbMessageFunction* bulk_ = nullptr;
  const fw::LocalClock* clock_ = nullptr;
  BulkEndpoints bulk_ep_;
  bool running_ = false;
  bool configured_ = false;
  bool suspended_ = false;
  bool bulk_in_busy_ = false;
  bool zlp_pending_ = false;
  uint8_t setup_[fw::kUsbSetupSize] = {};
  uint16_t ep0_out_size_ = 0;     // the last EP0 OUT packet (already in place), until its
  bool ep0_out_ready_ = false;    // transfer-complete event
};

}  // namespace tetrapulse::stm32f405

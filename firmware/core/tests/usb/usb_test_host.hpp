#pragma once
// Test support: a USB host's side of control transfers, in two flavours that the device
// code meets in the field:
//   PacketHost    64-byte packets through UsbEndpointZero and UsbControl, with the event
//                 order an STM32 OTG controller reports (SETUP, IN taken, OUT received);
//                 it checks every packet rule of USB 2.0 §8.5.3 on the way
//   FunctionHost  whole stages straight into one UsbFunction, as a Linux FunctionFS gadget
//                 hands over ep0 (the kernel answered the standard requests)
// plus a controller that records what the standard requests asked of it.
#include <cstdint>
#include <string>
#include <vector>

#include "tetrapulse/fw/usb/usb_control.hpp"
#include "tetrapulse/fw/usb/usb_device_controller.hpp"
#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"
#include "tetrapulse/fw/usb/usb_function.hpp"
#include "tetrapulse/fw/usb/usb_setup.hpp"

namespace tetrapulse::fw::testing {

class RecordingController final : public UsbDeviceController {
 public:
  uint8_t address = 0;
  bool configured = false;
  std::vector<std::pair<uint8_t, bool>> halts;  // (endpoint, halted) in call order

 private:
  void do_set_address(uint8_t a) override { address = a; }
  void do_set_configured(bool c) override { configured = c; }
  void do_set_endpoint_halt(uint8_t ep, bool halted) override { halts.emplace_back(ep, halted); }
};

struct ControlResult {
  bool stalled = false;
  std::vector<uint8_t> data;          // IN: the data stage as the host received it
  std::vector<size_t> packet_sizes;   // PacketHost: the data packets, a trailing ZLP included
};

class ControlPipe {
 public:
  virtual ~ControlPipe() = default;
  virtual ControlResult in(const UsbSetup& setup) = 0;
  virtual ControlResult out(const UsbSetup& setup, const std::vector<uint8_t>& data) = 0;
  // USB reset, as the bus delivers it to the device.
  virtual void bus_reset() = 0;
};

class PacketHost final : public ControlPipe {
 public:
  explicit PacketHost(UsbControl& control) : control_(control), ep0_(control) {}
  ControlResult in(const UsbSetup& setup) override;
  ControlResult out(const UsbSetup& setup, const std::vector<uint8_t>& data) override;
  void bus_reset() override;

 private:
  UsbControl& control_;
  UsbEndpointZero ep0_;
};

class FunctionHost final : public ControlPipe {
 public:
  explicit FunctionHost(UsbFunction& function, size_t scratch = 1024) : function_(function), scratch_(scratch) {}
  ControlResult in(const UsbSetup& setup) override;
  ControlResult out(const UsbSetup& setup, const std::vector<uint8_t>& data) override;
  void bus_reset() override { function_.bus_reset(); }

 private:
  UsbFunction& function_;
  std::vector<uint8_t> scratch_;
};

// Setup packets.
UsbSetup standard_in(UsbRecipient to, uint8_t request, uint16_t value, uint16_t index, uint16_t length);
UsbSetup standard_out(UsbRecipient to, uint8_t request, uint16_t value, uint16_t index);
UsbSetup get_descriptor(uint8_t type, uint8_t index, uint16_t length, uint16_t language = 0);
UsbSetup class_in(uint8_t request, uint16_t value, uint16_t interface, uint16_t length);
UsbSetup class_out(uint8_t request, uint16_t value, uint16_t interface, uint16_t length);
UsbSetup vendor_in(uint8_t request, uint16_t interface, uint16_t length);
UsbSetup vendor_out(uint8_t request, uint16_t interface, uint16_t length);

// What Linux does on plugging the device in: device descriptor (64), address, device
// descriptor, configuration (9, then whole), strings 0, 2, 1, 3 (255 each), configuration
// 1. Fails the test on any stall; returns the whole configuration descriptor.
std::vector<uint8_t> enumerate(ControlPipe& host, RecordingController& controller);

// A string descriptor's text (ASCII only).
std::string string_of(const std::vector<uint8_t>& descriptor);

}  // namespace tetrapulse::fw::testing

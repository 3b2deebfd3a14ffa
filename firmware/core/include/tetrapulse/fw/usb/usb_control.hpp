#pragma once
// The control endpoint of a tetrapulse USB device (SPEC.md §5): the standard requests of
// USB 2.0 chapter 9, answered from the protocol's descriptor builders (one parameter set
// for the STM32 firmware, the Linux gadget and the tests), and every class or vendor
// request to an interface routed to the UsbFunction behind that interface:
//   application (PID 0x0001): interface 0 messages (UsbMessageFunction), 1 DFU run-time
//   bootloader  (PID 0x0002): interface 0 DFU mode
//
// Standard requests answered: GET_STATUS (device, interface, endpoint), CLEAR_FEATURE /
// SET_FEATURE (ENDPOINT_HALT), SET_ADDRESS, GET_DESCRIPTOR (device, configuration,
// strings 0..4), GET_CONFIGURATION, SET_CONFIGURATION (0 or 1), GET_INTERFACE /
// SET_INTERFACE (alternate setting 0). Everything else is stalled: remote wakeup (not
// offered), SET_DESCRIPTOR, device qualifier and other-speed descriptors (full speed
// only), requests to interfaces or endpoints before the device is configured.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/usb/usb_device_controller.hpp"
#include "tetrapulse/fw/usb/usb_function.hpp"
#include "tetrapulse/fw/usb/usb_setup.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

namespace tetrapulse::fw {

class UsbControl {
 public:
  static constexpr uint8_t kMaxInterfaces = 2;
  // Smallest answer buffer: a configuration descriptor (50 bytes) or a string (50).
  static constexpr size_t kMinBuffer = protocol::kUsbMaxConfigurationSize;

  // `serial`: the serial-number string (ASCII, NUL-terminated; lives as long as this).
  // `buffer`: caller-owned room for the answers of device-to-host requests, also the
  // functions' scratch (>= kMinBuffer; the message function needs kMaxMessageSize).
  UsbControl(const protocol::UsbDeviceParams& params, const char* serial, UsbDeviceController& controller,
             uint8_t* buffer, size_t capacity);

  // The function behind interface `number` (< the mode's interface count).
  void set_function(uint8_t number, UsbFunction& function);

  // The three stages of a control transfer (usb_function.hpp), as the controller sees them.
  UsbControlReply setup(const UsbSetup& setup);
  bool data_out(const UsbSetup& setup, protocol::ByteView data);
  void status_complete(const UsbSetup& setup);
  // USB reset: address 0, not configured, every function back to its initial state.
  void bus_reset();

  bool configured() const { return configuration_ != 0; }
  uint8_t interface_count() const;
  const protocol::UsbDeviceParams& params() const { return params_; }

 private:
  UsbControlReply standard_device(const UsbSetup& setup);
  UsbControlReply standard_interface(const UsbSetup& setup);
  UsbControlReply standard_endpoint(const UsbSetup& setup);
  UsbControlReply descriptor(const UsbSetup& setup);
  UsbControlReply send_built(const protocol::Result<size_t>& built);
  UsbControlReply send_bytes(const uint8_t* bytes, size_t size);
  // The function a class/vendor request goes to, or null.
  UsbFunction* function_for(const UsbSetup& setup) const;
  // Bit of a bulk endpoint address in halted_, 0 when it is not one of ours.
  uint8_t endpoint_bit(uint16_t endpoint) const;
  void set_configuration(uint8_t value);

  protocol::UsbDeviceParams params_;
  const char* serial_;
  UsbDeviceController& controller_;
  uint8_t* buffer_;
  size_t capacity_;
  UsbFunction* functions_[kMaxInterfaces] = {};
  uint8_t configuration_ = 0;
  uint8_t halted_ = 0;  // bit 0 bulk OUT, bit 1 bulk IN
};

}  // namespace tetrapulse::fw

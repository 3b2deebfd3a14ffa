#pragma once
// One function of a USB device: the class and vendor control requests addressed to its
// interface (the tetrapulse message interface, DFU). The same functions run behind the
// STM32's own control endpoint (UsbControl answers the standard requests and routes the
// rest here) and behind a Linux FunctionFS gadget (the kernel answers the standard
// requests; the gadget hands the ep0 SETUP events of its interfaces to these calls).
//
// A control transfer, as a function sees it:
//   setup()            the SETUP packet; the reply says what the data stage does
//   data_out()         host-to-device requests with a data stage: the whole data stage
//   status_complete()  the status stage is done: the host has the answer (or the ack)
// A request is stalled (reply kStall, or data_out() returning false) when it is not
// valid now; the host sees a STALL handshake and the next SETUP starts afresh.
#include <cstddef>
#include <cstdint>

#include "tetrapulse/fw/usb/usb_setup.hpp"
#include "tetrapulse/protocol/bytes.hpp"

namespace tetrapulse::fw {

struct UsbControlReply {
  enum class Kind : uint8_t {
    kStall,    // refuse the request
    kSend,     // device-to-host: `data`, `size` bytes (the controller sends at most wLength)
    kReceive,  // host-to-device with data: receive wLength bytes into `buffer`
    kAccept,   // no data stage: acknowledge in the status stage
  };
  Kind kind = Kind::kStall;
  const uint8_t* data = nullptr;  // kSend: valid until status_complete() (or the next setup)
  size_t size = 0;                // kSend: bytes to send; kReceive: capacity of `buffer`
  uint8_t* buffer = nullptr;      // kReceive: where the data stage goes

  static UsbControlReply stall() { return UsbControlReply{}; }
  static UsbControlReply send(const uint8_t* data, size_t size) { return UsbControlReply{Kind::kSend, data, size, nullptr}; }
  static UsbControlReply receive(uint8_t* buffer, size_t capacity) {
    return UsbControlReply{Kind::kReceive, nullptr, capacity, buffer};
  }
  static UsbControlReply accept() { return UsbControlReply{Kind::kAccept, nullptr, 0, nullptr}; }
};

class UsbFunction {
 public:
  // The SETUP of a class or vendor request to this function's interface. `scratch` is the
  // caller's, untouched until the next setup, for the answer of a device-to-host request
  // (the message function needs kMaxMessageSize bytes, DFU 6 and its transfer size for
  // UPLOAD); a function stalls what does not fit.
  UsbControlReply setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
    return do_setup(setup, scratch, capacity);
  }
  // The data stage of a host-to-device request whose setup() answered kReceive (`data`
  // lies in that reply's buffer, data.size <= wLength). False stalls the status stage.
  bool data_out(const UsbSetup& setup, protocol::ByteView data) { return do_data_out(setup, data); }
  // The status stage of `setup` completed.
  void status_complete(const UsbSetup& setup) { do_status_complete(setup); }
  // USB bus reset, or the configuration was set or cleared: back to the initial state.
  void bus_reset() { do_bus_reset(); }

 protected:
  ~UsbFunction() = default;

 private:
  virtual UsbControlReply do_setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) = 0;
  virtual bool do_data_out(const UsbSetup& setup, protocol::ByteView data) = 0;
  virtual void do_status_complete(const UsbSetup& setup) = 0;
  virtual void do_bus_reset() = 0;
};

}  // namespace tetrapulse::fw

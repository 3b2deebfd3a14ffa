#pragma once
// Interface 0 of the application (SPEC.md §5.3, §5.4): protocol messages over the vendor
// control requests PROTOCOL_INFO, MESSAGE_OUT and MESSAGE_IN, and over the bulk
// endpoints' framing; both paths end in UsbLink, which hands messages to the firmware and
// queues the answers of MESSAGE_OUT requests for MESSAGE_IN.
//
// Stalled (the host retries or gives up): an unknown request; PROTOCOL_INFO with wLength
// under 8; MESSAGE_OUT with wLength outside 3..320, or while the answer queue is full;
// MESSAGE_IN with wLength shorter than the pending message (it stays pending).
#include <cstdint>

#include "tetrapulse/fw/clock/local_clock.hpp"
#include "tetrapulse/fw/links/message_link.hpp"
#include "tetrapulse/fw/links/usb_link.hpp"
#include "tetrapulse/fw/usb/usb_function.hpp"

namespace tetrapulse::fw {

class UsbMessageFunction final : public UsbFunction {
 public:
  // `capabilities`: the PROTOCOL_INFO bits (protocol::kUsbCapability*). Messages are
  // stamped with `clock` at their arrival and go to `sink`.
  UsbMessageFunction(UsbLink& link, MessageSink& sink, const LocalClock& clock, uint32_t capabilities);

  // One packet from the bulk OUT endpoint (the driver's glue to the bulk framing).
  void on_bulk_packet(protocol::ByteView packet);

 private:
  UsbControlReply do_setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) override;
  bool do_data_out(const UsbSetup& setup, protocol::ByteView data) override;
  void do_status_complete(const UsbSetup&) override {}
  void do_bus_reset() override {}

  UsbLink& link_;
  MessageSink& sink_;
  const LocalClock& clock_;
  uint32_t capabilities_;
};

}  // namespace tetrapulse::fw

#include "tetrapulse/fw/usb/usb_message_function.hpp"

#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/usb_device.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;

UsbMessageFunction::UsbMessageFunction(UsbLink& link, MessageSink& sink, const LocalClock& clock,
                                       uint32_t capabilities)
    : link_(link), sink_(sink), clock_(clock), capabilities_(capabilities) {}

void UsbMessageFunction::on_bulk_packet(tp::ByteView packet) { link_.on_bulk_packet(packet, clock_.now(), sink_); }

UsbControlReply UsbMessageFunction::do_setup(const UsbSetup& setup, uint8_t* scratch, size_t capacity) {
  if (setup.type() != UsbRequestType::kVendor || setup.value != 0) return UsbControlReply::stall();
  const bool in = setup.device_to_host();
  switch (static_cast<tp::UsbVendorRequest>(setup.request)) {
    case tp::UsbVendorRequest::kProtocolInfo: {
      if (!in || setup.length < tp::kUsbProtocolInfoSize) break;
      tp::UsbProtocolInfo info;
      info.capabilities = capabilities_;
      const tp::Result<size_t> n = tp::encode_usb_protocol_info(info, scratch, capacity);
      if (!n) break;
      return UsbControlReply::send(scratch, *n);
    }
    case tp::UsbVendorRequest::kMessageOut:
      if (in || setup.length < tp::kMessageHeaderSize || setup.length > tp::kMaxMessageSize) break;
      if (link_.control_queue_full() || capacity < setup.length) break;
      return UsbControlReply::receive(scratch, capacity);
    case tp::UsbVendorRequest::kMessageIn: {
      if (!in) break;
      const size_t room = setup.length < capacity ? setup.length : capacity;
      const tp::Result<size_t> n = link_.take_control_response(scratch, room);
      if (!n) break;  // longer than wLength: it stays pending
      return UsbControlReply::send(scratch, *n);
    }
  }
  return UsbControlReply::stall();
}

bool UsbMessageFunction::do_data_out(const UsbSetup& setup, tp::ByteView data) {
  if (static_cast<tp::UsbVendorRequest>(setup.request) != tp::UsbVendorRequest::kMessageOut) return false;
  if (data.size != setup.length) return false;  // a short data stage: not the message announced
  link_.on_control_message(data, clock_.now(), sink_);
  return true;
}

}  // namespace tetrapulse::fw

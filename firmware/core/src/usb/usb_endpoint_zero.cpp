#include "tetrapulse/fw/usb/usb_endpoint_zero.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;
using Kind = UsbControlReply::Kind;

namespace {
constexpr size_t kPacket = tp::kUsbMaxPacketSize;
}

void UsbEndpointZero::reset() {
  stage_ = Stage::kIdle;
  reply_ = UsbControlReply::stall();
  total_ = sent_ = packet_ = 0;
  zlp_ = false;
}

tp::ByteView UsbEndpointZero::in_packet() const {
  if (stage_ != Stage::kDataIn || reply_.data == nullptr) return tp::ByteView{};
  return tp::ByteView{reply_.data + (sent_ - packet_), packet_};
}

UsbEndpointZero::Action UsbEndpointZero::on_setup(const uint8_t (&packet)[kUsbSetupSize]) {
  reset();  // a SETUP ends whatever transfer was in progress
  setup_ = decode_usb_setup(packet);
  reply_ = control_.setup(setup_);
  switch (reply_.kind) {
    case Kind::kSend: {
      if (!setup_.device_to_host()) break;
      if (setup_.length == 0) {  // no data stage: the status stage is IN (USB 2.0 §8.5.3)
        stage_ = Stage::kStatusIn;
        return Action::kSendStatus;
      }
      total_ = reply_.size < setup_.length ? reply_.size : setup_.length;
      zlp_ = total_ < setup_.length && total_ % kPacket == 0;  // also a zero-length data stage
      stage_ = Stage::kDataIn;
      packet_ = total_ < kPacket ? total_ : kPacket;
      sent_ = packet_;
      if (packet_ == 0) zlp_ = false;  // this packet is the zero-length one
      return Action::kSendPacket;
    }
    case Kind::kReceive:
      if (setup_.device_to_host() || reply_.buffer == nullptr || reply_.size < setup_.length) break;
      if (setup_.length == 0) return finish_out_stage();
      stage_ = Stage::kDataOut;
      return Action::kReceivePacket;
    case Kind::kAccept:
      if (setup_.device_to_host() && setup_.length != 0) break;  // an IN request needs its data
      stage_ = Stage::kStatusIn;
      return Action::kSendStatus;
    case Kind::kStall:
      break;
  }
  reset();
  return Action::kStall;
}

UsbEndpointZero::Action UsbEndpointZero::on_in_complete() {
  switch (stage_) {
    case Stage::kDataIn:
      if (sent_ < total_) {
        const size_t left = total_ - sent_;
        packet_ = left < kPacket ? left : kPacket;
        sent_ += packet_;
        return Action::kSendPacket;
      }
      if (zlp_) {
        zlp_ = false;
        packet_ = 0;
        return Action::kSendPacket;
      }
      stage_ = Stage::kStatusOut;
      return Action::kReceiveStatus;
    case Stage::kStatusIn:
      return status_done();
    default:
      return Action::kNone;
  }
}

uint8_t* UsbEndpointZero::out_target(size_t* room) {
  if (stage_ != Stage::kDataOut) {
    *room = 0;
    return reply_.buffer;
  }
  const size_t left = setup_.length - total_;
  *room = left < kPacket ? left : kPacket;
  return reply_.buffer + total_;
}

UsbEndpointZero::Action UsbEndpointZero::on_out_packet(tp::ByteView packet) {
  size_t room = 0;
  uint8_t* into = out_target(&room);
  if (packet.size <= room) {
    for (size_t i = 0; i < packet.size; ++i) into[i] = packet[i];
  }
  return on_out_received(packet.size);
}

UsbEndpointZero::Action UsbEndpointZero::on_out_received(size_t size) {
  switch (stage_) {
    case Stage::kDataOut:
      return take_out(size);
    case Stage::kDataIn:    // the host ended the data stage early (it had what it wanted)
    case Stage::kStatusOut:
      return status_done();
    default:
      return Action::kNone;
  }
}

UsbEndpointZero::Action UsbEndpointZero::take_out(size_t size) {
  if (size > kPacket || size > setup_.length - total_) {
    reset();
    return Action::kStall;
  }
  total_ += size;
  if (total_ < setup_.length && size == kPacket) return Action::kReceivePacket;
  return finish_out_stage();
}

UsbEndpointZero::Action UsbEndpointZero::finish_out_stage() {
  if (!control_.data_out(setup_, tp::ByteView{reply_.buffer, total_})) {
    reset();
    return Action::kStall;
  }
  stage_ = Stage::kStatusIn;
  return Action::kSendStatus;
}

UsbEndpointZero::Action UsbEndpointZero::status_done() {
  const UsbSetup done = setup_;
  reset();
  control_.status_complete(done);
  return Action::kNone;
}

}  // namespace tetrapulse::fw

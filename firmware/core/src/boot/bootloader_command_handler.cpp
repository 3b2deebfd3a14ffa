#include "tetrapulse/fw/boot/bootloader_command_handler.hpp"

#include "tetrapulse/fw/app/board_state.hpp"
#include "tetrapulse/fw/storage/flash_layout.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::fw {

namespace tp = protocol;
using tp::Body;
using tp::Error;
using tp::MessageType;
using tp::Result;

BootloaderCommandHandler::BootloaderCommandHandler(UpdateReceiver& update, const BootloaderIdentity& identity,
                                                   const LocalClock& clock, const CanLink* can)
    : update_(update), identity_(identity), clock_(clock), can_(can) {}

uint64_t BootloaderCommandHandler::uptime_ms() const {
  const uint32_t per_ms = clock_.tick_hz() / 1000u;
  return per_ms == 0 ? 0 : clock_.now() / per_ms;
}

tp::StatusReport BootloaderCommandHandler::status() const {
  tp::StatusReport s;
  s.rx_malformed = rx_malformed_;
  if (can_ != nullptr) {
    s.can_errors = can_->bus_errors();
    s.can_bus_off = can_->bus_off() ? 1 : 0;
  }
  s.flash_errors = update_.flash_errors();
  s.last_error = last_error_;
  s.update_state = update_.state();
  s.uptime_ms = uptime_ms();
  return s;
}

size_t BootloaderCommandHandler::handle(tp::ByteView message, uint8_t* out, size_t capacity) {
  if (message.size < tp::kMessageHeaderSize) {
    bump(rx_malformed_);
    return 0;
  }
  const auto type = static_cast<MessageType>(message[1]);
  const uint8_t seq = message[2];
  tp::ByteWriter w(out, capacity);
  const Result<tp::Message> decoded = tp::decode(message);
  if (!decoded) {
    bump(rx_malformed_);
    last_error_ = decoded.error();
    if (!tp::is_request(type) && tp::is_defined(type)) return 0;  // broken broadcasts and responses
    return tp::encode(tp::Message{seq, tp::ErrorResponse{type, decoded.error(), 0}}, w) ? w.size() : 0;
  }
  if (!tp::is_request(type)) return 0;
  uint16_t detail = 0;
  const Result<Body> result = execute(*decoded, &detail);
  if (!result) {
    last_error_ = result.error();
    reboot_requested_ = false;
    return tp::encode(tp::Message{seq, tp::ErrorResponse{type, result.error(), detail}}, w) ? w.size() : 0;
  }
  return tp::encode(tp::Message{seq, *result}, w) ? w.size() : 0;
}

Result<Body> BootloaderCommandHandler::execute(const tp::Message& request, uint16_t* detail) {
  const MessageType type = request.type();
  const auto ack = [type](uint32_t value) { return Body{tp::Ack{type, value}}; };
  switch (type) {
    case MessageType::kGetInfo: {
      tp::Info info;
      info.hw_model = identity_.hw_model;
      info.hw_revision = identity_.hw_revision;
      info.fw_version = 0;  // no application runs
      info.bootloader_version = identity_.bootloader_version;
      info.serial = identity_.serial;
      info.uptime_ms = uptime_ms();
      info.capabilities = identity_.capabilities;
      info.node_id = identity_.node_id;
      info.active_slot = kNoSlot;
      info.max_code_length = static_cast<uint8_t>(tp::kMaxCodeLength);
      return Body{info};
    }
    case MessageType::kGetStatus:
      return Body{status()};
    case MessageType::kReboot:
      reboot_requested_ = true;
      reboot_mode_ = request.get<tp::Reboot>()->mode;
      return ack(0);
    case MessageType::kUpdateBegin: {
      const Result<uint32_t> r = update_.begin(*request.get<tp::UpdateBegin>());
      return r ? ack(*r) : Result<Body>(r.error());
    }
    case MessageType::kUpdateChunk: {
      const Result<uint32_t> r = update_.chunk(*request.get<tp::UpdateChunk>(), detail);
      return r ? ack(*r) : Result<Body>(r.error());
    }
    case MessageType::kUpdateVerify: {
      const Result<uint32_t> r = update_.verify();
      return r ? ack(*r) : Result<Body>(r.error());
    }
    case MessageType::kUpdateAbort: {
      const tp::Status s = update_.abort();
      return s ? ack(0) : Result<Body>(s.error());
    }
    default:
      return Error::kNotSupported;
  }
}

void BootloaderCommandHandler::do_on_message(const ReceivedMessage& message) {
  uint8_t out[tp::kMaxMessageSize];
  const size_t n = handle(message.bytes, out, sizeof(out));
  if (n > 0 && message.link != nullptr) message.link->send(message.reply, tp::ByteView{out, n});
}

}  // namespace tetrapulse::fw

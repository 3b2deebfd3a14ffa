#include "board_responder.hpp"

#include <algorithm>

#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::host::testing {

using protocol::Error;
using protocol::Message;
using protocol::MessageType;

BoardResponder::BoardResponder(ResponderIdentity identity)
    : identity_(identity), running_(protocol::default_config()), stored_(protocol::default_config()) {
  running_.node_id = stored_.node_id = identity.node_id;
}

Message BoardResponder::ack(const Message& request, uint32_t value) const {
  return Message{request.seq, protocol::Ack{request.type(), value}};
}

Message BoardResponder::refuse(const Message& request, Error error, uint16_t detail) const {
  return Message{request.seq, protocol::ErrorResponse{request.type(), error, detail}};
}

std::optional<std::vector<uint8_t>> BoardResponder::answer(protocol::ByteView received, int64_t now_ns) {
  std::optional<Message> reply;
  const protocol::Result<Message> decoded = protocol::decode(received);
  if (decoded) {
    reply = handle(*decoded, now_ns);
  } else {
    ++malformed_;
    const auto type = received.size >= 2 ? static_cast<MessageType>(received[1]) : MessageType::kGetInfo;
    // SPEC.md §3: answer requests and undefined types; drop time sync, responses, runts.
    if (received.size >= 3 && (protocol::is_request(type) || !protocol::is_defined(type))) {
      reply = Message{received[2], protocol::ErrorResponse{type, decoded.error(), 0}};
      last_error_ = decoded.error();
    }
  }
  if (!reply) return std::nullopt;
  std::vector<uint8_t> out(protocol::kMaxMessageSize);
  protocol::ByteWriter writer(out.data(), out.size());
  if (!protocol::encode(*reply, writer)) return std::nullopt;
  out.resize(writer.size());
  return out;
}

protocol::Info BoardResponder::info(int64_t now_ns) const {
  protocol::Info i;
  i.hw_model = identity_.hw_model;
  i.hw_revision = identity_.hw_revision;
  i.fw_version = identity_.fw_version;
  i.bootloader_version = 0x01000000;
  i.serial = identity_.serial;
  i.uptime_ms = static_cast<uint64_t>((now_ns - boot_ns_) / 1'000'000);
  i.capabilities = identity_.capabilities;
  i.node_id = running_.node_id;
  i.active_slot = identity_.active_slot;
  i.max_code_length = protocol::kMaxCodeLength;
  return i;
}

protocol::StatusReport BoardResponder::status(int64_t now_ns) const {
  protocol::StatusReport s;
  s.sync_source = running_.sync_source;
  s.sync_accepted = static_cast<uint32_t>(sync_samples_.size());
  s.rx_malformed = static_cast<uint16_t>(std::min<uint32_t>(malformed_, 0xFFFF));
  s.last_error = last_error_;
  s.update_state = update_state_;
  s.uptime_ms = static_cast<uint64_t>((now_ns - boot_ns_) / 1'000'000);
  return s;
}

std::optional<Message> BoardResponder::handle(const Message& m, int64_t now_ns) {
  if (!booted_) {
    boot_ns_ = now_ns;
    booted_ = true;
  }
  switch (m.type()) {
    case MessageType::kGetInfo: return Message{m.seq, info(now_ns)};
    case MessageType::kGetConfig: return Message{m.seq, protocol::ConfigReport{running_}};
    case MessageType::kSetConfig:
      if (refuse_configs_) return refuse(m, Error::kNotSupported);
      running_ = m.get<protocol::SetConfig>()->config;
      return ack(m);
    case MessageType::kGetStatus: return Message{m.seq, status(now_ns)};
    case MessageType::kIdentify: identify_ = m.get<protocol::Identify>()->pattern; return ack(m);
    case MessageType::kPersistConfig:
      if (update_state_ == protocol::UpdateState::kReceiving) return refuse(m, Error::kAccessDenied);
      stored_ = running_;
      return ack(m);
    case MessageType::kFactoryReset:
      if (update_state_ == protocol::UpdateState::kReceiving) return refuse(m, Error::kAccessDenied);
      running_ = stored_ = protocol::default_config();
      return ack(m);
    case MessageType::kReboot: return reboot(m, now_ns);
    case MessageType::kUpdateBegin: return update_begin(m, *m.get<protocol::UpdateBegin>());
    case MessageType::kUpdateChunk: return update_chunk(m, *m.get<protocol::UpdateChunk>());
    case MessageType::kUpdateVerify: return update_verify(m);
    case MessageType::kUpdateAbort:
      update_state_ = protocol::UpdateState::kIdle;
      image_.clear();
      return ack(m);
    case MessageType::kGetLedLog: {
      protocol::LedLog log;  // plays no codes: an empty log that starts where asked
      log.next = m.get<protocol::GetLedLog>()->first;
      return Message{m.seq, log};
    }
    case MessageType::kSync:
      last_sync_ = std::make_pair(m.get<protocol::Sync>()->sync_seq, now_ns);
      return std::nullopt;
    case MessageType::kFollowUp: {
      const auto* f = m.get<protocol::FollowUp>();
      if (last_sync_ && last_sync_->first == f->sync_seq) {
        sync_samples_.push_back(SyncSample{f->sync_seq, last_sync_->second, f->tx_time_ns});
      }
      return std::nullopt;
    }
    default: return std::nullopt;  // responses are never answered
  }
}

Message BoardResponder::reboot(const Message& m, int64_t now_ns) {
  const auto mode = m.get<protocol::Reboot>()->mode;
  if (mode == protocol::RebootMode::kApplication && update_state_ == protocol::UpdateState::kVerified) {
    identity_.active_slot = static_cast<uint8_t>(1 - identity_.active_slot);
    identity_.fw_version = installed_version_;
  }
  update_state_ = protocol::UpdateState::kIdle;
  running_ = stored_;
  identify_ = protocol::IdentifyPattern::kStop;
  boot_ns_ = now_ns;
  ++reboots_;
  return ack(m);
}

Message BoardResponder::update_begin(const Message& m, const protocol::UpdateBegin& begin) {
  if (begin.image_size > identity_.slot_capacity) return refuse(m, Error::kImageRejected);
  update_ = begin;
  image_.assign(begin.image_size, 0xFF);
  next_offset_ = 0;
  last_chunk_length_ = 0;
  update_state_ = protocol::UpdateState::kReceiving;
  return ack(m, 0);
}

Message BoardResponder::update_chunk(const Message& m, const protocol::UpdateChunk& chunk) {
  if (update_state_ != protocol::UpdateState::kReceiving) return refuse(m, Error::kInvalidState);
  if (last_chunk_length_ != 0 && chunk.offset == last_chunk_offset_ && chunk.length == last_chunk_length_) {
    ++chunk_repeats_;  // the host lost our Ack: acknowledge again, write nothing
    return ack(m, chunk.offset + chunk.length);
  }
  if (chunk.offset != next_offset_ || uint64_t{chunk.offset} + chunk.length > update_.image_size) {
    return refuse(m, Error::kInvalidState, static_cast<uint16_t>(next_offset_));
  }
  std::copy(chunk.data.begin(), chunk.data.begin() + chunk.length, image_.begin() + chunk.offset);
  next_offset_ += chunk.length;
  last_chunk_offset_ = chunk.offset;
  last_chunk_length_ = chunk.length;
  ++chunks_written_;
  return ack(m, next_offset_);
}

Message BoardResponder::update_verify(const Message& m) {
  if (update_state_ != protocol::UpdateState::kReceiving || next_offset_ != update_.image_size) {
    return refuse(m, Error::kInvalidState);
  }
  const protocol::ByteView image{image_.data(), image_.size()};
  const uint32_t crc = protocol::crc32c(image_.data(), image_.size());
  const protocol::Result<protocol::ImageHeader> header = protocol::decode_image_header(image);
  const uint8_t inactive = static_cast<uint8_t>(1 - identity_.active_slot);
  const bool ok = crc == update_.crc32c && header.ok() &&
                  protocol::fits(*header, identity_.hw_model, identity_.hw_revision).ok() &&
                  header->load_address == identity_.slot_base[inactive] &&
                  protocol::image_size(*header) == update_.image_size &&
                  protocol::check_payload(*header, image).ok() && header->fw_version == update_.version;
  if (!ok) {
    update_state_ = protocol::UpdateState::kFailed;
    last_error_ = Error::kImageRejected;
    return refuse(m, Error::kImageRejected);
  }
  update_state_ = protocol::UpdateState::kVerified;
  installed_ = image_;
  installed_version_ = header->fw_version;
  return ack(m, crc);
}

}  // namespace tetrapulse::host::testing

#include "tetrapulse/fw/app/command_handler.hpp"

#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/protocol/limits.hpp"

namespace tetrapulse::fw {

using protocol::Body;
using protocol::Error;
using protocol::MessageType;
using protocol::Result;

namespace {

Body ack(MessageType request, uint32_t value = 0) { return protocol::Ack{request, value}; }

size_t write_reply(uint8_t seq, const Body& body, uint8_t* out, size_t capacity) {
  protocol::ByteWriter w(out, capacity);
  const protocol::Message m{seq, body};
  return protocol::encode(m, w) ? w.size() : 0;
}

}  // namespace

CommandReply CommandHandler::handle(protocol::ByteView message, Tick rx_tick, LinkKind link, uint8_t* out,
                                    size_t capacity) {
  CommandReply reply;
  Diagnostics& diag = board_.diagnostics();
  if (message.size < protocol::kMessageHeaderSize) {
    bump(diag.rx_malformed);
    return reply;
  }
  const auto type = static_cast<MessageType>(message[1]);
  const uint8_t seq = message[2];
  const Result<protocol::Message> decoded = protocol::decode(message);
  if (!decoded) {
    bump(diag.rx_malformed);
    diag.last_error = decoded.error();
    // Requests and undefined codes are answered (SPEC.md §3); broken time-sync messages
    // and responses are only counted.
    if (protocol::is_request(type) || !protocol::is_defined(type)) {
      reply.size = write_reply(seq, protocol::ErrorResponse{type, decoded.error(), 0}, out, capacity);
      board_.answered_request = true;
    }
    return reply;
  }
  const protocol::Message& m = *decoded;
  if (const auto* sync = m.get<protocol::Sync>()) {
    board_.sync().on_sync(sync->sync_seq, rx_tick, link);
    return reply;
  }
  if (const auto* follow_up = m.get<protocol::FollowUp>()) {
    board_.sync().on_follow_up(follow_up->sync_seq, follow_up->tx_time_ns, rx_tick, link);
    return reply;
  }
  if (!protocol::is_request(type)) return reply;  // a response: boards never answer those

  uint16_t detail = 0;
  const Result<Body> result = execute(m, reply, &detail);
  board_.answered_request = true;
  if (!result) {
    diag.last_error = result.error();
    reply.reboot = false;
    reply.size = write_reply(seq, protocol::ErrorResponse{type, result.error(), detail}, out, capacity);
    return reply;
  }
  reply.size = write_reply(seq, *result, out, capacity);
  return reply;
}

Result<Body> CommandHandler::execute(const protocol::Message& request, CommandReply& reply, uint16_t* detail) {
  const Tick now = board_.clock().now();
  const MessageType type = request.type();
  switch (type) {
    case MessageType::kGetInfo: {
      const FirmwareParts& parts = board_.parts();
      protocol::Info info;
      info.hw_model = board_.system().hw_model();
      info.hw_revision = board_.system().hw_revision();
      info.fw_version = parts.board.fw_version;
      info.bootloader_version = board_.system().bootloader_version();
      info.serial = board_.system().unique_id();
      info.uptime_ms = board_.uptime_ms(now);
      info.capabilities = parts.board.capabilities;
      info.node_id = board_.config().node_id;
      info.active_slot = parts.board.active_slot;
      info.max_code_length = static_cast<uint8_t>(protocol::kMaxCodeLength);
      return Body{info};
    }
    case MessageType::kGetConfig:
      return Body{protocol::ConfigReport{board_.config()}};
    case MessageType::kSetConfig: {
      const protocol::Config& config = request.get<protocol::SetConfig>()->config;
      const protocol::Status supported = board_.supports(config);
      if (!supported) return supported.error();
      board_.apply_config(config, now);
      return ack(type);
    }
    case MessageType::kGetStatus:
      return Body{board_.status(now)};
    case MessageType::kIdentify: {
      const protocol::Identify& identify = *request.get<protocol::Identify>();
      if (identify.pattern == protocol::IdentifyPattern::kStop) {
        board_.player().stop_identify();
        return ack(type);
      }
      const ClockMapping& clock = board_.sync().servo().mapping();
      const Tick until =
          identify.duration_ms == 0 ? 0 : now + uint64_t{identify.duration_ms} * (clock.tick_hz() / 1000u);
      board_.player().identify(identify_program(identify.pattern, clock.to_rig(now), board_.duty_ceiling()), until);
      return ack(type);
    }
    case MessageType::kPersistConfig:
    case MessageType::kFactoryReset: {
      if (board_.update().writing()) return Error::kAccessDenied;
      const protocol::Config config =
          type == MessageType::kFactoryReset ? protocol::default_config() : board_.config();
      if (!save_config(board_.store(), config)) {
        bump(board_.diagnostics().flash_errors);
        return Error::kFlashError;
      }
      if (type == MessageType::kFactoryReset) board_.apply_config(config, now);
      return ack(type);
    }
    case MessageType::kReboot:
      reply.reboot = true;
      reply.reboot_mode = request.get<protocol::Reboot>()->mode;
      return ack(type);
    case MessageType::kUpdateBegin: {
      const Result<uint32_t> r = board_.update().begin(*request.get<protocol::UpdateBegin>());
      if (!r) return r.error();
      return ack(type, *r);
    }
    case MessageType::kUpdateChunk: {
      const Result<uint32_t> r = board_.update().chunk(*request.get<protocol::UpdateChunk>(), detail);
      if (!r) return r.error();
      return ack(type, *r);
    }
    case MessageType::kUpdateVerify: {
      const Result<uint32_t> r = board_.update().verify();
      if (!r) return r.error();
      return ack(type, *r);
    }
    case MessageType::kUpdateAbort: {
      const protocol::Status s = board_.update().abort();
      if (!s) return s.error();
      return ack(type);
    }
    case MessageType::kGetLedLog: {
      LedLogRecord records[protocol::kMaxLedLogEntries];
      protocol::LedLog log;
      const size_t n = board_.led_log().read(request.get<protocol::GetLedLog>()->first, records,
                                             protocol::kMaxLedLogEntries, &log.next);
      log.count = static_cast<uint8_t>(n);
      for (size_t i = 0; i < n; ++i) {
        log.entries[i] = protocol::LedLogEntry{records[i].seq, records[i].rig_ns, records[i].marker, records[i].duty};
      }
      return Body{log};
    }
    default:
      return Error::kNotSupported;
  }
}

}  // namespace tetrapulse::fw

#include "tetrapulse/protocol/message_type.hpp"

#include "body_visit.hpp"

namespace tetrapulse::protocol {

const char* message_name(MessageType t) {
  switch (t) {
    case MessageType::kGetInfo: return "get_info";
    case MessageType::kGetConfig: return "get_config";
    case MessageType::kSetConfig: return "set_config";
    case MessageType::kGetStatus: return "get_status";
    case MessageType::kIdentify: return "identify";
    case MessageType::kPersistConfig: return "persist_config";
    case MessageType::kFactoryReset: return "factory_reset";
    case MessageType::kReboot: return "reboot";
    case MessageType::kUpdateBegin: return "update_begin";
    case MessageType::kUpdateChunk: return "update_chunk";
    case MessageType::kUpdateVerify: return "update_verify";
    case MessageType::kUpdateAbort: return "update_abort";
    case MessageType::kGetLedLog: return "get_led_log";
    case MessageType::kSync: return "sync";
    case MessageType::kFollowUp: return "follow_up";
    case MessageType::kAck: return "ack";
    case MessageType::kInfo: return "info";
    case MessageType::kConfigReport: return "config_report";
    case MessageType::kStatusReport: return "status_report";
    case MessageType::kLedLog: return "led_log";
    case MessageType::kErrorResponse: return "error_response";
  }
  return "unknown";
}

bool is_defined(MessageType t) {
  Body body;
  return detail::emplace_type(body, t);
}

MessageType Message::type() const {
  return detail::visit_body(body, [](const auto& b) { return std::decay_t<decltype(b)>::kType; });
}

}  // namespace tetrapulse::protocol

// The value ranges of SPEC.md §2, checked by encode before writing and by decode after reading.
#include "body_visit.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol {
namespace {

// Messages whose fields take every value.
template <class T>
Status check(const T&) {
  return {};
}

Status check(const SetConfig& m) { return validate(m.config); }
Status check(const ConfigReport& m) { return validate(m.config); }

Status check(const Identify& m) {
  return m.pattern <= IdentifyPattern::kCountIndex ? Status{} : Error::kBadValue;
}

Status check(const Reboot& m) {
  return m.mode <= RebootMode::kBootloader ? Status{} : Error::kBadValue;
}

Status check(const UpdateBegin& m) {
  return m.image_size >= kImageHeaderSize ? Status{} : Error::kBadValue;
}

Status check(const UpdateChunk& m) {
  return m.length >= 1 && m.length <= kMaxUpdateChunk ? Status{} : Error::kBadLength;
}

Status check(const Ack& m) {
  return is_request(m.request_type) && is_defined(m.request_type) ? Status{} : Error::kBadValue;
}

Status check(const Info& m) {
  if (!is_known(m.hw_model)) return Error::kBadValue;
  if (m.node_id < 1 || m.node_id > 254) return Error::kBadValue;
  if (m.max_code_length < 1 || m.max_code_length > kMaxCodeLength) return Error::kBadValue;
  return {};
}

Status check(const StatusReport& m) {
  if (m.sync_state > SyncState::kHoldover) return Error::kBadValue;
  if (m.sync_source > SyncSource::kCan) return Error::kBadValue;
  if (m.can_bus_off > 1) return Error::kBadValue;
  if (m.update_state > UpdateState::kFailed) return Error::kBadValue;
  return {};
}

Status check(const LedLog& m) {
  if (m.count > kMaxLedLogEntries) return Error::kBadLength;
  for (size_t i = 0; i < m.count; ++i) {
    if (m.entries[i].marker >= kMarkersPerTarget) return Error::kBadValue;
  }
  return {};
}

Status check(const ErrorResponse& m) {
  return m.error != Error::kNone ? Status{} : Error::kBadValue;
}

}  // namespace

Status validate(const Message& message) {
  return detail::visit_body(message.body, [](const auto& body) { return check(body); });
}

}  // namespace tetrapulse::protocol

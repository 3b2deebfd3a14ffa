#include "tetrapulse/host/board.hpp"

#include <fmt/format.h>

namespace tetrapulse::host {

using protocol::Body;
using protocol::Message;
using protocol::MessageType;

namespace {

MessageType type_of(const Body& body) { return Message{0, body}.type(); }

}  // namespace

HostError unexpected_answer(const std::string& board, MessageType request, const Message& answer) {
  const char* what = protocol::message_name(request);
  if (const auto* refused = answer.get<protocol::ErrorResponse>()) {
    std::string detail = refused->detail != 0 ? fmt::format(" (detail {})", refused->detail) : std::string();
    return HostError{HostErrorKind::kBoardRefused, board,
                     fmt::format("{}: board refused: {}{}", what, protocol::error_name(refused->error), detail),
                     refused->error};
  }
  return HostError{HostErrorKind::kMalformed, board,
                   fmt::format("{}: answered with {}", what, protocol::message_name(answer.type())),
                   protocol::Error::kBadValue};
}

template <class Response>
HostResult<Response> Board::ask(const Body& request, std::chrono::milliseconds timeout) {
  const MessageType type = type_of(request);
  auto answer = link_->request(request, timeout);
  if (!answer) return tl::unexpected(answer.error());
  const Message& m = answer->message;
  if (const auto* r = m.get<Response>()) {
    if constexpr (std::is_same_v<Response, protocol::Ack>) {
      if (r->request_type != type) return tl::unexpected(unexpected_answer(name(), type, m));
    }
    return *r;
  }
  return tl::unexpected(unexpected_answer(name(), type, m));
}

HostResult<uint32_t> Board::command(const Body& request, std::chrono::milliseconds timeout) {
  auto ack = ask<protocol::Ack>(request, timeout);
  if (!ack) return tl::unexpected(ack.error());
  return ack->value;
}

HostResult<protocol::Info> Board::info() { return ask<protocol::Info>(protocol::GetInfo{}, timeouts_.request); }

HostResult<protocol::Config> Board::config() {
  auto report = ask<protocol::ConfigReport>(protocol::GetConfig{}, timeouts_.request);
  if (!report) return tl::unexpected(report.error());
  return report->config;
}

HostResult<void> Board::configure(const protocol::Config& config) {
  const protocol::Status valid = protocol::validate(config);
  if (!valid) {
    return host_error(HostErrorKind::kBadInput, name(),
                      fmt::format("set_config: configuration not valid: {}", protocol::error_name(valid.error())),
                      valid.error());
  }
  auto done = command(protocol::SetConfig{config}, timeouts_.request);
  if (!done) return tl::unexpected(done.error());
  return {};
}

HostResult<void> Board::identify(protocol::IdentifyPattern pattern, uint16_t duration_ms) {
  auto done = command(protocol::Identify{pattern, duration_ms}, timeouts_.request);
  if (!done) return tl::unexpected(done.error());
  return {};
}

HostResult<void> Board::persist() {
  auto done = command(protocol::PersistConfig{}, timeouts_.flash);
  if (!done) return tl::unexpected(done.error());
  return {};
}

HostResult<void> Board::factory_reset() {
  auto done = command(protocol::FactoryReset{}, timeouts_.flash);
  if (!done) return tl::unexpected(done.error());
  return {};
}

HostResult<void> Board::reboot(protocol::RebootMode mode) {
  auto done = command(protocol::Reboot{mode}, timeouts_.request);
  if (!done) return tl::unexpected(done.error());
  return {};
}

HostResult<protocol::StatusReport> Board::status() {
  return ask<protocol::StatusReport>(protocol::GetStatus{}, timeouts_.request);
}

HostResult<protocol::LedLog> Board::led_log(uint32_t first) {
  return ask<protocol::LedLog>(protocol::GetLedLog{first}, timeouts_.request);
}

}  // namespace tetrapulse::host

#include "body_visit.hpp"
#include "field_io.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol {

Result<Message> decode(ByteView in) {
  ByteReader reader(in);
  const uint8_t version = reader.u8();
  if (!reader.ok()) return reader.error();
  if (version != kProtocolVersion) return Error::kBadVersion;

  const auto type = static_cast<MessageType>(reader.u8());
  if (!reader.ok()) return reader.error();
  Message message;
  if (!detail::emplace_type(message.body, type)) return Error::kUnknownMessage;

  message.seq = reader.u8();
  if (!reader.ok()) return reader.error();

  const Status s = detail::visit_body(message.body, [&](auto& body) {
    return detail::read_exactly(reader, body, [&](const auto&) { return validate(message); });
  });
  if (!s.ok()) return s.error();
  return message;
}

}  // namespace tetrapulse::protocol

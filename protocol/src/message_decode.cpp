#include "body_visit.hpp"
#include "field_io.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol {

Result<Message> decode(ByteView in) {
  size_t stopped_at = 0;
  return decode(in, &stopped_at);
}

Result<Message> decode(ByteView in, size_t* stopped_at) {
  ByteReader reader(in);
  // The reader stays at the start of a field it could not read, and after the last one it read.
  const auto stop = [&](Error e, size_t at) {
    *stopped_at = at;
    return e;
  };
  const uint8_t version = reader.u8();
  if (!reader.ok()) return stop(reader.error(), reader.position());
  if (version != kProtocolVersion) return stop(Error::kBadVersion, 0);

  const auto type = static_cast<MessageType>(reader.u8());
  if (!reader.ok()) return stop(reader.error(), reader.position());
  Message message;
  if (!detail::emplace_type(message.body, type)) return stop(Error::kUnknownMessage, 1);

  message.seq = reader.u8();
  if (!reader.ok()) return stop(reader.error(), reader.position());

  const Status s = detail::visit_body(message.body, [&](auto& body) {
    return detail::read_exactly(reader, body, [&](const auto&) { return validate(message); });
  });
  if (!s.ok()) return stop(s.error(), reader.position());
  return message;
}

}  // namespace tetrapulse::protocol

#include "body_visit.hpp"
#include "field_io.hpp"
#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol {

Status encode(const Message& message, ByteWriter& out) {
  if (const Status s = validate(message); !s.ok()) return s;
  out.u8(kProtocolVersion);
  out.u8(static_cast<uint8_t>(message.type()));
  out.u8(message.seq);
  if (!out.ok()) return Error::kBufferTooSmall;
  return detail::visit_body(message.body, [&](const auto& body) { return detail::write_fields(out, body); });
}

}  // namespace tetrapulse::protocol

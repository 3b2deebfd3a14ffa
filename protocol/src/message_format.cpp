#include "body_visit.hpp"
#include "field_io.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol {

size_t format_message(const Message& message, char* out, size_t capacity) {
  detail::FieldPrinter printer(out, capacity);
  printer.text(message_name(message.type()));
  printer.text(" ");
  printer.field("seq", message.seq);
  detail::visit_body(message.body, [&](const auto& body) {
    using T = std::decay_t<decltype(body)>;
    T::fields(printer, body);
  });
  return printer.length();
}

}  // namespace tetrapulse::protocol

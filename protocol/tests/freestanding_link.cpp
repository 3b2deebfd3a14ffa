// Linked bare-metal in the firmware build (protocol/CMakeLists.txt): every encoder and
// decoder in one image, so check_freestanding.cmake can show none of them pulls in the
// heap, exceptions or RTTI.
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/message.hpp"

using namespace tetrapulse::protocol;

namespace {
volatile uint8_t g_sink;
uint8_t g_buffer[kMaxMessageSize];
char g_text[128];
}  // namespace

int main() {
  const auto message = decode(ByteView{g_buffer, sizeof(g_buffer) - g_sink});
  if (message.ok()) {
    ByteWriter out(g_buffer, sizeof(g_buffer));
    g_sink = static_cast<uint8_t>(encode(*message, out).error());
    g_sink = static_cast<uint8_t>(format_message(*message, g_text, sizeof(g_text)));
  }
  const auto header = decode_image_header(ByteView{g_buffer, kImageHeaderSize});
  if (header.ok()) {
    g_sink = static_cast<uint8_t>(fits(*header, HwModel::kStm32f405Reference, 1).error());
    g_sink = static_cast<uint8_t>(check_payload(*header, ByteView{g_buffer, sizeof(g_buffer)}).error());
    ByteWriter out(g_buffer, sizeof(g_buffer));
    g_sink = static_cast<uint8_t>(encode_image_header(*header, out).error());
  }
  const auto config = decode_config(ByteView{g_buffer, kConfigSize});
  if (config.ok()) {
    ByteWriter out(g_buffer, sizeof(g_buffer));
    g_sink = static_cast<uint8_t>(encode_config(*config, out).error());
  }
  return g_sink;
}

// Linked bare-metal in the firmware build (protocol/CMakeLists.txt): every encoder, decoder
// and transport a board uses in one image, so check_freestanding.cmake can show none of
// them pulls in the heap, exceptions, RTTI or abort().
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/clock_bracket.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_control.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"

using namespace tetrapulse::protocol;

namespace {
volatile uint8_t g_sink;
uint8_t g_buffer[kMaxMessageSize];
uint8_t g_frame[kUartMaxFrameSize];
char g_text[128];
CanReceiveSession g_sessions[2];

void messages() {
  size_t stopped_at = 0;
  const auto message = decode(ByteView{g_buffer, sizeof(g_buffer) - g_sink}, &stopped_at);
  g_sink = static_cast<uint8_t>(stopped_at);
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
}

void transports() {
  const ByteView message{g_buffer, g_sink};
  CanTransferSender sender(g_sink);
  CanTransferReceiver receiver(g_sessions, 2);
  (void)sender.send(kCanPriorityRequest, g_sink, message, [&](const CanFrame& frame) {
    g_sink = static_cast<uint8_t>(receiver.accept(frame, g_sink).verdict);
    return Status{};
  });
  g_sink = static_cast<uint8_t>(receiver.expire(g_sink));

  const Result<size_t> n = encode_uart_frame(message, g_frame, sizeof(g_frame));
  UartFrameDecoder uart;
  size_t used = 0;
  if (n.ok()) g_sink = static_cast<uint8_t>(uart.feed(ByteView{g_frame, *n}, &used).kind);

  UsbBulkFrameReceiver bulk;
  g_sink = static_cast<uint8_t>(bulk.push_packet(ByteView{g_frame, g_sink}).kind);
  g_sink = static_cast<uint8_t>(encode_usb_bulk_frame(message, g_frame, sizeof(g_frame)).error());
  UsbMessageOutReceiver control;
  if (control.begin(g_sink).ok()) g_sink = static_cast<uint8_t>(control.push_packet(message).kind);
  g_sink = static_cast<uint8_t>(check_usb_message_in(g_sink, g_sink).error());

  UsbDeviceParams params;
  g_sink = static_cast<uint8_t>(build_usb_configuration_descriptor(params, g_frame, sizeof(g_frame)).error());
  g_sink = static_cast<uint8_t>(build_usb_string_descriptor(g_text, g_frame, sizeof(g_frame)).error());
  const auto status = decode_dfu_status(message);
  if (status.ok()) g_sink = static_cast<uint8_t>(encode_dfu_status(*status, g_frame, sizeof(g_frame)).error());
  g_sink = static_cast<uint8_t>(encode_usb_protocol_info(UsbProtocolInfo{}, g_frame, sizeof(g_frame)).error());
}

volatile int64_t g_clock;
int64_t read_clock() {
  g_clock = g_clock + g_sink;
  return g_clock;
}

void clocks() { g_sink = static_cast<uint8_t>(bracketed_clock_offset_ns(read_clock, [] { return g_clock * 2; })); }
}  // namespace

int main() {
  messages();
  transports();
  clocks();
  return g_sink;
}

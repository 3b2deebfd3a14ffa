// Every golden vector in protocol/vectors/{can,uart,usb}: encoding reproduces it byte
// for byte and decoding returns the original message.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "message_testing.hpp"
#include "transport_vectors.hpp"
#include "vector_cases.hpp"

namespace tetrapulse::protocol::testing {
namespace {

using Bytes = std::vector<uint8_t>;

std::vector<HexFile> read_all(const std::string& folder, const std::string& prefix = "") {
  auto files = read_vectors(folder, prefix);
  EXPECT_TRUE(files.has_value()) << files.error();
  return files ? std::move(*files) : std::vector<HexFile>{};
}

TEST(TransportVectors, Can) {
  const auto files = read_all("can");
  ASSERT_GE(files.size(), 8u);
  for (const HexFile& f : files) {
    SCOPED_TRACE(f.path);
    const auto v = can_transfer_vector(f);
    ASSERT_TRUE(v) << v.error();
    const Bytes& m = v->message;
    ASSERT_EQ(v->frames.size(), can_frame_count(m.size()));
    CanReceiveSession sessions[1];
    CanTransferReceiver rx(sessions, 1);
    for (size_t i = 0; i < v->frames.size(); ++i) {
      const CanFrame& golden = v->frames[i];
      const Result<CanFrame> built = make_can_transfer_frame(v->header, view(m), i);
      ASSERT_TRUE(built.ok());
      EXPECT_EQ(built->id, golden.id) << "frame " << i;
      EXPECT_EQ(Bytes(built->data, built->data + built->size), Bytes(golden.data, golden.data + golden.size))
          << "frame " << i;

      const CanReceiveOutcome out = rx.accept(golden, 1000 + static_cast<int64_t>(i));
      if (i + 1 < v->frames.size()) {
        EXPECT_EQ(out.verdict, CanFrameVerdict::kPending);
        continue;
      }
      ASSERT_EQ(out.verdict, CanFrameVerdict::kComplete) << can_fault_name(out.fault);
      EXPECT_EQ(Bytes(out.transfer.message.begin(), out.transfer.message.end()), m);
      EXPECT_EQ(out.transfer.id, (CanId{v->header.priority, m[1], v->header.destination, v->header.source}));
      EXPECT_EQ(out.transfer.transfer_id, v->header.transfer_id);
      EXPECT_EQ(out.transfer.timestamp_ns, 1000);
    }
  }
}

TEST(TransportVectors, Uart) {
  const auto files = read_all("uart");
  ASSERT_GE(files.size(), 9u);
  for (const HexFile& f : files) {
    SCOPED_TRACE(f.path);
    const Bytes message = record_bytes(f, "message");
    const Bytes frame = record_bytes(f, "frame");
    Bytes encoded(kUartMaxFrameSize);
    const Result<size_t> n = encode_uart_frame(view(message), encoded.data(), encoded.size());
    ASSERT_TRUE(n.ok());
    encoded.resize(*n);
    EXPECT_EQ(encoded, frame);
    UartFrameDecoder decoder;
    size_t used = 0;
    const ReceiveEvent e = decoder.feed(view(frame), &used);
    EXPECT_EQ(used, frame.size());
    ASSERT_EQ(e.kind, ReceiveKind::kMessage) << error_name(e.error);
    EXPECT_EQ(Bytes(e.message.begin(), e.message.end()), message);
  }
}

TEST(TransportVectors, UsbBulk) {
  const auto files = read_all("usb", "bulk_");
  ASSERT_GE(files.size(), 9u);
  for (const HexFile& f : files) {
    SCOPED_TRACE(f.path);
    const Bytes message = record_bytes(f, "message");
    const Bytes transfer = record_bytes(f, "transfer");
    Bytes encoded(kUsbBulkMaxTransfer);
    const Result<size_t> n = encode_usb_bulk_frame(view(message), encoded.data(), encoded.size());
    ASSERT_TRUE(n.ok());
    encoded.resize(*n);
    EXPECT_EQ(encoded, transfer);
    const Result<ByteView> decoded = decode_usb_bulk_frame(view(transfer));
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(Bytes(decoded->begin(), decoded->end()), message);
  }
}

TEST(TransportVectors, UsbDescriptors) {
  const auto files = read_all("usb", "descriptors_");
  ASSERT_GE(files.size(), 3u);
  for (const HexFile& f : files) {
    const auto v = usb_descriptor_vector(f);
    ASSERT_TRUE(v.has_value()) << v.error();
    SCOPED_TRACE(f.path);
    uint8_t out[kUsbMaxConfigurationSize];
    Result<size_t> n = build_usb_device_descriptor(v->params, out, sizeof(out));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(Bytes(out, out + *n), v->device);
    n = build_usb_configuration_descriptor(v->params, out, sizeof(out));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(Bytes(out, out + *n), v->configuration);
  }
}

// `value` encodes to `bytes` and `bytes` decode to `value`.
template <class T, class Encode, class Decode>
void expect_codec(const T& value, const Bytes& bytes, Encode encode, Decode decode) {
  uint8_t out[64];
  const Result<size_t> n = encode(value, out, sizeof(out));
  ASSERT_TRUE(n.ok()) << error_name(n.error());
  EXPECT_EQ(Bytes(out, out + *n), bytes);
  const Result<T> back = decode(view(bytes));
  ASSERT_TRUE(back.ok()) << error_name(back.error());
  EXPECT_EQ(*back, value);
}

TEST(TransportVectors, DfuStatus) {
  const auto files = read_all("usb", "dfu_status_");
  ASSERT_GE(files.size(), 4u);
  for (const HexFile& f : files) {
    SCOPED_TRACE(f.path);
    const auto field = [&](const char* key) { return record_number(f, "status", key); };
    const DfuStatus s{static_cast<DfuStatusCode>(field("status")), static_cast<uint32_t>(field("poll_timeout_ms")),
                      static_cast<DfuState>(field("state")), static_cast<uint8_t>(field("string_index"))};
    expect_codec(s, record_bytes(f, "bytes"), encode_dfu_status, decode_dfu_status);
  }
}

TEST(TransportVectors, UsbProtocolInfo) {
  const auto files = read_all("usb", "protocol_info");
  ASSERT_EQ(files.size(), 1u);
  const HexFile& f = files[0];
  const auto field = [&](const char* key) { return record_number(f, "info", key); };
  const UsbProtocolInfo info{static_cast<uint8_t>(field("protocol_version")),
                             static_cast<uint16_t>(field("max_message_size")),
                             static_cast<uint32_t>(field("capabilities"))};
  expect_codec(info, record_bytes(f, "bytes"), encode_usb_protocol_info, decode_usb_protocol_info);
}

// A CAN vector that lacks a record or holds an impossible value says which and where.
TEST(TransportVectors, CanVectorErrorsNameTheFile) {
  HexFile f;
  f.path = "x.hex";
  EXPECT_EQ(can_transfer_vector(f).error(), "x.hex: a CAN vector needs [message], [transfer] and [frame.N] records");
  HexRecord transfer{"transfer", "", {}, {{"priority", "8"}, {"source", "0"}, {"destination", "1"}, {"transfer_id", "0"}},
                     "x.hex:2"};
  f.records = {HexRecord{"message", "", {1, 4, 7}, {}, "x.hex:1"}, transfer,
               HexRecord{"frame.0", "", {1, 4, 7, 0xE0}, {{"id", "0x10040100"}}, "x.hex:3"}};
  EXPECT_EQ(can_transfer_vector(f).error(), "x.hex:2: [transfer] priority over 7");
  f.records[1].attributes["priority"] = "4";
  f.records[2].bytes.resize(9);
  EXPECT_EQ(can_transfer_vector(f).error(), "x.hex:3: [frame.0] holds more than 8 data bytes");
  f.records[2].bytes.resize(4);
  EXPECT_TRUE(can_transfer_vector(f).has_value());
}

}  // namespace
}  // namespace tetrapulse::protocol::testing

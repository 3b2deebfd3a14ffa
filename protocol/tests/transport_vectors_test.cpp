// Every golden vector in protocol/vectors/{can,uart,usb}: encoding reproduces it byte
// for byte and decoding returns the original message.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/dfu.hpp"
#include "tetrapulse/protocol/uart_frame.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "tetrapulse/protocol/usb_descriptors.hpp"
#include "vector_file.hpp"

namespace tetrapulse::protocol {
namespace {

using testing::VectorFile;
using testing::VectorRecord;
using Bytes = std::vector<uint8_t>;

std::vector<testing::VectorFile> read_all(const std::string& part, const std::string& prefix = "") {
  auto files = testing::read_vector_dir(testing::vectors_dir(part), prefix);
  EXPECT_TRUE(files.has_value()) << files.error();
  return files ? std::move(*files) : std::vector<testing::VectorFile>{};
}

ByteView view(const Bytes& b) { return ByteView{b.data(), b.size()}; }

TEST(TransportVectors, Can) {
  const auto files = read_all("can");
  ASSERT_GE(files.size(), 8u);
  for (const VectorFile& f : files) {
    SCOPED_TRACE(f.path);
    const VectorRecord* message = f.first("message");
    const VectorRecord* transfer = f.first("transfer");
    const auto frames = f.all("frame");
    ASSERT_TRUE(message && transfer && !frames.empty());
    const Bytes& m = message->bytes;
    const CanTransferHeader header{static_cast<uint8_t>(transfer->fields.at("priority")),
                                   static_cast<uint8_t>(transfer->fields.at("destination")),
                                   static_cast<uint8_t>(transfer->fields.at("source")),
                                   static_cast<uint8_t>(transfer->fields.at("transfer_id"))};
    ASSERT_EQ(frames.size(), can_frame_count(m.size()));
    CanReceiveSession sessions[1];
    CanTransferReceiver rx(sessions, 1);
    for (size_t i = 0; i < frames.size(); ++i) {
      const Result<CanFrame> built = make_can_transfer_frame(header, view(m), i);
      ASSERT_TRUE(built.ok());
      EXPECT_EQ(built->id, frames[i]->fields.at("id")) << "frame " << i;
      EXPECT_EQ(Bytes(built->data, built->data + built->size), frames[i]->bytes) << "frame " << i;

      CanFrame golden;
      golden.id = static_cast<uint32_t>(frames[i]->fields.at("id"));
      ASSERT_LE(frames[i]->bytes.size(), kCanFrameDataSize);
      for (uint8_t b : frames[i]->bytes) golden.data[golden.size++] = b;
      const CanReceiveOutcome out = rx.accept(golden, 1000 + static_cast<int64_t>(i));
      if (i + 1 < frames.size()) {
        EXPECT_EQ(out.verdict, CanFrameVerdict::kPending);
        continue;
      }
      ASSERT_EQ(out.verdict, CanFrameVerdict::kComplete) << can_fault_name(out.fault);
      EXPECT_EQ(Bytes(out.transfer.message.begin(), out.transfer.message.end()), m);
      EXPECT_EQ(out.transfer.id, (CanId{header.priority, m[1], header.destination, header.source}));
      EXPECT_EQ(out.transfer.transfer_id, header.transfer_id);
      EXPECT_EQ(out.transfer.timestamp_ns, 1000);
    }
  }
}

TEST(TransportVectors, Uart) {
  const auto files = read_all("uart");
  ASSERT_GE(files.size(), 9u);
  for (const VectorFile& f : files) {
    SCOPED_TRACE(f.path);
    const VectorRecord* message = f.first("message");
    const VectorRecord* frame = f.first("frame");
    ASSERT_TRUE(message && frame);
    Bytes encoded(kUartMaxFrameSize);
    const Result<size_t> n = encode_uart_frame(view(message->bytes), encoded.data(), encoded.size());
    ASSERT_TRUE(n.ok());
    encoded.resize(*n);
    EXPECT_EQ(encoded, frame->bytes);
    UartFrameDecoder decoder;
    size_t used = 0;
    const ReceiveEvent e = decoder.feed(view(frame->bytes), &used);
    EXPECT_EQ(used, frame->bytes.size());
    ASSERT_EQ(e.kind, ReceiveKind::kMessage) << error_name(e.error);
    EXPECT_EQ(Bytes(e.message.begin(), e.message.end()), message->bytes);
  }
}

TEST(TransportVectors, UsbBulk) {
  const auto files = read_all("usb", "bulk_");
  ASSERT_GE(files.size(), 9u);
  for (const VectorFile& f : files) {
    SCOPED_TRACE(f.path);
    const VectorRecord* message = f.first("message");
    const VectorRecord* transfer = f.first("transfer");
    ASSERT_TRUE(message && transfer);
    Bytes encoded(kUsbBulkMaxTransfer);
    const Result<size_t> n = encode_usb_bulk_frame(view(message->bytes), encoded.data(), encoded.size());
    ASSERT_TRUE(n.ok());
    encoded.resize(*n);
    EXPECT_EQ(encoded, transfer->bytes);
    const Result<ByteView> decoded = decode_usb_bulk_frame(view(transfer->bytes));
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(Bytes(decoded->begin(), decoded->end()), message->bytes);
  }
}

TEST(TransportVectors, UsbDescriptors) {
  const auto files = read_all("usb", "descriptors_");
  ASSERT_GE(files.size(), 3u);
  for (const VectorFile& f : files) {
    SCOPED_TRACE(f.path);
    const VectorRecord* params = f.first("params");
    const VectorRecord* device = f.first("device");
    const VectorRecord* configuration = f.first("configuration");
    ASSERT_TRUE(params && device && configuration);
    const auto& v = params->fields;
    UsbDeviceParams p;
    p.mode = v.at("bootloader") ? UsbMode::kBootloader : UsbMode::kApplication;
    p.bcd_device = static_cast<uint16_t>(v.at("bcd_device"));
    p.max_power_2ma = static_cast<uint8_t>(v.at("max_power_2ma"));
    p.self_powered = v.at("self_powered") != 0;
    p.bulk_out_address = static_cast<uint8_t>(v.at("bulk_out"));
    p.bulk_in_address = static_cast<uint8_t>(v.at("bulk_in"));
    p.dfu_attributes = static_cast<uint8_t>(v.at("dfu_attributes"));
    p.dfu_detach_timeout_ms = static_cast<uint16_t>(v.at("detach_timeout_ms"));
    p.dfu_transfer_size = static_cast<uint16_t>(v.at("transfer_size"));
    p.dfu_functional_descriptor = v.at("dfu_functional") != 0;
    uint8_t out[kUsbMaxConfigurationSize];
    Result<size_t> n = build_usb_device_descriptor(p, out, sizeof(out));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(Bytes(out, out + *n), device->bytes);
    n = build_usb_configuration_descriptor(p, out, sizeof(out));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(Bytes(out, out + *n), configuration->bytes);
  }
}

TEST(TransportVectors, DfuStatus) {
  const auto files = read_all("usb", "dfu_status_");
  ASSERT_GE(files.size(), 4u);
  for (const VectorFile& f : files) {
    SCOPED_TRACE(f.path);
    const VectorRecord* status = f.first("status");
    const VectorRecord* bytes = f.first("bytes");
    ASSERT_TRUE(status && bytes);
    const DfuStatus s{static_cast<DfuStatusCode>(status->fields.at("status")),
                      static_cast<uint32_t>(status->fields.at("poll_timeout_ms")),
                      static_cast<DfuState>(status->fields.at("state")),
                      static_cast<uint8_t>(status->fields.at("string_index"))};
    uint8_t out[kDfuStatusSize];
    const Result<size_t> n = encode_dfu_status(s, out, sizeof(out));
    ASSERT_TRUE(n.ok());
    EXPECT_EQ(Bytes(out, out + *n), bytes->bytes);
    const Result<DfuStatus> back = decode_dfu_status(view(bytes->bytes));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, s);
  }
}

TEST(TransportVectors, UsbProtocolInfo) {
  const auto files = read_all("usb", "protocol_info");
  ASSERT_EQ(files.size(), 1u);
  const VectorRecord* info = files[0].first("info");
  const VectorRecord* bytes = files[0].first("bytes");
  ASSERT_TRUE(info && bytes);
  const UsbProtocolInfo expected{static_cast<uint8_t>(info->fields.at("protocol_version")),
                                 static_cast<uint16_t>(info->fields.at("max_message_size")),
                                 static_cast<uint32_t>(info->fields.at("capabilities"))};
  uint8_t out[kUsbProtocolInfoSize];
  const Result<size_t> n = encode_usb_protocol_info(expected, out, sizeof(out));
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(Bytes(out, out + *n), bytes->bytes);
  const Result<UsbProtocolInfo> back = decode_usb_protocol_info(view(bytes->bytes));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, expected);
}

TEST(VectorFile, ReportsWhereAFileIsMalformed) {
  const std::string path = ::testing::TempDir() + "bad_vector.txt";
  FILE* out = std::fopen(path.c_str(), "w");
  ASSERT_NE(out, nullptr);
  std::fputs("# fine\nmessage: 01 04 07\nframe: id=0x10 data=0G\n", out);
  std::fclose(out);
  const auto file = testing::read_vector_file(path);
  ASSERT_FALSE(file.has_value());
  EXPECT_NE(file.error().find(":3:"), std::string::npos) << file.error();
  EXPECT_FALSE(testing::read_vector_file(path + ".missing").has_value());
}

}  // namespace
}  // namespace tetrapulse::protocol

// UsbLink's framing over a fake bulk pipe (the VM tests run it against a FunctionFS
// gadget): every golden bulk transfer both ways, ZLPs and broken transfers, and a
// conversation with a responder behind the pipe.
#include <gtest/gtest.h>

#include <deque>

#include "board_responder.hpp"
#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/usb_link.hpp"
#include "tetrapulse/protocol/usb_bulk_frame.hpp"
#include "wire_vectors.hpp"

namespace tetrapulse::host {
namespace {

using Bytes = std::vector<uint8_t>;

class FakeBulkPipe final : public UsbBulkPipe {
 public:
  std::vector<Bytes> written;
  std::deque<Bytes> to_read;
  testing::BoardResponder* responder = nullptr;

 private:
  HostResult<void> do_write_transfer(protocol::ByteView t, int) override {
    written.emplace_back(t.begin(), t.end());
    if (responder != nullptr) {
      auto m = protocol::decode_usb_bulk_frame(t);
      EXPECT_TRUE(m.ok());
      if (auto reply = responder->answer(*m, 0)) {
        Bytes frame(protocol::kUsbBulkMaxTransfer);
        auto n = protocol::encode_usb_bulk_frame(protocol::ByteView{reply->data(), reply->size()}, frame.data(),
                                                 frame.size());
        frame.resize(*n);
        to_read.push_back(frame);
      }
    }
    return {};
  }
  HostResult<std::optional<Bytes>> do_read_transfer(int) override {
    if (to_read.empty()) return std::nullopt;
    Bytes t = to_read.front();
    to_read.pop_front();
    return t;
  }
};

TEST(UsbLink, SendsEveryGoldenTransfer) {
  auto pipe = std::make_unique<FakeBulkPipe>();
  auto* p = pipe.get();
  UsbLink link("usb:TEST", std::move(pipe));
  const auto vectors = testing::wire_vectors("usb", "bulk_", "transfer");
  ASSERT_GE(vectors.size(), 9u);
  for (const auto& v : vectors) {
    ASSERT_TRUE(link.send_raw(protocol::ByteView{v.message.data(), v.message.size()}));
    EXPECT_EQ(p->written.back(), v.wire) << v.file;
  }
}

TEST(UsbLink, ReceivesEveryGoldenTransferAndSkipsZlpsAndBrokenOnes) {
  auto pipe = std::make_unique<FakeBulkPipe>();
  auto* p = pipe.get();
  UsbLink link("usb:TEST", std::move(pipe));
  for (const auto& v : testing::wire_vectors("usb", "bulk_", "transfer")) {
    Bytes wrong_length = v.wire;
    wrong_length[0] ^= 0x01;
    p->to_read = {Bytes{}, wrong_length, v.wire};
    auto got = link.receive_raw(50'000'000);
    ASSERT_TRUE(got) << got.error().what();
    ASSERT_TRUE(got->has_value()) << v.file;
    EXPECT_EQ((*got)->bytes, v.message) << v.file;
  }
  EXPECT_EQ(link.counters().transport_errors, 9u);
}

TEST(UsbLink, ConfiguresABoardBehindThePipe) {
  auto pipe = std::make_unique<FakeBulkPipe>();
  testing::BoardResponder responder;
  pipe->responder = &responder;
  Board board(std::make_unique<UsbLink>("usb:TEST", std::move(pipe)));
  protocol::Config c;
  c.brightness = 1234;
  ASSERT_TRUE(board.configure(c));
  auto back = board.config();
  ASSERT_TRUE(back) << back.error().what();
  EXPECT_EQ(back->brightness, 1234);
}

}  // namespace
}  // namespace tetrapulse::host

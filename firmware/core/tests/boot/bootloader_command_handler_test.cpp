// The bootloader's requests (SPEC.md §7.3): an update over CAN frames into the slot the
// bootloader chose, through the core's UpdateReceiver, answered on the bus; its identity
// and status; refusals of everything an application would do.
#include <gtest/gtest.h>

#include <deque>
#include <vector>

#include "tetrapulse/fw/boot/bootloader_command_handler.hpp"
#include "tetrapulse/fw/boot/update_receiver.hpp"
#include "tetrapulse/fw/boot/update_slot.hpp"
#include "tetrapulse/fw/links/can_link.hpp"
#include "tetrapulse/protocol/can_transfer_receiver.hpp"
#include "tetrapulse/protocol/can_transfer_sender.hpp"
#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_flash.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;
using tp::Error;

constexpr uint32_t kSlotBase[2] = {0x08020000, 0x08028000};
constexpr uint32_t kSlotSize = 0x8000;
constexpr uint8_t kNode = 12;
const BoardModel kBoard{tp::HwModel::kStm32f405Reference, 1};

FlashLayout layout() {
  FlashLayout l;
  l.record_sectors = {FlashRegion{0x08008000, 0x4000}, FlashRegion{0x0800C000, 0x4000}};
  for (uint8_t s = 0; s < 2; ++s) l.slots[s] = SlotLayout{FlashRegion{kSlotBase[s], kSlotSize}, kSlotBase[s]};
  l.vector_alignment = 512;
  return l;
}

std::vector<uint8_t> image_for(uint32_t base, uint32_t version) {
  std::vector<uint8_t> payload(2000);
  for (size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<uint8_t>(i * 31 + version);
  tp::ImageHeader h;
  h.hw_revision_max = 255;
  h.fw_version = version;
  h.payload_size = static_cast<uint32_t>(payload.size());
  h.vector_offset = 0x200;
  h.load_address = base;
  h.payload_crc32c = tp::crc32c(payload.data(), payload.size());
  std::vector<uint8_t> image(0x200, 0);
  tp::ByteWriter w(image.data(), image.size());
  EXPECT_TRUE(tp::encode_image_header(h, w).ok());
  image.insert(image.end(), payload.begin(), payload.end());
  return image;
}

class Clock final : public LocalClock {
 public:
  Tick t = 2'500'000;  // 2.5 s at 1 MHz
 private:
  Tick do_now() const override { return t; }
  uint32_t do_tick_hz() const override { return 1'000'000; }
};

class RecordingBus final : public CanBus {
 public:
  std::deque<tp::CanFrame> sent;

 private:
  tp::Status do_send(const tp::CanFrame& f) override {
    sent.push_back(f);
    return {};
  }
  void do_set_filters(const tp::CanNodeFilters&) override {}
  uint16_t do_error_count() const override { return 3; }
  bool do_bus_off() const override { return false; }
};

struct Bootloader {
  Bootloader()
      : flash({FlashRegion{0x08008000, 0x4000}, FlashRegion{0x0800C000, 0x4000}, FlashRegion{kSlotBase[0], kSlotSize},
               FlashRegion{kSlotBase[1], kSlotSize}}),
        store(flash, layout().record_sectors),
        // Slot 0 is the known-good image: updates go to slot 1 (UpdateReceiver's target is
        // the slot that is not "active").
        update(flash, layout(), store, kBoard, 0),
        link(bus, 1'000'000, kNode),
        handler(update, identity(), clock, &link) {
    EXPECT_TRUE(store.open().ok());
  }
  static BootloaderIdentity identity() {
    BootloaderIdentity id;
    id.hw_revision = 1;
    id.bootloader_version = tp::pack_version(1, 2, 3);
    id.serial = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    id.capabilities = tp::capability::kCan | tp::capability::kCanUpdate;
    id.node_id = kNode;
    return id;
  }

  // One request from the host (node 0) over CAN; the decoded answer, if any.
  std::optional<tp::Message> request(const tp::Body& body) {
    uint8_t bytes[tp::kMaxMessageSize];
    tp::ByteWriter w(bytes, sizeof(bytes));
    EXPECT_TRUE(tp::encode(tp::Message{seq++, body}, w).ok());
    std::vector<tp::CanFrame> frames;
    host.send(tp::kCanPriorityRequest, kNode, w.view(), [&](const tp::CanFrame& f) {
      frames.push_back(f);
      return tp::Status{};
    });
    for (const tp::CanFrame& f : frames) link.on_frame(f, clock.t += 100, handler);
    std::optional<tp::Message> answer;
    while (!bus.sent.empty()) {
      const tp::CanReceiveOutcome o = receiver.accept(bus.sent.front(), static_cast<int64_t>(clock.t));
      bus.sent.pop_front();
      if (o.verdict == tp::CanFrameVerdict::kComplete) {
        EXPECT_EQ(o.transfer.id.source, kNode);
        EXPECT_EQ(o.transfer.id.destination, tp::kCanHostNode);
        const tp::Result<tp::Message> m = tp::decode(o.transfer.message);
        EXPECT_TRUE(m.ok());
        if (m) answer = *m;
      }
    }
    return answer;
  }

  sim_board::SimFlash flash;
  RecordStore store;
  UpdateReceiver update;
  Clock clock;
  RecordingBus bus;
  CanLink link;
  BootloaderCommandHandler handler;
  tp::CanTransferSender host{tp::kCanHostNode};
  tp::CanReceiveSession sessions[2];
  tp::CanTransferReceiver receiver{sessions, 2, 1'000'000'000};
  uint8_t seq = 1;
};

Error error_of(const std::optional<tp::Message>& m) {
  if (!m) return Error::kTimeout;
  const auto* e = m->get<tp::ErrorResponse>();
  return e == nullptr ? Error::kNone : e->error;
}

TEST(BootloaderCommands, AnUpdateOverCanLandsInTheTargetSlotAndIsPending) {
  Bootloader b;
  const uint32_t v = tp::pack_version(2, 1, 0);
  const std::vector<uint8_t> img = image_for(kSlotBase[1], v);
  const uint32_t crc = tp::crc32c(img.data(), img.size());
  ASSERT_EQ(error_of(b.request(tp::UpdateBegin{static_cast<uint32_t>(img.size()), v, crc})), Error::kNone);
  for (size_t off = 0; off < img.size(); off += tp::kMaxUpdateChunk) {
    tp::UpdateChunk c;
    c.offset = static_cast<uint32_t>(off);
    c.length = static_cast<uint16_t>(std::min<size_t>(tp::kMaxUpdateChunk, img.size() - off));
    std::copy(img.begin() + static_cast<std::ptrdiff_t>(off),
              img.begin() + static_cast<std::ptrdiff_t>(off + c.length), c.data.begin());
    const auto ack = b.request(c);
    ASSERT_EQ(error_of(ack), Error::kNone) << off;
    EXPECT_EQ(ack->get<tp::Ack>()->value, off + c.length);
  }
  const auto verified = b.request(tp::UpdateVerify{});
  ASSERT_EQ(error_of(verified), Error::kNone);
  EXPECT_EQ(verified->get<tp::Ack>()->value, crc);
  const tp::Result<BootState> state = load_boot_state(b.store);
  ASSERT_TRUE(state.ok());
  EXPECT_EQ(state->pending_slot, 1);
  EXPECT_EQ(state->pending_version, v);
  const auto status = b.request(tp::GetStatus{});
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->get<tp::StatusReport>()->update_state, tp::UpdateState::kVerified);
  EXPECT_EQ(status->get<tp::StatusReport>()->can_errors, 3);
}

TEST(BootloaderCommands, AnImageLinkedForTheOtherSlotIsRejected) {
  Bootloader b;
  const std::vector<uint8_t> img = image_for(kSlotBase[0], 5);
  const uint32_t crc = tp::crc32c(img.data(), img.size());
  b.request(tp::UpdateBegin{static_cast<uint32_t>(img.size()), 5, crc});
  for (size_t off = 0; off < img.size(); off += 256) {
    tp::UpdateChunk c;
    c.offset = static_cast<uint32_t>(off);
    c.length = static_cast<uint16_t>(std::min<size_t>(256, img.size() - off));
    std::copy(img.begin() + static_cast<std::ptrdiff_t>(off),
              img.begin() + static_cast<std::ptrdiff_t>(off + c.length), c.data.begin());
    b.request(c);
  }
  EXPECT_EQ(error_of(b.request(tp::UpdateVerify{})), Error::kImageRejected);
  EXPECT_FALSE(load_boot_state(b.store).ok());
}

TEST(BootloaderCommands, InfoSaysNoApplicationRuns) {
  Bootloader b;
  const auto m = b.request(tp::GetInfo{});
  ASSERT_TRUE(m.has_value());
  const tp::Info* info = m->get<tp::Info>();
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->fw_version, 0u);
  EXPECT_EQ(info->active_slot, kNoSlot);
  EXPECT_EQ(info->bootloader_version, tp::pack_version(1, 2, 3));
  EXPECT_EQ(info->node_id, kNode);
  EXPECT_EQ(info->hw_revision, 1);
  EXPECT_EQ(info->uptime_ms, 2500u + 0);  // the request's one frame took 100 us
  EXPECT_NE(info->capabilities & tp::capability::kCanUpdate, 0u);
}

TEST(BootloaderCommands, RefusesApplicationRequestsAndMalformedOnes) {
  Bootloader b;
  EXPECT_EQ(error_of(b.request(tp::GetConfig{})), Error::kNotSupported);
  EXPECT_EQ(error_of(b.request(tp::Identify{tp::IdentifyPattern::kChase, 100})), Error::kNotSupported);
  uint8_t out[tp::kMaxMessageSize];
  const uint8_t empty_chunk[] = {0x01, 0x11, 0x05, 0, 0, 0, 0, 0, 0};  // UpdateChunk, length 0
  const size_t n = b.handler.handle(tp::ByteView{empty_chunk, sizeof(empty_chunk)}, out, sizeof(out));
  const tp::Result<tp::Message> refused = tp::decode(tp::ByteView{out, n});
  ASSERT_TRUE(refused.ok());
  EXPECT_EQ(error_of(*refused), Error::kBadLength) << "length 0 fails to decode";
  const uint8_t unknown[] = {0x01, 0x3A, 0x05};
  EXPECT_GT(b.handler.handle(tp::ByteView{unknown, 3}, out, sizeof(out)), 0u) << "an undefined request code";
  const uint8_t response[] = {0x01, 0x80, 0x05, 0x01};
  EXPECT_EQ(b.handler.handle(tp::ByteView{response, 4}, out, sizeof(out)), 0u) << "broken responses are dropped";
  EXPECT_EQ(b.request(tp::Sync{4}), std::nullopt) << "time sync is never answered";
  const auto status = b.request(tp::GetStatus{});
  EXPECT_EQ(status->get<tp::StatusReport>()->rx_malformed, 3);
}

TEST(BootloaderCommands, RebootIsAcknowledgedThenRequested) {
  Bootloader b;
  EXPECT_FALSE(b.handler.reboot_requested());
  EXPECT_EQ(error_of(b.request(tp::Reboot{tp::RebootMode::kApplication})), Error::kNone);
  EXPECT_TRUE(b.handler.reboot_requested());
  EXPECT_EQ(b.handler.reboot_mode(), tp::RebootMode::kApplication);
}

}  // namespace
}  // namespace tetrapulse::fw::testing

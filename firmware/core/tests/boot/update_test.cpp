// Firmware update (SPEC.md §7.3) and boot selection on the simulated board: every
// refusal, the trial boots of a new image, its confirmation, and the fallback.
#include <gtest/gtest.h>

#include <vector>

#include "board_testing.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::Error;

constexpr uint32_t kOld = protocol::pack_version(1, 0, 0);
constexpr uint32_t kNew = protocol::pack_version(2, 0, 0);

std::vector<uint8_t> image(uint32_t version = kNew, uint32_t payload = 700) {
  sim_board::SimImageSpec spec;
  spec.fw_version = version;
  spec.payload_size = payload;
  spec.seed = version;
  return sim_board::make_sim_image(spec);
}

protocol::UpdateChunk chunk_of(const std::vector<uint8_t>& img, size_t off, size_t len) {
  protocol::UpdateChunk c;
  c.offset = static_cast<uint32_t>(off);
  c.length = static_cast<uint16_t>(len);
  std::copy(img.begin() + static_cast<std::ptrdiff_t>(off), img.begin() + static_cast<std::ptrdiff_t>(off + len),
            c.data.begin());
  return c;
}

Error error_of(const protocol::Message& m) {
  const auto* e = m.get<protocol::ErrorResponse>();
  return e == nullptr ? Error::kNone : e->error;
}
uint32_t ack_value(const protocol::Message& m) {
  const auto* a = m.get<protocol::Ack>();
  EXPECT_NE(a, nullptr);
  return a == nullptr ? 0xDEADBEEF : a->value;
}

// Begin + all chunks; returns the last answer.
protocol::Message send_image(TestBoard& b, const std::vector<uint8_t>& img, uint32_t version, uint32_t crc,
                             LinkKind link = LinkKind::kUsb) {
  protocol::Message last = b.request(protocol::UpdateBegin{static_cast<uint32_t>(img.size()), version, crc}, link);
  if (error_of(last) != Error::kNone) return last;
  for (size_t off = 0; off < img.size(); off += 256) {
    last = b.request(chunk_of(img, off, std::min<size_t>(256, img.size() - off)), link);
    if (error_of(last) != Error::kNone) return last;
  }
  return last;
}

uint32_t crc_of(const std::vector<uint8_t>& img) { return protocol::crc32c(img.data(), img.size()); }

TEST(Update, VerifiedImageBootsOnRebootAndConfirmsItself) {
  for (LinkKind link : {LinkKind::kUsb, LinkKind::kCan, LinkKind::kUart}) {
    TestBoard b{sim_board::SimBoardOptions{}};
    const std::vector<uint8_t> img = image();
    send_image(b, img, kNew, crc_of(img), link);
    EXPECT_EQ(ack_value(b.request(protocol::UpdateVerify{}, link)), crc_of(img));
    EXPECT_EQ(b.board.status().update_state, protocol::UpdateState::kVerified);
    EXPECT_EQ(b.board.running_version(), kOld);  // nothing changes before the reboot
    b.request(protocol::Reboot{protocol::RebootMode::kApplication}, link);
    EXPECT_EQ(b.board.running_version(), kNew);
    EXPECT_EQ(b.board.active_slot(), 1);
    EXPECT_FALSE(b.board.firmware()->confirmed());
    b.board.advance_to(b.board.now() + 3 * kSecond);
    b.request(protocol::GetInfo{}, link);
    EXPECT_FALSE(b.board.firmware()->confirmed()) << "confirmed before kConfirmAfterMs";
    b.board.advance_to(b.board.now() + 3 * kSecond);
    EXPECT_TRUE(b.board.firmware()->confirmed());
    b.board.power_cycle();
    EXPECT_EQ(b.board.running_version(), kNew) << "the confirmed image stays";
  }
}

TEST(Update, UnconfirmedImageGetsThreeTrialsThenTheOldOneRunsAgain) {
  TestBoard b{sim_board::SimBoardOptions{}};
  const std::vector<uint8_t> img = image();
  send_image(b, img, kNew, crc_of(img));
  b.request(protocol::UpdateVerify{});
  b.request(protocol::Reboot{protocol::RebootMode::kApplication});
  // The new image never answers a request (as if it hung): each reset is one trial.
  for (uint8_t trial = 1; trial <= kMaxTrialBoots; ++trial) {
    EXPECT_EQ(b.board.running_version(), kNew) << "trial " << int{trial};
    b.board.advance_to(b.board.now() + 10 * kSecond);
    b.board.power_cycle();
  }
  EXPECT_EQ(b.board.running_version(), kOld);
  EXPECT_EQ(b.board.active_slot(), 0);
  b.board.power_cycle();
  EXPECT_EQ(b.board.running_version(), kOld);
}

TEST(Update, CorruptedPendingSlotIsNeverStarted) {
  TestBoard b{sim_board::SimBoardOptions{}};
  const std::vector<uint8_t> img = image();
  send_image(b, img, kNew, crc_of(img));
  b.request(protocol::UpdateVerify{});
  // A bit flips in the new payload after verification.
  const uint32_t at = sim_board::sim_flash_layout().slots[1].region.address + 300;
  b.board.flash().load(at, {static_cast<uint8_t>(b.board.flash().contents()[at] ^ 0x10)});
  b.request(protocol::Reboot{protocol::RebootMode::kApplication});
  EXPECT_EQ(b.board.running_version(), kOld);
}

TEST(Update, RefusesWhatSpecSaysAndKeepsRunningImage) {
  const std::vector<uint8_t> img = image();
  {  // too big for the slot
    TestBoard b{sim_board::SimBoardOptions{}};
    EXPECT_EQ(error_of(b.request(protocol::UpdateBegin{0x4001, kNew, 0})), Error::kImageRejected);
    EXPECT_EQ(b.board.status().update_state, protocol::UpdateState::kIdle);
  }
  {  // chunk without begin, out of order, past the end; repeat of the last chunk
    TestBoard b{sim_board::SimBoardOptions{}};
    EXPECT_EQ(error_of(b.request(chunk_of(img, 0, 16))), Error::kInvalidState);
    EXPECT_EQ(error_of(b.request(protocol::UpdateVerify{})), Error::kInvalidState);
    b.request(protocol::UpdateBegin{static_cast<uint32_t>(img.size()), kNew, crc_of(img)});
    EXPECT_EQ(ack_value(b.request(chunk_of(img, 0, 100))), 100u);
    EXPECT_EQ(ack_value(b.request(chunk_of(img, 0, 100))), 100u);  // lost Ack: acknowledged again
    const protocol::Message wrong = b.request(chunk_of(img, 200, 10));
    EXPECT_EQ(error_of(wrong), Error::kInvalidState);
    EXPECT_EQ(wrong.get<protocol::ErrorResponse>()->detail, 100);
    EXPECT_EQ(error_of(b.request(protocol::UpdateVerify{})), Error::kInvalidState);  // not all bytes yet
    EXPECT_EQ(ack_value(b.request(chunk_of(img, 100, 256))), 356u);
    EXPECT_EQ(ack_value(b.request(chunk_of(img, 356, 256))), 612u);
    protocol::UpdateChunk past = chunk_of(img, 612, 100);
    past.length = 256;  // 612 + 256 runs past image_size (828)
    EXPECT_EQ(error_of(b.request(past)), Error::kInvalidState);
    EXPECT_EQ(error_of(b.request(protocol::PersistConfig{})), Error::kAccessDenied);
    EXPECT_EQ(error_of(b.request(protocol::FactoryReset{})), Error::kAccessDenied);
    EXPECT_NE(b.request(protocol::GetStatus{}).get<protocol::StatusReport>(), nullptr);  // works during an update
    b.request(protocol::UpdateAbort{});
    EXPECT_EQ(b.board.status().update_state, protocol::UpdateState::kIdle);
    EXPECT_EQ(error_of(b.request(chunk_of(img, 100, 10))), Error::kInvalidState);
  }
  struct Bad {
    const char* what;
    std::vector<uint8_t> bytes;
    uint32_t version;
    uint32_t crc;
  };
  std::vector<uint8_t> other_model = img;
  other_model[8] = 1;  // hw_model stm32f405 (the header CRC then fails too)
  sim_board::SimImageSpec rev;
  rev.fw_version = kNew;
  rev.payload_size = 700;
  rev.hw_revision_min = 5;
  rev.hw_revision_max = 9;
  const std::vector<uint8_t> wrong_revision = sim_board::make_sim_image(rev);
  std::vector<uint8_t> bad_payload = img;
  bad_payload[500] ^= 1;
  const std::vector<Bad> bad = {
      {"crc of the whole image", img, kNew, crc_of(img) ^ 1},
      {"version differs from UpdateBegin", img, kOld, crc_of(img)},
      {"header for another model", other_model, kNew, crc_of(other_model)},
      {"board revision outside the image's range", wrong_revision, kNew, crc_of(wrong_revision)},
      {"payload crc", bad_payload, kNew, crc_of(bad_payload)},
  };
  for (const Bad& c : bad) {
    TestBoard b{sim_board::SimBoardOptions{}};
    send_image(b, c.bytes, c.version, c.crc);
    EXPECT_EQ(error_of(b.request(protocol::UpdateVerify{})), Error::kImageRejected) << c.what;
    EXPECT_EQ(b.board.status().update_state, protocol::UpdateState::kFailed) << c.what;
    b.request(protocol::Reboot{protocol::RebootMode::kApplication});
    EXPECT_EQ(b.board.running_version(), kOld) << c.what;
  }
}

TEST(Update, RebootIntoBootloaderStaysThere) {
  TestBoard b{sim_board::SimBoardOptions{}};
  b.request(protocol::Reboot{protocol::RebootMode::kBootloader});
  EXPECT_EQ(b.board.firmware(), nullptr);
  b.board.power_cycle();
  EXPECT_NE(b.board.firmware(), nullptr);
}

// select_boot on its own: every combination of stored state and slot validity.
TEST(BootSelection, NeverStartsAnInvalidSlotAndPrefersConfirmedOverExhaustedTrials) {
  const std::array<uint8_t, 3> slot_values = {0, 1, kNoSlot};
  for (uint8_t confirmed : slot_values) {
    for (uint8_t pending : slot_values) {
      for (uint8_t attempts = 0; attempts <= kMaxTrialBoots + 1; ++attempts) {
        for (int validity = 0; validity < 4; ++validity) {
          for (bool have_state : {false, true}) {
            const std::array<SlotCheck, kSlotCount> slots = {SlotCheck{(validity & 1) != 0, 10},
                                                             SlotCheck{(validity & 2) != 0, 20}};
            BootState s;
            s.confirmed_slot = confirmed;
            s.pending_slot = pending;
            s.attempts = attempts;
            const protocol::Result<BootState> stored =
                have_state ? protocol::Result<BootState>(s) : protocol::Result<BootState>(Error::kInvalidState);
            const BootDecision d = select_boot(stored, slots, false);
            SCOPED_TRACE(::testing::Message() << "confirmed " << int{confirmed} << " pending " << int{pending}
                                            << " attempts " << int{attempts} << " validity " << validity
                                            << " state " << have_state);
            if (validity == 0) {
              EXPECT_FALSE(d.boot);
              continue;
            }
            ASSERT_TRUE(d.boot);
            EXPECT_TRUE(slots[d.slot].valid);
            if (have_state && pending != kNoSlot && slots[pending].valid && attempts < kMaxTrialBoots) {
              EXPECT_EQ(d.slot, pending);
              EXPECT_EQ(d.state.attempts, attempts + 1);
              EXPECT_TRUE(d.write_state);
            } else if (have_state && confirmed != kNoSlot && slots[confirmed].valid) {
              EXPECT_EQ(d.slot, confirmed);
              EXPECT_EQ(d.state.pending_slot, kNoSlot);
            }
            EXPECT_FALSE(select_boot(stored, slots, true).boot);
          }
        }
      }
    }
  }
}

TEST(BootState, ConfirmOnlyTheRunningPendingImage) {
  bool changed = false;
  BootState s{0, 1, 2, 7};
  EXPECT_EQ(confirm_slot(s, 1, &changed), (BootState{1, kNoSlot, 0, 0}));
  EXPECT_TRUE(changed);
  EXPECT_EQ(confirm_slot(s, 0, &changed), s) << "the old image must not drop a pending update";
  EXPECT_FALSE(changed);
  uint8_t bytes[kBootStateSize];
  ASSERT_TRUE(encode_boot_state(s, bytes).ok());
  EXPECT_EQ(*decode_boot_state(protocol::ByteView{bytes, sizeof(bytes)}), s);
  bytes[0] = 7;
  EXPECT_EQ(decode_boot_state(protocol::ByteView{bytes, sizeof(bytes)}).error(), Error::kBadValue);
}

}  // namespace
}  // namespace tetrapulse::fw::testing

// Power cut at every flash write step (a programmed byte or an erase step) of configuration
// writes and of a whole firmware update, on the simulated board: after the cut and a
// reboot the board always starts a valid image with a valid configuration, old or new.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "board_testing.hpp"
#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"

namespace tetrapulse::fw::testing {
namespace {

using protocol::Config;

Config numbered_config(uint16_t n) {
  Config c = edge_rich_config(kMs);
  c.target_id = n;
  c.brightness = static_cast<uint16_t>(1000 + n);
  return c;
}

protocol::Config stored_config(TestBoard& b) {
  const protocol::Message m = b.request(protocol::GetConfig{});
  const auto* report = m.get<protocol::ConfigReport>();
  EXPECT_NE(report, nullptr);
  return report != nullptr ? report->config : protocol::Config{};
}

bool same(const Config& a, const Config& b) {
  uint8_t x[protocol::kConfigSize], y[protocol::kConfigSize];
  protocol::ByteWriter wx(x, sizeof(x)), wy(y, sizeof(y));
  return protocol::encode_config(a, wx) && protocol::encode_config(b, wy) &&
         std::equal(x, x + sizeof(x), y);
}

bool acked(const protocol::Message& m) { return m.get<protocol::Ack>() != nullptr; }

// Persists configs 1..prefill without cuts (the record store nearly full), then configs
// prefill+1 .. prefill+count with the power cut after `cut` more write steps. Returns
// the index of the last config whose PersistConfig was acknowledged.
int persist_sequence(TestBoard& b, int prefill, int count, std::optional<uint64_t> cut) {
  int last_ok = 0;
  for (int i = 1; i <= prefill + count; ++i) {
    if (i == prefill + 1 && cut) b.board.flash().cut_power_after(*cut);
    b.configure(numbered_config(static_cast<uint16_t>(i)));
    if (!acked(b.request(protocol::PersistConfig{}))) break;
    last_ok = i;
  }
  return last_ok;
}

TEST(ConfigStore, PowerCutAtEveryWriteStepLeavesOldOrNewConfig) {
  // How many write steps the cut sequence takes, from an uncut run.
  constexpr int kPrefill = 38, kCount = 6;  // 4 KB sectors hold 41 records: a compaction happens in the cut range
  uint64_t total = 0;
  {
    TestBoard b{sim_board::SimBoardOptions{}};
    persist_sequence(b, kPrefill, 0, std::nullopt);
    const uint64_t before = b.board.flash().steps();
    persist_sequence(b, 0, kCount, std::nullopt);
    total = b.board.flash().steps() - before;
    ASSERT_GT(b.board.firmware()->board().store().compactions(), 0u) << "the cut range must include a compaction";
  }
  size_t old_kept = 0, new_kept = 0;
  for (uint64_t cut = 0; cut <= total; ++cut) {
    TestBoard b{sim_board::SimBoardOptions{}};
    const int last_ok = persist_sequence(b, kPrefill, kCount, cut);
    b.board.power_cycle();
    ASSERT_NE(b.board.firmware(), nullptr) << "no firmware after a cut at step " << cut;
    const Config now = stored_config(b);
    const bool is_old = same(now, numbered_config(static_cast<uint16_t>(last_ok)));
    const bool is_new = last_ok < kPrefill + kCount && same(now, numbered_config(static_cast<uint16_t>(last_ok + 1)));
    ASSERT_TRUE(is_old || is_new) << "cut at step " << cut << ": config " << now.target_id
                                  << ", last acknowledged " << last_ok;
    (is_old ? old_kept : new_kept)++;
    // And the board keeps working: the next persist succeeds and survives a reboot.
    b.configure(numbered_config(999));
    ASSERT_TRUE(acked(b.request(protocol::PersistConfig{}))) << "cut at step " << cut;
    b.board.power_cycle();
    ASSERT_TRUE(same(stored_config(b), numbered_config(999))) << "cut at step " << cut;
  }
  std::printf("[measure] config power cuts: %llu cut points, old kept %zu, new kept %zu\n",
              static_cast<unsigned long long>(total + 1), old_kept, new_kept);
  EXPECT_GT(old_kept, 0u);
  EXPECT_GT(new_kept, 0u);
}

// A whole update as a host runs it: begin, chunks, verify, reboot into the new image,
// which then runs and is asked for its status until it has confirmed itself.
struct UpdateRun {
  bool verified = false;
  bool rebooted = false;
};

UpdateRun run_update(TestBoard& b, const std::vector<uint8_t>& image, uint32_t version, LinkKind link) {
  UpdateRun run;
  const uint32_t crc = protocol::crc32c(image.data(), image.size());
  if (!acked(b.request(protocol::UpdateBegin{static_cast<uint32_t>(image.size()), version, crc}, link))) return run;
  for (size_t off = 0; off < image.size(); off += protocol::kMaxUpdateChunk) {
    protocol::UpdateChunk chunk;
    chunk.offset = static_cast<uint32_t>(off);
    chunk.length = static_cast<uint16_t>(std::min<size_t>(protocol::kMaxUpdateChunk, image.size() - off));
    std::copy(image.begin() + static_cast<std::ptrdiff_t>(off),
              image.begin() + static_cast<std::ptrdiff_t>(off + chunk.length), chunk.data.begin());
    if (!acked(b.request(chunk, link))) return run;
  }
  if (!acked(b.request(protocol::UpdateVerify{}, link))) return run;
  run.verified = true;
  if (!acked(b.request(protocol::Reboot{protocol::RebootMode::kApplication}, link))) return run;
  run.rebooted = true;
  for (int i = 0; i < 8; ++i) {
    b.board.advance_to(b.board.now() + kSecond);
    b.request(protocol::GetStatus{}, link);
  }
  return run;
}

constexpr uint32_t kOld = protocol::pack_version(1, 0, 0);
constexpr uint32_t kNew = protocol::pack_version(1, 1, 0);

std::vector<uint8_t> new_image() {
  sim_board::SimImageSpec spec;
  spec.fw_version = kNew;
  spec.payload_size = 1500;
  spec.seed = 42;
  return sim_board::make_sim_image(spec);
}

TEST(Update, PowerCutAtEveryWriteStepAlwaysBootsAValidImageAndConfig) {
  const std::vector<uint8_t> image = new_image();
  const Config config = numbered_config(7);
  uint64_t total = 0;
  {
    TestBoard b{sim_board::SimBoardOptions{}};
    b.configure(config);
    ASSERT_TRUE(acked(b.request(protocol::PersistConfig{})));
    const uint64_t before = b.board.flash().steps();
    const UpdateRun run = run_update(b, image, kNew, LinkKind::kUsb);
    ASSERT_TRUE(run.rebooted);
    ASSERT_EQ(b.board.running_version(), kNew);
    ASSERT_TRUE(b.board.firmware()->confirmed());
    total = b.board.flash().steps() - before;
  }
  size_t old_runs = 0, new_runs = 0;
  for (uint64_t cut = 0; cut <= total; ++cut) {
    TestBoard b{sim_board::SimBoardOptions{}};
    b.configure(config);
    ASSERT_TRUE(acked(b.request(protocol::PersistConfig{})));
    b.board.flash().cut_power_after(cut);
    run_update(b, image, kNew, LinkKind::kUsb);
    b.board.power_cycle();
    ASSERT_NE(b.board.firmware(), nullptr) << "cut at step " << cut << ": no image started";
    const uint32_t v = b.board.running_version();
    ASSERT_TRUE(v == kOld || v == kNew) << "cut at step " << cut;
    (v == kOld ? old_runs : new_runs)++;
    ASSERT_TRUE(same(stored_config(b), config)) << "cut at step " << cut << ": configuration lost";
    const protocol::Message info = b.request(protocol::GetInfo{});
    ASSERT_NE(info.get<protocol::Info>(), nullptr);
    EXPECT_EQ(info.get<protocol::Info>()->fw_version, v);
  }
  std::printf("[measure] update power cuts: %llu cut points, old image kept %zu, new image running %zu\n",
              static_cast<unsigned long long>(total + 1), old_runs, new_runs);
  EXPECT_GT(old_runs, 0u);
  EXPECT_GT(new_runs, 0u);
}

}  // namespace
}  // namespace tetrapulse::fw::testing

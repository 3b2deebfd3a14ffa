// The bootloader's own update paths on the simulated board (sim_bootloader.hpp, built as
// the STM32F405's bootloader builds them), with the power cut after every flash write step
// (one programmed byte or a quarter-sector erase step; the torn step leaves random bits):
//   USB DFU   the application asked to stay in the bootloader, dfu-util downloads the new
//             image, the bootloader restarts into it, the trial start, its confirmation;
//   CAN       the same through UpdateBegin/Chunk/Verify and Reboot, into the other slot
//             (the image switches back to slot 0);
//   rollback  a new image that never confirms itself: three trial starts, then the old one.
// After every cut the board is powered up again: it must start a valid image (the old or
// the new one) with its configuration intact, and take the same update again. Images the
// bootloader must refuse (foreign, truncated, stale, tampered) leave the running one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include "board_testing.hpp"
#include "dfu_util_model.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;

constexpr uint32_t kV1 = tp::pack_version(1, 0, 0);  // the factory image, slot 0
constexpr uint32_t kV2 = tp::pack_version(2, 0, 0);
constexpr uint32_t kV3 = tp::pack_version(3, 0, 0);

std::vector<uint8_t> image(uint32_t version, uint32_t seed = 5) {
  sim_board::SimImageSpec spec;
  spec.fw_version = version;
  spec.payload_size = 600;
  spec.seed = seed;
  return sim_board::make_sim_image(spec);
}

// Configurations that differ in fields the store keeps (the LEDs stay dark: the sequences
// run tens of seconds of board time, and LED changes cost simulation time, not coverage).
tp::Config numbered_config(uint16_t n) {
  tp::Config c = tp::default_config();
  c.target_id = n;
  c.brightness = static_cast<uint16_t>(1000 + n);
  return c;
}

bool same(const tp::Config& a, const tp::Config& b) {
  uint8_t x[tp::kConfigSize], y[tp::kConfigSize];
  tp::ByteWriter wx(x, sizeof(x)), wy(y, sizeof(y));
  return tp::encode_config(a, wx) && tp::encode_config(b, wy) && std::equal(x, x + sizeof(x), y);
}

// A request whose answer may not come (the power is gone): no test failure then.
std::optional<tp::Message> try_request(TestBoard& b, const tp::Body& body, LinkKind link) {
  const tp::Result<tp::Message> m = b.host.request(link, tp::Message{++b.seq, body});
  if (!m) return std::nullopt;
  return *m;
}
bool acked(const std::optional<tp::Message>& m) { return m && m->get<tp::Ack>() != nullptr; }

std::optional<tp::Config> stored_config(TestBoard& b) {
  const auto m = try_request(b, tp::GetConfig{}, LinkKind::kUsb);
  const auto* report = m ? m->get<tp::ConfigReport>() : nullptr;
  if (report == nullptr) return std::nullopt;
  return report->config;
}

// The host's end of the bootloader's DFU interface, as a FunctionFS gadget hands ep0 over;
// a board that has left the bootloader (reset) stalls everything, as a vanished device.
class BootloaderDfuPipe final : public ControlPipe {
 public:
  explicit BootloaderDfuPipe(sim_board::SimBoard& board) : board_(board) {}
  ControlResult in(const UsbSetup& setup) override {
    if (board_.bootloader() == nullptr) return gone();
    FunctionHost host(board_.bootloader()->dfu());
    return host.in(setup);
  }
  ControlResult out(const UsbSetup& setup, const std::vector<uint8_t>& data) override {
    if (board_.bootloader() == nullptr) return gone();
    FunctionHost host(board_.bootloader()->dfu());
    return host.out(setup, data);
  }
  void bus_reset() override {
    if (board_.bootloader() != nullptr) board_.bootloader()->dfu().bus_reset();
  }

 private:
  static ControlResult gone() {
    ControlResult r;
    r.stalled = true;
    return r;
  }
  sim_board::SimBoard& board_;
};

// The application asks to stay in the bootloader (Reboot{bootloader}, as DFU_DETACH does).
bool enter_bootloader(TestBoard& b) {
  try_request(b, tp::Reboot{tp::RebootMode::kBootloader}, LinkKind::kUsb);
  b.board.advance_to(b.board.now() + 10 * kMs);
  return b.board.bootloader() != nullptr;
}

// After an install the board restarts into the new image; the host asks for its status
// every second until it has confirmed itself (5 s and an answered request).
void run_until_confirmed(TestBoard& b) {
  b.board.advance_to(b.board.now() + 300 * kMs);
  for (int i = 0; i < 7; ++i) {
    b.board.advance_to(b.board.now() + kSecond);
    try_request(b, tp::GetStatus{}, LinkKind::kUsb);
  }
}

// dfu-util -D file, then the restart and the confirmation. True when dfu-util said Done.
bool dfu_update(TestBoard& b, const std::vector<uint8_t>& file) {
  if (!enter_bootloader(b)) return false;
  BootloaderDfuPipe pipe(b.board);
  DfuUtilModel util(pipe, 0, sim_board::SimBootloader::kTransferSize,
                    [&](uint32_t ms) { b.board.advance_to(b.board.now() + int64_t{ms} * kMs); });
  const bool done = util.download(file);
  run_until_confirmed(b);
  return done;
}

// The CAN path: UpdateBegin, chunks, UpdateVerify, Reboot{application}. True when verified.
bool can_update(TestBoard& b, const std::vector<uint8_t>& img, uint32_t announced_version) {
  if (!enter_bootloader(b)) return false;
  const uint32_t crc = tp::crc32c(img.data(), img.size());
  bool ok = acked(try_request(b, tp::UpdateBegin{static_cast<uint32_t>(img.size()), announced_version, crc},
                              LinkKind::kCan));
  for (size_t off = 0; ok && off < img.size(); off += tp::kMaxUpdateChunk) {
    tp::UpdateChunk chunk;
    chunk.offset = static_cast<uint32_t>(off);
    chunk.length = static_cast<uint16_t>(std::min<size_t>(tp::kMaxUpdateChunk, img.size() - off));
    std::copy(img.begin() + static_cast<std::ptrdiff_t>(off),
              img.begin() + static_cast<std::ptrdiff_t>(off + chunk.length), chunk.data.begin());
    ok = acked(try_request(b, chunk, LinkKind::kCan));
  }
  const bool verified = ok && acked(try_request(b, tp::UpdateVerify{}, LinkKind::kCan));
  try_request(b, tp::Reboot{tp::RebootMode::kApplication}, LinkKind::kCan);
  run_until_confirmed(b);
  return verified;
}

// A new image that never confirms itself (it hangs, never answering): the watchdog resets
// the board over and over; after kMaxTrialBoots trial starts the old image runs again.
void never_confirming_boots(TestBoard& b) {
  for (int i = 0; i < kMaxTrialBoots + 1 && b.board.flash().powered(); ++i) {
    b.board.advance_to(b.board.now() + 6 * kSecond);
    b.board.reset();
  }
}

enum class Start {
  kFactory,    // v1 in slot 0, confirmed
  kV2Confirmed,  // v2 in slot 1, confirmed (installed over DFU)
  kV2OnTrial,  // v2 downloaded over DFU and started once, never answering: not confirmed
};

// The factory board with `prefill` rewrites of its boot state (24 bytes each, the record
// store's smallest record: they move it towards a compaction in steps small enough that
// some prefill puts one into any sequence), configuration `config` persisted, then brought
// to `start` uncut.
void prepare(TestBoard& b, const tp::Config& config, int prefill, Start start) {
  if (prefill > 0) {
    RecordStore store(b.board.flash(), sim_board::sim_flash_layout().record_sectors);
    ASSERT_TRUE(store.open().ok());
    const tp::Result<BootState> state = load_boot_state(store);
    ASSERT_TRUE(state.ok());
    for (int i = 0; i < prefill; ++i) ASSERT_TRUE(save_boot_state(store, *state).ok());
    b.board.power_cycle();
  }
  b.configure(config);
  ASSERT_TRUE(acked(try_request(b, tp::PersistConfig{}, LinkKind::kUsb)));
  if (start == Start::kV2Confirmed) {
    ASSERT_TRUE(dfu_update(b, image(kV2)));
    ASSERT_EQ(b.board.running_version(), kV2);
    ASSERT_TRUE(b.board.firmware()->confirmed());
  } else if (start == Start::kV2OnTrial) {
    ASSERT_TRUE(enter_bootloader(b));
    BootloaderDfuPipe pipe(b.board);
    DfuUtilModel util(pipe, 0, sim_board::SimBootloader::kTransferSize,
                      [&](uint32_t ms) { b.board.advance_to(b.board.now() + int64_t{ms} * kMs); });
    ASSERT_TRUE(util.download(image(kV2))) << util.error;
    b.board.advance_to(b.board.now() + 300 * kMs);
    ASSERT_EQ(b.board.running_version(), kV2);
    ASSERT_FALSE(b.board.firmware()->confirmed());
  }
}

// Both record sectors written: appends touch only the active one, a compaction writes
// the other (and its header last).
bool compacted(const std::vector<uint8_t>& before, const std::vector<uint8_t>& after) {
  const FlashLayout layout = sim_board::sim_flash_layout();
  int changed = 0;
  for (const FlashRegion& r : layout.record_sectors) {
    const auto from = static_cast<std::ptrdiff_t>(r.address), to = static_cast<std::ptrdiff_t>(r.address + r.size);
    changed += !std::equal(before.begin() + from, before.begin() + to, after.begin() + from);
  }
  return changed == 2;
}

struct Sweep {
  const char* name;
  Start start;
  std::function<void(TestBoard&)> run;  // the sequence the cuts fall in
  uint32_t old_version, new_version;    // what runs before and after it
};

struct SweepResult {
  uint64_t cut_points = 0;
  size_t old_runs = 0, new_runs = 0;
  int prefill = 0;
};

// The first prefill (0..200 boot-state rewrites: more than a sector) whose uncut sequence
// compacts the record store, so the cuts also fall into a compaction.
int prefill_for_compaction(const Sweep& s, const tp::Config& config) {
  for (int prefill = 0; prefill <= 200; ++prefill) {
    TestBoard b{sim_board::SimBoardOptions{}};
    prepare(b, config, prefill, s.start);
    const std::vector<uint8_t> before = b.board.flash().contents();
    s.run(b);
    if (compacted(before, b.board.flash().contents())) return prefill;
  }
  ADD_FAILURE() << s.name << ": no prefill puts a compaction into the sequence";
  return 0;
}

SweepResult sweep(const Sweep& s, const std::vector<uint8_t>& again) {
  const tp::Config config = numbered_config(7);
  SweepResult result;
  result.prefill = prefill_for_compaction(s, config);
  uint64_t total = 0;
  {
    TestBoard b{sim_board::SimBoardOptions{}};
    prepare(b, config, result.prefill, s.start);
    const uint64_t before = b.board.flash().steps();
    s.run(b);
    EXPECT_EQ(b.board.running_version(), s.new_version) << s.name << ": the uncut sequence ends on the new image";
    total = b.board.flash().steps() - before;
  }
  for (uint64_t cut = 0; cut <= total; ++cut) {
    TestBoard b{sim_board::SimBoardOptions{}};
    prepare(b, config, result.prefill, s.start);
    b.board.flash().cut_power_after(cut);
    s.run(b);
    b.board.power_cycle();
    const std::string where = std::string(s.name) + ", cut at step " + std::to_string(cut);
    if (b.board.firmware() == nullptr) {
      ADD_FAILURE() << where << ": no valid image started";
      return result;
    }
    const uint32_t v = b.board.running_version();
    if (v != s.old_version && v != s.new_version) {
      ADD_FAILURE() << where << ": runs version " << v;
      return result;
    }
    (v == s.old_version ? result.old_runs : result.new_runs)++;
    if (s.start == Start::kV2OnTrial) {
      // The rollback goes on from wherever the cut left it and ends on the old image.
      never_confirming_boots(b);
      if (b.board.firmware() == nullptr || b.board.running_version() != kV1) {
        ADD_FAILURE() << where << ": the rollback did not end on v1";
        return result;
      }
    }
    const std::optional<tp::Config> now = stored_config(b);
    if (!now || !same(*now, config)) {
      ADD_FAILURE() << where << ": configuration lost";
      return result;
    }
    // Not wedged: the same update again, uncut, lands (DFU into whichever slot is free).
    if (!dfu_update(b, again) || !b.board.firmware() || b.board.running_version() != tp::pack_version(9, 0, 0) ||
        !b.board.firmware()->confirmed()) {
      ADD_FAILURE() << where << ": the next update did not land";
      return result;
    }
  }
  result.cut_points = total + 1;
  return result;
}

class BootloaderPowerCut : public ::testing::TestWithParam<int> {};

TEST_P(BootloaderPowerCut, EveryWriteStepLeavesAValidImageAndTheConfiguration) {
  const std::vector<uint8_t> v2 = image(kV2), v3 = image(kV3, 6), v9 = image(tp::pack_version(9, 0, 0), 9);
  const Sweep sweeps[] = {
      {"USB DFU (v1 -> v2 in slot 1)", Start::kFactory, [&](TestBoard& b) { dfu_update(b, v2); }, kV1, kV2},
      {"CAN (v2 -> v3, back in slot 0)", Start::kV2Confirmed, [&](TestBoard& b) { can_update(b, v3, kV3); }, kV2, kV3},
      {"rollback (v2 on trial never confirms: v1 again)", Start::kV2OnTrial, never_confirming_boots, kV2, kV1},
  };
  const Sweep& s = sweeps[GetParam()];
  const SweepResult r = sweep(s, v9);
  std::printf("[measure] bootloader power cuts, %s: %llu cut points (record store prefilled with %d records: a"
              " compaction among them); afterwards the old image ran %zu times, the new one %zu; 0 unbootable,"
              " 0 configurations lost, the next update landed every time\n",
              s.name, static_cast<unsigned long long>(r.cut_points), r.prefill, r.old_runs, r.new_runs);
  EXPECT_GT(r.cut_points, 0u);
  EXPECT_GT(r.old_runs, 0u);
  EXPECT_GT(r.new_runs, 0u);
}

INSTANTIATE_TEST_SUITE_P(Paths, BootloaderPowerCut, ::testing::Values(0, 1, 2));

// Images the bootloader must refuse, on either path; the running image stays, byte for
// byte, with nothing pending and the configuration intact.
struct BadImage {
  const char* name;
  std::vector<uint8_t> file;
  uint32_t announced_version;  // CAN's UpdateBegin.version
  bool over_dfu = true;        // DFU announces nothing: a stale image is only refusable on CAN
};

std::vector<BadImage> bad_images() {
  std::vector<BadImage> out;
  sim_board::SimImageSpec foreign;
  foreign.fw_version = kV2;
  foreign.payload_size = 600;
  foreign.hw_model = tp::HwModel::kStm32f405Reference;
  out.push_back({"foreign (built for the STM32F405)", sim_board::make_sim_image(foreign), kV2});
  sim_board::SimImageSpec revision = foreign;
  revision.hw_model = tp::HwModel::kSimulatedBoard;
  revision.hw_revision_min = 5;  // the board is revision 1
  out.push_back({"foreign (for hardware revisions 5..255)", sim_board::make_sim_image(revision), kV2});
  std::vector<uint8_t> truncated = image(kV2);
  truncated.resize(truncated.size() - 100);
  out.push_back({"truncated (100 bytes short)", truncated, kV2});
  // Stale: the host announces v3 and sends the old v2 build.
  // (SPEC.md §7.3: an older image itself is not refused; downgrades are the host's choice.)
  out.push_back({"stale (v2 sent as v3)", image(kV2), kV3, false});
  std::vector<uint8_t> payload = image(kV2);
  payload[payload.size() / 2] ^= 0x10;
  out.push_back({"tampered payload (one bit)", payload, kV2});
  std::vector<uint8_t> header = image(kV2);
  header[20] ^= 0x01;  // inside the 64-byte header
  out.push_back({"tampered header (one bit)", header, kV2});
  return out;
}

class RefusedImage : public ::testing::TestWithParam<std::tuple<size_t, LinkKind>> {};

TEST_P(RefusedImage, IsRefusedAndTheRunningImageKept) {
  const auto [index, link] = GetParam();
  const BadImage bad = bad_images()[index];
  TestBoard b{sim_board::SimBoardOptions{}};
  const tp::Config config = numbered_config(7);
  prepare(b, config, 0, Start::kFactory);
  const FlashLayout layout = sim_board::sim_flash_layout();
  const auto slot0 = [&] {
    const auto& c = b.board.flash().contents();
    const auto from = static_cast<std::ptrdiff_t>(layout.slots[0].region.address);
    return std::vector<uint8_t>(c.begin() + from, c.begin() + from + static_cast<std::ptrdiff_t>(layout.slots[0].region.size));
  };
  const std::vector<uint8_t> before = slot0();
  ASSERT_EQ(bad.file.empty(), false);
  bool installed = false;
  if (link == LinkKind::kCan) {
    installed = can_update(b, bad.file, bad.announced_version);
  } else if (enter_bootloader(b)) {
    BootloaderDfuPipe pipe(b.board);
    DfuUtilModel util(pipe, 0, sim_board::SimBootloader::kTransferSize,
                      [&](uint32_t ms) { b.board.advance_to(b.board.now() + int64_t{ms} * kMs); });
    installed = util.download(bad.file);
    std::printf("[measure] DFU, %s: dfu-util says \"%s\" (status %d)\n", bad.name, util.error.c_str(),
                static_cast<int>(util.last.status));
  }
  EXPECT_FALSE(installed) << bad.name;
  b.board.power_cycle();
  ASSERT_NE(b.board.firmware(), nullptr) << bad.name;
  EXPECT_EQ(b.board.running_version(), kV1) << bad.name;
  EXPECT_EQ(b.board.active_slot(), 0) << bad.name;
  EXPECT_EQ(slot0(), before) << bad.name << ": the running image was touched";
  RecordStore store(b.board.flash(), layout.record_sectors);
  ASSERT_TRUE(store.open().ok());
  EXPECT_EQ(load_boot_state(store)->pending_slot, kNoSlot) << bad.name << ": nothing may be pending";
  const std::optional<tp::Config> now = stored_config(b);
  ASSERT_TRUE(now.has_value());
  EXPECT_TRUE(same(*now, config));
  // The same path takes a good image afterwards (so the refusal was the image's).
  const bool good = link == LinkKind::kCan ? can_update(b, image(kV3, 6), kV3) : dfu_update(b, image(kV3, 6));
  EXPECT_TRUE(good) << bad.name;
  EXPECT_EQ(b.board.running_version(), kV3) << bad.name;
}

std::vector<std::tuple<size_t, LinkKind>> refusal_cases() {
  std::vector<std::tuple<size_t, LinkKind>> out;
  const std::vector<BadImage> all = bad_images();
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i].over_dfu) out.emplace_back(i, LinkKind::kUsb);
    out.emplace_back(i, LinkKind::kCan);
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(BothPaths, RefusedImage, ::testing::ValuesIn(refusal_cases()));

}  // namespace
}  // namespace tetrapulse::fw::testing

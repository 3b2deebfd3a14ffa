// The bootloader's DFU download target (SPEC.md §5.6, §7.2): a release bundle (one image
// per slot, back to back) or a single image streams in blocks of any size; only the image
// linked for the target slot lands there, verified and marked pending, and every broken
// file is refused with the DFU status the host sees. The last tests run the whole
// bootloader path on the host: dfu-util, the control endpoint, the DFU state machine,
// this writer, and the boot selection that starts the new image.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "dfu_util_model.hpp"
#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/fw/boot/image_bundle_writer.hpp"
#include "tetrapulse/fw/boot/slot_survey.hpp"
#include "tetrapulse/fw/boot/update_slot.hpp"
#include "tetrapulse/fw/usb/dfu_device.hpp"
#include "tetrapulse/protocol/crc.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "tetrapulse/sim_board/sim_flash.hpp"
#include "usb_test_host.hpp"

namespace tetrapulse::fw::testing {
namespace {

namespace tp = protocol;
using tp::DfuStatusCode;

// A flash shaped like the STM32F405's, scaled down: two record sectors, two slots whose
// images are linked for their own base (load_address = slot address), 512-byte vectors.
constexpr uint32_t kSlotBase[2] = {0x08020000, 0x08028000};
constexpr uint32_t kSlotSize = 0x8000;
constexpr uint32_t kVectorOffset = 0x200;
const BoardModel kBoard{tp::HwModel::kStm32f405Reference, 1};

std::vector<FlashRegion> sectors() {
  return {FlashRegion{0x08008000, 0x4000}, FlashRegion{0x0800C000, 0x4000}, FlashRegion{kSlotBase[0], kSlotSize},
          FlashRegion{kSlotBase[1], kSlotSize}};
}

FlashLayout layout() {
  FlashLayout l;
  l.record_sectors = {FlashRegion{0x08008000, 0x4000}, FlashRegion{0x0800C000, 0x4000}};
  for (uint8_t s = 0; s < 2; ++s) l.slots[s] = SlotLayout{FlashRegion{kSlotBase[s], kSlotSize}, kSlotBase[s]};
  l.vector_alignment = 512;
  return l;
}

struct ImageSpec {
  uint32_t load_address = kSlotBase[0];
  uint32_t version = tp::pack_version(2, 0, 0);
  uint32_t payload = 3000;
  tp::HwModel model = tp::HwModel::kStm32f405Reference;
  uint32_t seed = 1;
};

std::vector<uint8_t> make_image(const ImageSpec& spec) {
  std::vector<uint8_t> payload(spec.payload);
  uint32_t x = spec.seed * 2654435761u + spec.load_address;
  for (auto& b : payload) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<uint8_t>(x >> 24);
  }
  tp::ImageHeader h;
  h.hw_model = spec.model;
  h.hw_revision_min = 0;
  h.hw_revision_max = 255;
  h.fw_version = spec.version;
  h.payload_size = spec.payload;
  h.vector_offset = kVectorOffset;
  h.load_address = spec.load_address;
  h.payload_crc32c = tp::crc32c(payload.data(), payload.size());
  std::vector<uint8_t> image(kVectorOffset, 0);
  tp::ByteWriter w(image.data(), image.size());
  EXPECT_TRUE(tp::encode_image_header(h, w).ok());
  image.insert(image.end(), payload.begin(), payload.end());
  return image;
}

std::vector<uint8_t> bundle(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  std::vector<uint8_t> out = a;
  out.insert(out.end(), b.begin(), b.end());
  return out;
}

struct Board {
  Board() : flash(sectors()), store(flash, layout().record_sectors) { EXPECT_TRUE(store.open().ok()); }
  std::vector<uint8_t> slot(uint8_t s, size_t n) const {
    const size_t base = kSlotBase[s] - sectors()[0].address;
    return std::vector<uint8_t>(flash.contents().begin() + static_cast<std::ptrdiff_t>(base),
                                flash.contents().begin() + static_cast<std::ptrdiff_t>(base + n));
  }
  sim_board::SimFlash flash;
  RecordStore store;
};

// Streams `file` in blocks of `block` bytes, then manifests; the first failing status.
DfuStatusCode stream(ImageBundleWriter& w, const std::vector<uint8_t>& file, size_t block) {
  DfuDownloadTarget& t = w;
  for (size_t off = 0; off < file.size(); off += block) {
    const size_t n = std::min(block, file.size() - off);
    const DfuStatusCode s = t.download(static_cast<uint32_t>(off), tp::ByteView{file.data() + off, n});
    if (s != DfuStatusCode::kOk) return s;
  }
  return t.manifest(static_cast<uint32_t>(file.size()));
}

TEST(ImageBundleWriter, WritesTheImageForTheTargetSlotAndSkipsTheOther) {
  for (uint8_t target : {0, 1}) {
    Board b;
    const std::vector<uint8_t> for0 = make_image({kSlotBase[0], tp::pack_version(2, 0, 0), 3000});
    const std::vector<uint8_t> for1 = make_image({kSlotBase[1], tp::pack_version(2, 0, 0), 3000});
    const std::vector<uint8_t> untouched = b.slot(target == 0 ? 1 : 0, 4096);
    ImageBundleWriter w(b.flash, layout(), b.store, kBoard, target, kNoSlot);
    EXPECT_EQ(stream(w, bundle(for0, for1), 1024), DfuStatusCode::kOk);
    const std::vector<uint8_t>& mine = target == 0 ? for0 : for1;
    EXPECT_EQ(b.slot(target, mine.size()), mine) << "slot " << int(target);
    EXPECT_EQ(b.slot(target == 0 ? 1 : 0, 4096), untouched) << "the other slot is never written";
    const tp::Result<BootState> state = load_boot_state(b.store);
    ASSERT_TRUE(state.ok());
    EXPECT_EQ(state->pending_slot, target);
    EXPECT_EQ(state->pending_version, tp::pack_version(2, 0, 0));
    EXPECT_EQ(state->attempts, 0);
  }
}

TEST(ImageBundleWriter, ASingleImageForTheTargetSlotIsABundleOfOne) {
  Board b;
  const std::vector<uint8_t> img = make_image({kSlotBase[1], tp::pack_version(3, 1, 0), 5000});
  ImageBundleWriter w(b.flash, layout(), b.store, kBoard, 1, 0);
  EXPECT_EQ(stream(w, img, 1024), DfuStatusCode::kOk);
  EXPECT_EQ(b.slot(1, img.size()), img);
  const tp::Result<BootState> state = load_boot_state(b.store);
  ASSERT_TRUE(state.ok());
  EXPECT_EQ(state->pending_slot, 1);
  EXPECT_EQ(state->confirmed_slot, 0) << "the known-good slot stays confirmed";
}

RC_GTEST_PROP(ImageBundleWriter, AnyBlockSizeWritesTheSameSlot, ()) {
  const auto block = *rc::gen::inRange<size_t>(1, 2100);
  const auto first = *rc::gen::inRange<uint32_t>(1, 4000);
  const auto second = *rc::gen::inRange<uint32_t>(1, 4000);
  const auto target = *rc::gen::inRange<uint8_t>(0, 2);
  Board b;
  const std::vector<uint8_t> for0 = make_image({kSlotBase[0], 7, first, tp::HwModel::kStm32f405Reference, first});
  const std::vector<uint8_t> for1 = make_image({kSlotBase[1], 8, second, tp::HwModel::kStm32f405Reference, second});
  const bool slot1_first = *rc::gen::arbitrary<bool>();
  ImageBundleWriter w(b.flash, layout(), b.store, kBoard, target, kNoSlot);
  RC_ASSERT(stream(w, slot1_first ? bundle(for1, for0) : bundle(for0, for1), block) == DfuStatusCode::kOk);
  const std::vector<uint8_t>& mine = target == 0 ? for0 : for1;
  RC_ASSERT(b.slot(target, mine.size()) == mine);
  RC_ASSERT(w.image_header().fw_version == (target == 0 ? 7u : 8u));
}

TEST(ImageBundleWriter, RefusesFilesItCannotInstall) {
  const std::vector<uint8_t> for0 = make_image({kSlotBase[0]});
  const std::vector<uint8_t> for1 = make_image({kSlotBase[1]});
  const auto status_of = [](const std::vector<uint8_t>& file, uint8_t target = 1) {
    Board b;
    ImageBundleWriter w(b.flash, layout(), b.store, kBoard, target, kNoSlot);
    const DfuStatusCode s = stream(w, file, 1024);
    if (s != DfuStatusCode::kOk) {
      EXPECT_FALSE(load_boot_state(b.store).ok()) << "nothing marked pending";
    }
    return s;
  };
  EXPECT_EQ(status_of(for0), DfuStatusCode::kErrFile) << "no image for slot 1";
  EXPECT_EQ(status_of(bundle(for1, for1)), DfuStatusCode::kErrFile) << "two images for slot 1";
  std::vector<uint8_t> bad_magic = bundle(for0, for1);
  bad_magic[for0.size()] ^= 0xFF;
  EXPECT_EQ(status_of(bad_magic), DfuStatusCode::kErrFile) << "second header broken";
  std::vector<uint8_t> trailing = bundle(for0, for1);
  trailing.insert(trailing.end(), 100, 0xFF);
  EXPECT_EQ(status_of(trailing), DfuStatusCode::kErrFile) << "bytes after the last image";
  std::vector<uint8_t> short_tail = bundle(for0, for1);
  short_tail.insert(short_tail.end(), 10, 0xFF);
  EXPECT_EQ(status_of(short_tail), DfuStatusCode::kErrNotDone) << "a partial header at the end";
  std::vector<uint8_t> cut = bundle(for0, for1);
  cut.resize(cut.size() - 1);
  EXPECT_EQ(status_of(cut), DfuStatusCode::kErrNotDone) << "the file ends inside an image";
  std::vector<uint8_t> corrupt = bundle(for0, for1);
  corrupt[for0.size() + kVectorOffset + 100] ^= 0x01;
  EXPECT_EQ(status_of(corrupt), DfuStatusCode::kErrVerify) << "payload CRC";
  std::vector<uint8_t> corrupt_other = bundle(for0, for1);
  corrupt_other[kVectorOffset + 100] ^= 0x01;
  EXPECT_EQ(status_of(corrupt_other), DfuStatusCode::kOk) << "the skipped image is not ours to check";
  const std::vector<uint8_t> sim = make_image({kSlotBase[1], 1, 3000, tp::HwModel::kSimulatedBoard});
  EXPECT_EQ(status_of(sim), DfuStatusCode::kErrTarget) << "built for another board";
  const std::vector<uint8_t> huge = make_image({kSlotBase[1], 1, kSlotSize});
  EXPECT_EQ(status_of(huge), DfuStatusCode::kErrAddress) << "larger than the slot";
}

TEST(ImageBundleWriter, FlashFailuresBecomeDfuStatuses) {
  const std::vector<uint8_t> img = make_image({kSlotBase[1]});
  {
    Board b;
    ImageBundleWriter w(b.flash, layout(), b.store, kBoard, 1, kNoSlot);
    b.flash.fail_next(1);
    EXPECT_EQ(stream(w, img, 1024), DfuStatusCode::kErrErase);
  }
  {
    Board b;
    ImageBundleWriter w(b.flash, layout(), b.store, kBoard, 1, kNoSlot);
    DfuDownloadTarget& t = w;
    ASSERT_EQ(t.download(0, tp::ByteView{img.data(), 1024}), DfuStatusCode::kOk);
    b.flash.fail_next(1);
    EXPECT_EQ(t.download(1024, tp::ByteView{img.data() + 1024, 1024}), DfuStatusCode::kErrProg);
  }
}

TEST(ImageBundleWriter, ANewDownloadClearsAPendingMarkOnItsSlot) {
  Board b;
  ASSERT_TRUE(mark_slot_pending(b.store, 1, 5, 0).ok());
  ImageBundleWriter w(b.flash, layout(), b.store, kBoard, 1, 0);
  const std::vector<uint8_t> img = make_image({kSlotBase[1]});
  DfuDownloadTarget& t = w;
  ASSERT_EQ(t.download(0, tp::ByteView{img.data(), 512}), DfuStatusCode::kOk);
  const tp::Result<BootState> state = load_boot_state(b.store);
  ASSERT_TRUE(state.ok());
  EXPECT_EQ(state->pending_slot, kNoSlot) << "a half-written slot must never be tried";
  t.abort();
  EXPECT_EQ(load_boot_state(b.store)->pending_slot, kNoSlot);
}

TEST(UpdateSlot, TheTargetIsNeverTheKnownGoodImage) {
  const std::array<SlotCheck, kSlotCount> both{SlotCheck{true, 5}, SlotCheck{true, 7}};
  const std::array<SlotCheck, kSlotCount> only0{SlotCheck{true, 5}, SlotCheck{false, 0}};
  const std::array<SlotCheck, kSlotCount> only1{SlotCheck{false, 0}, SlotCheck{true, 5}};
  const std::array<SlotCheck, kSlotCount> none{};
  const tp::Result<BootState> fresh = tp::Error::kInvalidState;
  EXPECT_EQ(update_target_slot(fresh, none), 0) << "an empty board fills slot 0";
  EXPECT_EQ(update_target_slot(fresh, only0), 1);
  EXPECT_EQ(update_target_slot(fresh, only1), 0);
  EXPECT_EQ(update_target_slot(fresh, both), 0) << "the newest (slot 1) is what runs";
  BootState confirmed0;
  confirmed0.confirmed_slot = 0;
  EXPECT_EQ(update_target_slot(confirmed0, both), 1);
  BootState pending0 = confirmed0;
  pending0.confirmed_slot = 1;
  pending0.pending_slot = 0;
  EXPECT_EQ(update_target_slot(pending0, both), 0) << "the untested pending image is replaced, not the confirmed one";
  EXPECT_EQ(update_target_slot(confirmed0, only1), 0) << "a confirmed slot that no longer checks is not good";
}

TEST(UpdateSlot, MarkingPendingKeepsOrSetsTheConfirmedSlot) {
  Board b;
  ASSERT_TRUE(mark_slot_pending(b.store, 1, 9, 0).ok());
  BootState s = *load_boot_state(b.store);
  EXPECT_EQ(s, (BootState{0, 1, 0, 9}));
  ASSERT_TRUE(mark_slot_pending(b.store, 0, 10, kNoSlot).ok());
  s = *load_boot_state(b.store);
  EXPECT_EQ(s, (BootState{kNoSlot, 0, 0, 10})) << "slot 0's confirmed image was overwritten";
  ASSERT_TRUE(clear_pending_slot(b.store, 1).ok());
  EXPECT_EQ(*load_boot_state(b.store), s) << "slot 1 was not pending: nothing changes";
  ASSERT_TRUE(clear_pending_slot(b.store, 0).ok());
  EXPECT_EQ(load_boot_state(b.store)->pending_slot, kNoSlot);
}

// What a bootloader starts from: both slots' checks and headers, the stored state, and the
// known-good and target slots that follow from them.
TEST(SlotSurvey, SeesBothSlotsAndTheStoredStateAndNeverTargetsTheKnownGoodImage) {
  Board b;
  const uint32_t v1 = tp::pack_version(1, 0, 0);
  const uint32_t v2 = tp::pack_version(2, 0, 0);
  b.flash.load(kSlotBase[0], make_image({kSlotBase[0], v1, 2500}));
  std::vector<uint8_t> newer = make_image({kSlotBase[1], v2, 2500});
  b.flash.load(kSlotBase[1], newer);

  SlotSurvey fresh = survey_slots(b.store, b.flash, layout(), kBoard);
  EXPECT_EQ(fresh.stored.error(), tp::Error::kInvalidState) << "a factory-fresh board stores no boot state";
  ASSERT_TRUE(fresh.checks[0].valid && fresh.checks[1].valid);
  EXPECT_EQ(fresh.checks[0].fw_version, v1);
  EXPECT_EQ(fresh.headers[1].fw_version, v2);
  EXPECT_EQ(fresh.headers[1].load_address, kSlotBase[1]);
  EXPECT_EQ(fresh.known_good(), 1) << "with no state the newest valid image is the one to keep";
  EXPECT_EQ(fresh.update_target(), 0);

  BootState state;
  state.confirmed_slot = 0;
  ASSERT_TRUE(save_boot_state(b.store, state).ok());
  const SlotSurvey confirmed = survey_slots(b.store, b.flash, layout(), kBoard);
  ASSERT_TRUE(confirmed.stored.ok());
  EXPECT_EQ(*confirmed.stored, state);
  EXPECT_EQ(confirmed.known_good(), 0) << "the confirmed image, not the newer one";
  EXPECT_EQ(confirmed.update_target(), 1);

  newer.back() ^= 0x01;  // a payload byte: the CRC-32C check fails
  Board corrupted;
  corrupted.flash.load(kSlotBase[0], make_image({kSlotBase[0], v1, 2500}));
  corrupted.flash.load(kSlotBase[1], newer);
  const SlotSurvey one = survey_slots(corrupted.store, corrupted.flash, layout(), kBoard);
  EXPECT_TRUE(one.checks[0].valid);
  EXPECT_FALSE(one.checks[1].valid);
  EXPECT_EQ(one.checks[1].fw_version, 0u);
  EXPECT_EQ(one.known_good(), 0);
  EXPECT_EQ(one.update_target(), 1);
}

// The bootloader path end to end: dfu-util sends the release bundle, the bootloader
// installs the image for its inactive slot, and the next reset starts it on trial.
class BootloaderDfu : public ::testing::TestWithParam<size_t> {};

TEST_P(BootloaderDfu, DfuUtilBundleBecomesTheNextBoot) {
  Board b;
  const std::vector<uint8_t> old0 = make_image({kSlotBase[0], tp::pack_version(1, 0, 0), 2500});
  b.flash.load(kSlotBase[0], old0);
  ASSERT_TRUE(choose_boot_slot(b.flash, layout(), kBoard, false).boot);  // slot 0 confirmed
  ASSERT_TRUE(b.store.open().ok());  // choose_boot_slot wrote through a store of its own

  // The bootloader, asked to stay, picks its target and enumerates.
  const SlotSurvey survey = survey_slots(b.store, b.flash, layout(), kBoard);
  const uint8_t target = survey.update_target();
  ASSERT_EQ(target, 1);
  ImageBundleWriter writer(b.flash, layout(), b.store, kBoard, target, survey.known_good());
  tp::UsbDeviceParams params;
  params.mode = tp::UsbMode::kBootloader;
  params.dfu_transfer_size = static_cast<uint16_t>(GetParam());
  std::vector<uint8_t> block(params.dfu_transfer_size);
  DfuDevice dfu(writer, params, block.data(), block.size());
  RecordingController controller;
  uint8_t buffer[64];
  UsbControl control(params, "SERIAL", controller, buffer, sizeof(buffer));
  control.set_function(0, dfu);
  PacketHost host(control);
  enumerate(host, controller);
  uint32_t now = 0;
  DfuUtilModel util(host, 0, params.dfu_transfer_size, [&](uint32_t ms) { dfu.poll(now += ms); });

  const uint32_t v2 = tp::pack_version(2, 0, 0);
  const std::vector<uint8_t> release =
      bundle(make_image({kSlotBase[0], v2, 6000}), make_image({kSlotBase[1], v2, 6000}));
  ASSERT_TRUE(util.download(release)) << util.error;
  EXPECT_TRUE(dfu.installed());
  EXPECT_GE(util.states.size(), 3u);

  const BootChoice next = choose_boot_slot(b.flash, layout(), kBoard, false);
  ASSERT_TRUE(b.store.open().ok());
  EXPECT_TRUE(next.boot);
  EXPECT_EQ(next.slot, 1);
  EXPECT_EQ(next.header.fw_version, v2);
  EXPECT_EQ(load_boot_state(b.store)->attempts, 1) << "started on trial";
  EXPECT_EQ(load_boot_state(b.store)->confirmed_slot, 0) << "the old image stays the fallback";
}

INSTANTIATE_TEST_SUITE_P(TransferSizes, BootloaderDfu, ::testing::Values(64, 1024, 2048));

}  // namespace
}  // namespace tetrapulse::fw::testing

// update_firmware over a SimLink to the protocol responder: the whole §7.3 sequence,
// lost Acks answered by resending, refusals and cancellation aborting cleanly; and the
// choice of the image a board takes from a release of per-slot images.
#include <gtest/gtest.h>

#include "responder_sim_port.hpp"
#include "test_images.hpp"
#include "tetrapulse/host/firmware_update.hpp"
#include "tetrapulse/host/sim_link.hpp"

namespace tetrapulse::host {
namespace {

using protocol::HwModel;
using protocol::Message;
using testing::ResponderSimPort;
using testing::TestImageSpec;

FirmwareImage image_of(const TestImageSpec& spec, const std::string& name = "fw.bin") {
  auto image = check_firmware_image(testing::make_test_image(spec), name);
  EXPECT_TRUE(image) << image.error().what();
  return *image;
}

struct SimBoard {
  std::shared_ptr<ResponderSimPort> port = std::make_shared<ResponderSimPort>();
  Board board{std::make_unique<SimLink>("sim:1", port)};
};

TEST(FirmwareUpdate, WritesVerifiesAndRebootsIntoTheNewVersion) {
  SimBoard b;
  const FirmwareImage image = image_of(TestImageSpec{});
  std::vector<FlashProgress> seen;
  UpdateOptions options;
  options.progress = [&](const FlashProgress& p) { seen.push_back(p); };
  auto report = update_firmware(b.board, image, options);
  ASSERT_TRUE(report) << report.error().what();
  EXPECT_EQ(b.port->responder().installed_image(), image.bytes);
  EXPECT_EQ(report->chunks, (image.bytes.size() + 255) / 256);
  EXPECT_EQ(report->crc32c, image.crc32c);
  EXPECT_EQ(report->running_version, 0x01020003u);
  EXPECT_EQ(report->resent, 0u);
  EXPECT_EQ(b.port->responder().identity().active_slot, 1);
  uint64_t written = 0;
  for (const FlashProgress& p : seen) {
    if (std::string(p.stage) != "write") continue;
    EXPECT_GT(p.done, written);
    written = p.done;
    EXPECT_EQ(p.total, image.bytes.size());
  }
  EXPECT_EQ(written, image.bytes.size());
}

TEST(FirmwareUpdate, ResendsAChunkWhoseAckWasLost) {
  SimBoard b;
  bool lost = false;
  b.port->lose_answers_when([&](const Message& m) {
    const auto* ack = m.get<protocol::Ack>();
    if (lost || ack == nullptr || ack->request_type != protocol::MessageType::kUpdateChunk || ack->value != 1024) return false;
    return lost = true;
  });
  const FirmwareImage image = image_of(TestImageSpec{});
  auto report = update_firmware(b.board, image, UpdateOptions{});
  ASSERT_TRUE(report) << report.error().what();
  EXPECT_EQ(report->resent, 1u);
  EXPECT_EQ(b.port->responder().chunk_repeats(), 1u);
  EXPECT_EQ(b.port->responder().chunks_written(), report->chunks);
  EXPECT_EQ(b.port->responder().installed_image(), image.bytes);
}

TEST(FirmwareUpdate, ALostVerifyAckIsRecoveredFromTheBoardsState) {
  SimBoard b;
  bool lost = false;
  b.port->lose_answers_when([&](const Message& m) {
    const auto* ack = m.get<protocol::Ack>();
    if (lost || ack == nullptr || ack->request_type != protocol::MessageType::kUpdateVerify) return false;
    return lost = true;
  });
  auto report = update_firmware(b.board, image_of(TestImageSpec{}), UpdateOptions{});
  ASSERT_TRUE(report) << report.error().what();
  EXPECT_EQ(report->resent, 1u);
  EXPECT_EQ(report->running_version, 0x01020003u);
}

TEST(FirmwareUpdate, ARefusedImageIsAbortedAndTheErrorSaysWhy) {
  SimBoard b;
  TestImageSpec wrong_slot;
  wrong_slot.load_address = 0x08040000;  // this board runs images at 0
  auto r = update_firmware(b.board, image_of(wrong_slot), UpdateOptions{});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kBoardRefused);
  EXPECT_EQ(r.error().what(), "sim:1: update_verify: board refused: image_rejected");
  EXPECT_EQ(b.port->responder().update_state(), protocol::UpdateState::kIdle) << "UpdateAbort after the refusal";
  EXPECT_EQ(b.port->responder().identity().fw_version, 0x01000000u);
}

TEST(FirmwareUpdate, CancellingAbortsBetweenChunks) {
  SimBoard b;
  CancelFlag cancel{false};
  UpdateOptions options;
  options.cancel = &cancel;
  options.progress = [&](const FlashProgress& p) {
    if (std::string(p.stage) == "write" && p.done >= 768) cancel = true;
  };
  auto r = update_firmware(b.board, image_of(TestImageSpec{}), options);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kCancelled);
  EXPECT_EQ(b.port->responder().chunks_written(), 3u);
  EXPECT_EQ(b.port->responder().update_state(), protocol::UpdateState::kIdle);
}

TEST(FirmwareUpdate, ChunkSizesFromOneByteToTheMaximumGiveTheSameImage) {
  for (size_t chunk : {1u, 7u, 100u, 255u, 256u}) {
    SimBoard b;
    TestImageSpec spec;
    spec.payload_size = 600;
    UpdateOptions options;
    options.chunk_size = chunk;
    const FirmwareImage image = image_of(spec);
    ASSERT_TRUE(update_firmware(b.board, image, options)) << chunk;
    EXPECT_EQ(b.port->responder().installed_image(), image.bytes) << chunk;
  }
  SimBoard b;
  UpdateOptions too_big;
  too_big.chunk_size = 257;
  EXPECT_EQ(update_firmware(b.board, image_of(TestImageSpec{}), too_big).error().kind, HostErrorKind::kBadInput);
}

protocol::Info stm32_board(uint8_t revision, uint8_t active_slot) {
  protocol::Info info;
  info.hw_model = HwModel::kStm32f405Reference;
  info.hw_revision = revision;
  info.active_slot = active_slot;
  return info;
}

TEST(ChooseImage, TakesTheImageLinkedForTheSlotThatIsNotRunning) {
  TestImageSpec spec;
  spec.hw_model = HwModel::kStm32f405Reference;
  spec.vector_offset = 0x200;
  spec.load_address = 0x08020000;
  const FirmwareImage slot0 = image_of(spec, "fw-slot0.bin");
  spec.load_address = 0x08040000;
  const FirmwareImage slot1 = image_of(spec, "fw-slot1.bin");
  const std::vector<FirmwareImage> release{slot0, slot1};
  auto for_slot0_runner = choose_image(release, stm32_board(1, 0), "usb:A");
  ASSERT_TRUE(for_slot0_runner);
  EXPECT_EQ((*for_slot0_runner)->name, "fw-slot1.bin");
  auto for_slot1_runner = choose_image(release, stm32_board(1, 1), "usb:A");
  ASSERT_TRUE(for_slot1_runner);
  EXPECT_EQ((*for_slot1_runner)->name, "fw-slot0.bin");
  const std::vector<FirmwareImage> just_slot0{slot0};
  auto only_slot0 = choose_image(just_slot0, stm32_board(1, 0), "usb:A");
  ASSERT_FALSE(only_slot0);
  EXPECT_EQ(only_slot0.error().what(),
            "usb:A: no image fits: fw-slot0.bin: linked for 0x08020000, the board runs slot 0 and takes an image for "
            "slot 1 at 0x08040000");
}

TEST(ChooseImage, RefusesOtherModelsAndRevisions) {
  TestImageSpec spec;
  spec.hw_model = HwModel::kStm32f405Reference;
  spec.hw_revision_min = 2;
  spec.hw_revision_max = 3;
  spec.load_address = 0x08040000;
  const FirmwareImage rev2 = image_of(spec, "rev2.bin");
  const FirmwareImage linux_image = image_of(TestImageSpec{}, "linux.bin");
  const std::vector<FirmwareImage> images{rev2, linux_image};
  auto r = choose_image(images, stm32_board(1, 0), "can:can0:4");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, HostErrorKind::kImageRejected);
  EXPECT_EQ(r.error().what(),
            "can:can0:4: no image fits: rev2.bin: built for stm32f405 rev 2..3, the board is stm32f405 rev 1; "
            "linux.bin: built for linux rev 0..255, the board is stm32f405 rev 1");
}

TEST(FirmwareImageFile, BrokenFilesAreRefusedWithTheirName) {
  std::vector<uint8_t> bytes = testing::make_test_image(TestImageSpec{});
  auto cut = check_firmware_image(std::vector<uint8_t>(bytes.begin(), bytes.end() - 1), "cut.bin");
  ASSERT_FALSE(cut);
  EXPECT_EQ(cut.error().what(), "cut.bin: header says 3128 bytes, the file has 3127");
  bytes.back() ^= 0x40;
  auto flipped = check_firmware_image(bytes, "flipped.bin");
  ASSERT_FALSE(flipped);
  EXPECT_EQ(flipped.error().kind, HostErrorKind::kBadFile);
  EXPECT_EQ(flipped.error().protocol_error, protocol::Error::kBadCrc);
  auto text = check_firmware_image(std::vector<uint8_t>(100, 'x'), "notes.txt");
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().what(), "notes.txt: not a tetrapulse firmware image: header bad_value");
  auto missing = read_firmware_image("/nonexistent/fw.bin");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().what(), "/nonexistent/fw.bin: cannot read the file");
}

}  // namespace
}  // namespace tetrapulse::host

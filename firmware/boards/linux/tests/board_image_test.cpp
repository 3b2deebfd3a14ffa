#include "tetrapulse/linux_board/board_image.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "tetrapulse/fw/boot/boot_slot.hpp"
#include "tetrapulse/fw/boot/boot_state.hpp"
#include "tetrapulse/fw/boot/image_bundle_writer.hpp"
#include "tetrapulse/fw/boot/update_slot.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/linux_board/ffs_function.hpp"
#include "tetrapulse/linux_board/file_flash.hpp"
#include "tetrapulse/linux_board/linux_system.hpp"
#include "tetrapulse/protocol/image_header.hpp"
#include "tetrapulse/protocol/version.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace fs = std::filesystem;
namespace tp = protocol;
using tp::DfuStatusCode;

const fw::BoardModel kModel{tp::HwModel::kLinuxBoard, LinuxSystem::kHwRevision};

TEST(LinuxImage, HeaderFitsTheLinuxBoardAndEitherSlot) {
  const std::vector<uint8_t> image = make_linux_image(tp::pack_version(2, 1, 7), seeded_payload(5000, 3));
  const tp::ByteView bytes{image.data(), image.size()};
  const tp::Result<tp::ImageHeader> h = tp::decode_image_header(bytes);
  ASSERT_TRUE(h);
  EXPECT_TRUE(tp::fits(*h, tp::HwModel::kLinuxBoard, LinuxSystem::kHwRevision));
  EXPECT_FALSE(tp::fits(*h, tp::HwModel::kStm32f405Reference, 1));
  EXPECT_TRUE(tp::check_payload(*h, bytes));
  for (const fw::SlotLayout& slot : linux_flash_layout().slots) EXPECT_EQ(h->load_address, slot.load_address);
  EXPECT_TRUE(make_linux_image(1, {}).empty());
}

TEST(LinuxImage, VersionAndSerialTexts) {
  EXPECT_EQ(parse_version("1.2.3"), tp::pack_version(1, 2, 3));
  EXPECT_EQ(parse_version("255.255.65535"), tp::pack_version(255, 255, 65535));
  for (const char* bad : {"", "1.2", "1.2.3.4", "1.2.x", "256.0.0", "1.2.65536", "1.2.3 "}) {
    EXPECT_FALSE(parse_version(bad)) << bad;
  }
  const BoardSerial s = {0x00, 0x01, 0xAB, 0xCD, 0xEF, 0x10, 0x20, 0x30, 0x40, 0x50, 0x60, 0xFF};
  EXPECT_EQ(serial_text(s), "0001ABCDEF102030405060FF");
  EXPECT_EQ(parse_serial("0001abcdef102030405060ff"), s);
  EXPECT_FALSE(parse_serial("0001ABCDEF102030405060F"));
  EXPECT_FALSE(parse_serial("0001ABCDEF102030405060FG"));
}

// The high-speed copy differs from the protocol's full-speed descriptors only in the
// bulk endpoints' packet size.
TEST(LinuxUsb, FunctionFsBlobsCarryTheProtocolDescriptors) {
  tp::UsbDeviceParams p;
  p.bulk_in_address = 0x82;
  uint8_t built[tp::kUsbMaxConfigurationSize];
  const tp::Result<size_t> n = tp::build_usb_function_descriptors(p, built, sizeof(built));
  ASSERT_TRUE(n);
  const FfsBlobs blobs = ffs_blobs(p, "SERIAL");
  ASSERT_EQ(blobs.descriptors.size(), 20 + 2 * *n);
  EXPECT_EQ(blobs.descriptors[4] | (blobs.descriptors[5] << 8), static_cast<int>(blobs.descriptors.size()));
  EXPECT_EQ(blobs.descriptors[12], 5);  // per speed: interface, 2 endpoints, interface, DFU functional
  const uint8_t* full = blobs.descriptors.data() + 20;
  const uint8_t* high = full + *n;
  EXPECT_TRUE(std::equal(full, full + *n, built));
  int endpoints = 0;
  for (size_t at = 0; at < *n; at += high[at]) {
    if (high[at + 1] == tp::kUsbDescriptorEndpoint) {
      ++endpoints;
      EXPECT_EQ(high[at + 4] | (high[at + 5] << 8), 512);
    } else {
      EXPECT_TRUE(std::equal(high + at, high + at + high[at], built + at));
    }
  }
  EXPECT_EQ(endpoints, 2);
}

class LinuxUpdateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (fs::temp_directory_path() / ("linux_board_update_" + std::to_string(::getpid()) + "_" +
                                          ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".bin"))
                .string();
    BoardResult<std::unique_ptr<FileFlash>> opened = FileFlash::open(path_, linux_flash_sectors());
    ASSERT_TRUE(opened) << opened.error().what();
    flash_ = std::move(*opened);
    const std::vector<uint8_t> factory = make_linux_image(tp::pack_version(1, 0, 0), seeded_payload(3000, 1));
    ASSERT_TRUE(flash_->load(layout_.slots[0].region.address, tp::ByteView{factory.data(), factory.size()}));
    store_.emplace(*flash_, layout_.record_sectors);
    ASSERT_TRUE(store_->open());
    fw::BootState state;
    state.confirmed_slot = 0;
    ASSERT_TRUE(fw::save_boot_state(*store_, state));
  }
  void TearDown() override { fs::remove(path_); }

  // What the DFU bootloader does with one downloaded file, in 1024-byte blocks.
  DfuStatusCode download(const std::vector<uint8_t>& file) {
    fw::ImageBundleWriter writer(*flash_, layout_, *store_, kModel, 1, 0);
    for (size_t at = 0; at < file.size(); at += 1024) {
      const size_t n = std::min<size_t>(1024, file.size() - at);
      const DfuStatusCode s = writer.download(static_cast<uint32_t>(at), tp::ByteView{file.data() + at, n});
      if (s != DfuStatusCode::kOk) return s;
    }
    return writer.manifest(static_cast<uint32_t>(file.size()));
  }
  uint32_t booted_version() {
    const fw::BootChoice c = fw::choose_boot_slot(*flash_, layout_, kModel, false);
    return c.boot ? c.header.fw_version : 0;
  }

  std::string path_;
  fw::FlashLayout layout_ = linux_flash_layout();
  std::unique_ptr<FileFlash> flash_;
  std::optional<fw::RecordStore> store_;
};

TEST_F(LinuxUpdateTest, AnInstalledImageBootsAndACorruptedOneIsRefused) {
  std::vector<uint8_t> corrupted = make_linux_image(tp::pack_version(1, 1, 0), seeded_payload(20000, 2));
  corrupted[5000] ^= 0x40;
  EXPECT_EQ(download(corrupted), DfuStatusCode::kErrVerify);
  EXPECT_EQ(booted_version(), tp::pack_version(1, 0, 0));

  // A valid image for another board model.
  std::vector<uint8_t> other_board = make_linux_image(tp::pack_version(1, 1, 0), seeded_payload(2000, 2));
  tp::ImageHeader h = *tp::decode_image_header(tp::ByteView{other_board.data(), other_board.size()});
  h.hw_model = tp::HwModel::kStm32f405Reference;
  tp::ByteWriter w(other_board.data(), tp::kImageHeaderSize);
  ASSERT_TRUE(tp::encode_image_header(h, w));
  EXPECT_EQ(download(other_board), DfuStatusCode::kErrTarget);
  EXPECT_EQ(booted_version(), tp::pack_version(1, 0, 0));

  const std::vector<uint8_t> good = make_linux_image(tp::pack_version(1, 1, 0), seeded_payload(20000, 2));
  EXPECT_EQ(download(good), DfuStatusCode::kOk);
  EXPECT_EQ(booted_version(), tp::pack_version(1, 1, 0));
}

}  // namespace
}  // namespace tetrapulse::linux_board

// The real bootloader's image checks and slot choice under QEMU (netduinoplus2): an image
// whose payload fails its CRC-32C is never started, and the board falls back on the image
// in the other slot. The application answering GetInfo over USART1 says what was started.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "qemu_board.hpp"

namespace tetrapulse::stm32f405::testing {
namespace {

namespace tp = protocol;

// A copy of `image` with its last byte (payload, covered by the header's CRC-32C) flipped.
std::string corrupted_copy(const std::string& image) {
  std::ifstream in(image, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) return "";
  bytes.back() = static_cast<char>(bytes.back() ^ 0x5A);
  const std::string path = ::testing::TempDir() + "tetrapulse_corrupt_slot_" + std::to_string(getpid()) + ".img";
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return out ? path : "";
}

// GetInfo until the application answers, for up to `attempts` x 200 ms.
std::optional<tp::Info> info_of(QemuBoard& board, int attempts) {
  for (int i = 0; i < attempts; ++i) {
    const std::optional<tp::Message> reply = board.request(request_message(1, tp::GetInfo{}), 200);
    if (reply && reply->get<tp::Info>() != nullptr) return *reply->get<tp::Info>();
  }
  return std::nullopt;
}

class QemuBoot : public ::testing::Test {
 protected:
  void SetUp() override {
    bootloader_ = artefact("TETRAPULSE_BOOTLOADER_ELF");
    slot1_ = artefact("TETRAPULSE_SLOT1_IMAGE");
    corrupt_slot0_ = corrupted_copy(artefact("TETRAPULSE_SLOT0_IMAGE"));
    ASSERT_FALSE(bootloader_.empty() || slot1_.empty()) << "CTest sets the firmware paths";
    ASSERT_FALSE(corrupt_slot0_.empty()) << "could not copy the slot 0 image";
  }
  void TearDown() override {
    if (!corrupt_slot0_.empty()) std::remove(corrupt_slot0_.c_str());
  }
  std::string bootloader_;
  std::string slot1_;
  std::string corrupt_slot0_;
};

TEST_F(QemuBoot, FallsBackOnTheOtherSlotWhenAnImageFailsItsCrc) {
  QemuBoard board(bootloader_, corrupt_slot0_, slot1_);
  ASSERT_TRUE(board.running()) << "qemu-system-arm did not start";
  const std::optional<tp::Info> info = info_of(board, 50);
  ASSERT_TRUE(info.has_value()) << "no application answered within 10 s";
  EXPECT_EQ(info->active_slot, 1) << "the bootloader must start the valid image in slot 1";
  EXPECT_EQ(info->bootloader_version, TETRAPULSE_FW_VERSION) << "started through the bootloader";
}

TEST_F(QemuBoot, StartsNoImageThatFailsItsCrc) {
  QemuBoard board(bootloader_, corrupt_slot0_);
  ASSERT_TRUE(board.running()) << "qemu-system-arm did not start";
  // The good image answers within a second of boot (the test above, qemu_uart); the
  // bootloader itself never speaks on USART1: it stays waiting for an update.
  EXPECT_FALSE(info_of(board, 15).has_value()) << "an image with a broken CRC was started";
}

}  // namespace
}  // namespace tetrapulse::stm32f405::testing

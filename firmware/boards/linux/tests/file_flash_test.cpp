#include "tetrapulse/linux_board/file_flash.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tetrapulse/fw/storage/config_store.hpp"
#include "tetrapulse/fw/storage/record_store.hpp"

namespace tetrapulse::linux_board {
namespace {

namespace fs = std::filesystem;

class FileFlashTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("linux_board_flash_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    path_ = (dir_ / "flash.bin").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<FileFlash> open(bool* created = nullptr) {
    BoardResult<std::unique_ptr<FileFlash>> flash = FileFlash::open(path_, linux_flash_sectors());
    EXPECT_TRUE(flash) << flash.error().what();
    if (!flash) return nullptr;
    if (created != nullptr) *created = (*flash)->created();
    return std::move(*flash);
  }

  fs::path dir_;
  std::string path_;
};

TEST_F(FileFlashTest, NewFileReadsErasedAndKeepsWhatWasProgrammed) {
  bool created = false;
  {
    auto flash = open(&created);
    ASSERT_TRUE(flash);
    EXPECT_TRUE(created);
    uint8_t b[4] = {};
    ASSERT_TRUE(flash->read(0x50000, b, sizeof(b)));
    for (uint8_t x : b) EXPECT_EQ(x, 0xFF);
    const uint8_t data[4] = {0x12, 0x34, 0x56, 0x78};
    ASSERT_TRUE(flash->program(0x50000, protocol::ByteView{data, 4}));
  }
  auto again = open(&created);
  ASSERT_TRUE(again);
  EXPECT_FALSE(created);
  uint8_t b[4] = {};
  ASSERT_TRUE(again->read(0x50000, b, sizeof(b)));
  EXPECT_EQ(b[0], 0x12);
  EXPECT_EQ(b[3], 0x78);
}

TEST_F(FileFlashTest, ProgrammingOnlyClearsBitsAndEraseIsPerSector) {
  auto flash = open();
  ASSERT_TRUE(flash);
  const uint8_t first = 0xF0;
  const uint8_t clears = 0x30;
  const uint8_t sets = 0x0F;
  ASSERT_TRUE(flash->program(0x1008, protocol::ByteView{&first, 1}));
  EXPECT_TRUE(flash->program(0x1008, protocol::ByteView{&clears, 1}));
  EXPECT_EQ(flash->program(0x1008, protocol::ByteView{&sets, 1}).error(), protocol::Error::kFlashError);
  EXPECT_EQ(flash->erase_sector(0x1008).error(), protocol::Error::kBadValue);  // not a sector start
  ASSERT_TRUE(flash->erase_sector(0x1000));
  uint8_t b = 0;
  ASSERT_TRUE(flash->read(0x1008, &b, 1));
  EXPECT_EQ(b, 0xFF);
  EXPECT_EQ(flash->read(0x90000 - 1, &b, 2).error(), protocol::Error::kBadValue);
  EXPECT_EQ(flash->program(0x90000, protocol::ByteView{&b, 1}).error(), protocol::Error::kBadValue);
}

TEST_F(FileFlashTest, RefusesAFileOfAnotherSize) {
  { std::FILE* f = std::fopen(path_.c_str(), "wb"); std::fputs("short", f); std::fclose(f); }
  const BoardResult<std::unique_ptr<FileFlash>> flash = FileFlash::open(path_, linux_flash_sectors());
  ASSERT_FALSE(flash);
  EXPECT_EQ(flash.error().kind, BoardErrorKind::kFlash);
  const std::string error = flash.error().what();
  EXPECT_NE(error.find("not the board's"), std::string::npos) << error;
}

// The daemon killed (or the computer losing power) after any number of bytes reached the
// file while a configuration is being stored: the next start finds the old or the new one.
TEST_F(FileFlashTest, ConfigurationSurvivesACutAfterEveryByte) {
  const fw::FlashLayout layout = linux_flash_layout();
  protocol::Config old_config = protocol::default_config();
  old_config.node_id = 7;
  protocol::Config new_config = old_config;
  new_config.node_id = 9;
  {
    auto flash = open();
    fw::RecordStore store(*flash, layout.record_sectors);
    ASSERT_TRUE(store.open());
    ASSERT_TRUE(fw::save_config(store, old_config));
  }
  const std::string pristine = path_ + ".pristine";
  fs::copy_file(path_, pristine);
  int old_seen = 0;
  int new_seen = 0;
  for (uint64_t cut = 0;; ++cut) {
    fs::copy_file(pristine, path_, fs::copy_options::overwrite_existing);
    bool completed = false;
    {
      auto flash = open();
      fw::RecordStore store(*flash, layout.record_sectors);
      ASSERT_TRUE(store.open());
      flash->cut_power_after(cut);
      completed = fw::save_config(store, new_config).ok();
    }
    auto flash = open();
    fw::RecordStore store(*flash, layout.record_sectors);
    ASSERT_TRUE(store.open()) << "cut after " << cut << " bytes";
    const fw::StoredConfig stored = fw::load_config(store);
    ASSERT_TRUE(stored.from_flash) << "cut after " << cut << " bytes";
    if (stored.config.node_id == 7) {
      ++old_seen;
    } else {
      ASSERT_EQ(stored.config.node_id, 9) << "cut after " << cut << " bytes";
      ++new_seen;
    }
    // The store still takes a write after the cut.
    ASSERT_TRUE(fw::save_config(store, old_config)) << "cut after " << cut << " bytes";
    if (completed) {
      EXPECT_EQ(stored.config.node_id, 9);
      break;
    }
    ASSERT_LT(cut, 10'000u) << "the store never completed a write";
  }
  EXPECT_GT(old_seen, 0);
  EXPECT_GT(new_seen, 0);
  std::printf("[measure] configuration write cut after each of %d byte positions: old %d, new %d\n",
              old_seen + new_seen, old_seen, new_seen);
}

}  // namespace
}  // namespace tetrapulse::linux_board

// The golden-vector reader: records, names, comments, and errors that name the place.
#include "hex_vectors.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace tetrapulse::protocol::testing {
namespace {

class HexFileTest : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    std::ofstream(path_) << text;
    return path_;
  }
  void TearDown() override { std::remove(path_.c_str()); }
  std::string path_ = ::testing::TempDir() + "/sample.hex";
};

TEST_F(HexFileTest, UnnamedRecordTakesTheFileName) {
  const auto f = read_hex_file(write("# one message\n01 05 07  # header\n0288 13\n"));
  ASSERT_TRUE(f) << f.error();
  ASSERT_EQ(f->records.size(), 1u);
  EXPECT_EQ(f->records[0].name, "sample");
  EXPECT_EQ(f->records[0].description, "one message");
  EXPECT_EQ(f->records[0].bytes, (std::vector<uint8_t>{1, 5, 7, 2, 0x88, 0x13}));
}

TEST_F(HexFileTest, NamedRecordsKeepTheirOwnBytesAndComments) {
  const auto f = read_hex_file(write("# file comment\n\n[a]\n# first\nAA bb\n[b]\n# second\n# more\ncc\n[empty]\n"));
  ASSERT_TRUE(f) << f.error();
  ASSERT_EQ(f->records.size(), 3u);
  EXPECT_EQ(f->find("a")->bytes, (std::vector<uint8_t>{0xAA, 0xBB}));
  EXPECT_EQ(f->find("a")->description, "first");
  EXPECT_EQ(f->find("b")->description, "second\nmore");
  EXPECT_TRUE(f->find("empty")->bytes.empty());
  EXPECT_EQ(f->find("b")->origin, path_ + ":6");
}

TEST_F(HexFileTest, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(read_hex_file(write("01\n0g\n")).error(), path_ + ":2: '0g' is not hex");
  EXPECT_EQ(read_hex_file(write("012\n")).error(), path_ + ":1: '012' has an odd number of hex digits");
  EXPECT_EQ(read_hex_file(write("[a]\n[a]\n")).error(), path_ + ":2: record [a] repeated");
  EXPECT_EQ(read_hex_file(write("[a\n")).error(), path_ + ":1: a record name is written [name]");
  EXPECT_EQ(read_hex_file(path_ + ".missing").error(), path_ + ".missing: cannot open");
}

TEST(HexFolder, ReadsTheMessageVectorsSortedByName) {
  const auto files = read_hex_folder(vectors_dir() + "/messages");
  ASSERT_TRUE(files) << files.error();
  ASSERT_GE(files->size(), 2u);
  for (size_t i = 1; i < files->size(); ++i) EXPECT_LT((*files)[i - 1].stem, (*files)[i].stem);
}

}  // namespace
}  // namespace tetrapulse::protocol::testing

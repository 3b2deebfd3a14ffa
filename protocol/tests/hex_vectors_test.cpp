// The golden-vector reader: records, names, comments, attributes, and errors that name the place.
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
  ASSERT_NE(f->find("empty"), nullptr);
  EXPECT_TRUE(f->find("empty")->bytes.empty());
  EXPECT_EQ(f->find("b")->origin, path_ + ":6");
}

TEST_F(HexFileTest, AttributesBelongToTheirRecordAndReadAsNumbers) {
  const auto f = read_hex_file(write("# a transfer\n[message] priority=4 01 04 07\n[frame.0] id=0x1004FF00\n01 04 07 E0\n"
                                     "[frame.1] id=268500736 error=bad_crc\n[other]\n"));
  ASSERT_TRUE(f) << f.error();
  EXPECT_EQ(f->description, "a transfer");
  ASSERT_EQ(f->records.size(), 4u);
  const HexRecord& message = *f->find("message");
  EXPECT_EQ(message.bytes, (std::vector<uint8_t>{1, 4, 7}));
  EXPECT_EQ(message.number("priority").value(), 4u);
  const auto frames = f->starting_with("frame.");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0]->number("id").value(), 0x1004FF00u);
  EXPECT_EQ(frames[0]->bytes, (std::vector<uint8_t>{1, 4, 7, 0xE0}));
  EXPECT_EQ(frames[1]->number("id").value(), 268500736u);
  EXPECT_TRUE(frames[1]->bytes.empty());
  ASSERT_NE(frames[1]->attribute("error"), nullptr);
  EXPECT_EQ(*frames[1]->attribute("error"), "bad_crc");
  EXPECT_EQ(frames[1]->number("error").error(), path_ + ":5: [frame.1] error=bad_crc is not a 64-bit number");
  EXPECT_EQ(message.number("id").error(), path_ + ":2: [message] has no id=");
  EXPECT_EQ(f->find("other")->attribute("id"), nullptr);
}

// An empty first record is a record, not a file comment (a malformed vector may be empty).
TEST_F(HexFileTest, AnEmptyNamedRecordFirstIsKept) {
  const auto f = read_hex_file(write("# file\n[none]\n# no bytes\n[one]\n01\n"));
  ASSERT_TRUE(f) << f.error();
  ASSERT_EQ(f->records.size(), 2u);
  EXPECT_EQ(f->records[0].name, "none");
  EXPECT_EQ(f->records[0].description, "no bytes");
  EXPECT_EQ(f->description, "file");
}

TEST_F(HexFileTest, AttributesBeforeAnyNameBelongToTheFileRecord) {
  const auto f = read_hex_file(write("error=truncated\n01\n[next]\n02\n"));
  ASSERT_TRUE(f) << f.error();
  ASSERT_EQ(f->records.size(), 2u);
  EXPECT_EQ(*f->find("sample")->attribute("error"), "truncated");
}

TEST_F(HexFileTest, NumbersOutOf64BitsAreRefused) {
  const auto f = read_hex_file(write("a=18446744073709551615 b=18446744073709551616 c=0xFFFFFFFFFFFFFFFF d=0x1FFFFFFFFFFFFFFFF\n"));
  ASSERT_TRUE(f) << f.error();
  const HexRecord& r = f->records[0];
  EXPECT_EQ(r.number("a").value(), UINT64_MAX);
  EXPECT_FALSE(r.number("b").has_value());
  EXPECT_EQ(r.number("c").value(), UINT64_MAX);
  EXPECT_FALSE(r.number("d").has_value());
}

TEST_F(HexFileTest, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(read_hex_file(write("01\n0g\n")).error(), path_ + ":2: '0g' is not hex");
  EXPECT_EQ(read_hex_file(write("012\n")).error(), path_ + ":1: '012' has an odd number of hex digits");
  EXPECT_EQ(read_hex_file(write("[a]\n[a]\n")).error(), path_ + ":2: record [a] repeated");
  EXPECT_EQ(read_hex_file(write("[a\n")).error(), path_ + ":1: a record name is written [name]");
  EXPECT_EQ(read_hex_file(write("[a] id=1 id=2\n")).error(), path_ + ":1: attribute id repeated");
  EXPECT_EQ(read_hex_file(write("[a]\nid=\n")).error(), path_ + ":2: 'id=' is not key=value");
  EXPECT_EQ(read_hex_file(write("[a]\nId=1\n")).error(), path_ + ":2: 'Id=1' is not key=value");
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

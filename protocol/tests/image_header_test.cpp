// Firmware image headers: golden vectors, every malformed vector, every truncation and bit
// flip, random round trips, and the checks a board makes before it accepts an image.
#include "tetrapulse/protocol/image_header.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <sstream>

#include "hex_vectors.hpp"
#include "message_testing.hpp"
#include "tetrapulse/protocol/version.hpp"
#include "vector_cases.hpp"

namespace tetrapulse::protocol::testing {
namespace {

std::string header_text(const ImageHeader& h) {
  std::ostringstream s;
  s << "model=" << static_cast<int>(h.hw_model) << " rev=" << int{h.hw_revision_min} << ".." << int{h.hw_revision_max}
    << " fw=" << h.fw_version << " payload_size=" << h.payload_size << " vector_offset=" << h.vector_offset
    << " load_address=" << h.load_address << " payload_crc32c=" << h.payload_crc32c << " flags=" << h.flags;
  return s.str();
}

std::vector<uint8_t> encode_header(const ImageHeader& h, Error* error) {
  std::vector<uint8_t> bytes(kImageHeaderSize);
  ByteWriter out(bytes.data(), bytes.size());
  *error = encode_image_header(h, out).error();
  bytes.resize(out.size());
  return bytes;
}

ImageHeader stm32f405_example() {
  ImageHeader h;
  h.hw_model = HwModel::kStm32f405Reference;
  h.hw_revision_min = 1;
  h.hw_revision_max = 3;
  h.fw_version = pack_version(1, 2, 3);
  h.payload_size = 0x1F000;
  h.vector_offset = 0x200;
  h.load_address = 0x08020000;
  h.payload_crc32c = 0x12345678;
  return h;
}

HexRecord header_vector(const std::string& name) {
  const auto file = read_hex_file(vectors_dir() + "/image/header.hex");
  EXPECT_TRUE(file) << (file ? "" : file.error());
  const HexRecord* r = file ? file->find(name) : nullptr;
  EXPECT_NE(r, nullptr) << name;
  return r != nullptr ? *r : HexRecord{};
}

TEST(ImageHeader, GoldenHeaderDecodesToItsFieldsAndReencodes) {
  const HexRecord r = header_vector("stm32f405");
  ASSERT_EQ(r.bytes.size(), kImageHeaderSize);
  const auto h = decode_image_header(view(r.bytes));
  ASSERT_TRUE(h.ok()) << error_name(h.error());
  EXPECT_EQ(header_text(*h), header_text(stm32f405_example()));
  Error error = Error::kNone;
  EXPECT_EQ(to_hex(encode_header(stm32f405_example(), &error)), to_hex(r.bytes));
  EXPECT_EQ(error, Error::kNone);
}

TEST(ImageHeader, GoldenTinyImageIsAcceptedByTheBoardItWasBuiltFor) {
  const HexRecord r = header_vector("tiny_image");
  const auto h = decode_image_header(view(r.bytes));
  ASSERT_TRUE(h.ok()) << error_name(h.error());
  EXPECT_EQ(image_size(*h), r.bytes.size());
  EXPECT_TRUE(fits(*h, HwModel::kSimulatedBoard, 0).ok());
  EXPECT_TRUE(check_payload(*h, view(r.bytes)).ok());
  EXPECT_EQ(fits(*h, HwModel::kStm32f405Reference, 0).error(), Error::kImageRejected);
  EXPECT_EQ(fits(*h, HwModel::kSimulatedBoard, 1).error(), Error::kImageRejected);

  // Any changed payload byte, or a missing or extra byte, is refused.
  for (size_t i = h->vector_offset; i < r.bytes.size(); ++i) {
    auto bytes = r.bytes;
    bytes[i] ^= 0x40;
    EXPECT_EQ(check_payload(*h, view(bytes)).error(), Error::kImageRejected) << i;
  }
  auto longer = r.bytes;
  longer.push_back(0);
  EXPECT_EQ(check_payload(*h, view(longer)).error(), Error::kImageRejected);
  EXPECT_EQ(check_payload(*h, ByteView{r.bytes.data(), r.bytes.size() - 1}).error(), Error::kImageRejected);
}

TEST(ImageHeader, FitsOnlyTheModelAndRevisionRange) {
  const ImageHeader h = stm32f405_example();  // revisions 1..3
  for (int rev = 0; rev < 256; ++rev) {
    EXPECT_EQ(fits(h, HwModel::kStm32f405Reference, static_cast<uint8_t>(rev)).ok(), rev >= 1 && rev <= 3) << rev;
  }
  EXPECT_EQ(fits(h, HwModel::kLinuxBoard, 2).error(), Error::kImageRejected);
}

TEST(ImageHeader, EveryTruncationIsTruncated) {
  const HexRecord r = header_vector("stm32f405");
  for (size_t n = 0; n < kImageHeaderSize; ++n) {
    EXPECT_EQ(decode_image_header(ByteView{r.bytes.data(), n}).error(), Error::kTruncated) << n;
  }
}

// CRC-32C detects every single-bit error, so no flipped header is ever accepted.
TEST(ImageHeader, EverySingleBitFlipIsRefused) {
  const HexRecord r = header_vector("stm32f405");
  for (size_t bit = 0; bit < kImageHeaderSize * 8; ++bit) {
    auto bytes = r.bytes;
    bytes[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    EXPECT_FALSE(decode_image_header(view(bytes)).ok()) << "bit " << bit;
  }
}

TEST(ImageHeader, RandomValidHeadersRoundTrip) {
  EXPECT_TRUE(rc::check("image header round trip", [](uint8_t rev_a, uint8_t rev_b, uint32_t fw, uint32_t crc) {
    ImageHeader h;
    h.hw_model = *rc::gen::element(HwModel::kStm32f405Reference, HwModel::kLinuxBoard, HwModel::kSimulatedBoard);
    h.hw_revision_min = std::min(rev_a, rev_b);
    h.hw_revision_max = std::max(rev_a, rev_b);
    h.fw_version = fw;
    h.vector_offset = *rc::gen::inRange<uint32_t>(1, 1024) * kMinVectorAlignment;
    h.payload_size = *rc::gen::inRange<uint32_t>(1, UINT32_MAX - h.vector_offset + 1);
    h.load_address = *rc::gen::inRange<uint32_t>(0, UINT32_MAX / kMinVectorAlignment) * kMinVectorAlignment;
    h.payload_crc32c = crc;
    Error error = Error::kNone;
    const auto bytes = encode_header(h, &error);
    RC_ASSERT(error == Error::kNone);
    const auto decoded = decode_image_header(view(bytes));
    RC_ASSERT(decoded.ok());
    RC_ASSERT(header_text(*decoded) == header_text(h));
  }));
}

TEST(ImageHeader, EncodeRefusesWhatDecodeRefuses) {
  ImageHeader bad = stm32f405_example();
  bad.flags = 1;
  Error error = Error::kNone;
  EXPECT_TRUE(encode_header(bad, &error).empty());
  EXPECT_EQ(error, Error::kBadValue);
  bad = stm32f405_example();
  bad.payload_size = UINT32_MAX;
  EXPECT_EQ(validate(bad).error(), Error::kBadLength);
}

class MalformedImageHeader : public ::testing::TestWithParam<VectorCase> {};

TEST_P(MalformedImageHeader, FailsWithTheNamedError) {
  const VectorCase& c = GetParam();
  ASSERT_EQ(c.load_error, "");
  const Error expected = expected_error(c.record);
  ASSERT_NE(expected, Error::kNone) << c.record.origin;
  EXPECT_EQ(decode_image_header(view(c.record.bytes)).error(), expected)
      << c.record.origin << " (" << c.record.description << ")";
}

INSTANTIATE_TEST_SUITE_P(Vectors, MalformedImageHeader, ::testing::ValuesIn(vector_cases("image/malformed")),
                         case_name);

}  // namespace
}  // namespace tetrapulse::protocol::testing

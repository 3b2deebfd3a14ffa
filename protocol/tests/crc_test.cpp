#include "tetrapulse/protocol/crc.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace tetrapulse::protocol {
namespace {

const uint8_t* check_string() { return reinterpret_cast<const uint8_t*>("123456789"); }

TEST(Crc32c, CatalogueCheckValue) { EXPECT_EQ(crc32c(check_string(), 9), 0xE3069283u); }

TEST(Crc32c, EmptyInputIsZero) { EXPECT_EQ(crc32c(nullptr, 0), 0u); }

TEST(Crc16Ccitt, CatalogueCheckValue) { EXPECT_EQ(crc16_ccitt(check_string(), 9), 0x29B1u); }

TEST(Crc16Ccitt, EmptyInputIsInit) { EXPECT_EQ(crc16_ccitt(nullptr, 0), 0xFFFFu); }

// Feeding the data in arbitrary pieces gives the same value as one call.
TEST(Crc, IncrementalEqualsOneShot) {
  std::mt19937 rng(7);
  std::vector<uint8_t> data(1000);
  for (auto& b : data) b = static_cast<uint8_t>(rng());
  for (int trial = 0; trial < 50; ++trial) {
    Crc32c a;
    Crc16Ccitt b;
    size_t pos = 0;
    while (pos < data.size()) {
      size_t n = std::min<size_t>(rng() % 64, data.size() - pos);
      a.update(data.data() + pos, n);
      b.update(data.data() + pos, n);
      pos += n;
    }
    EXPECT_EQ(a.value(), crc32c(data.data(), data.size()));
    EXPECT_EQ(b.value(), crc16_ccitt(data.data(), data.size()));
  }
}

// Any single-bit error is detected by both.
TEST(Crc, DetectsEverySingleBitFlip) {
  std::vector<uint8_t> data(64);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 37 + 11);
  const uint32_t c32 = crc32c(data.data(), data.size());
  const uint16_t c16 = crc16_ccitt(data.data(), data.size());
  int missed = 0;
  for (size_t bit = 0; bit < data.size() * 8; ++bit) {
    data[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
    missed += crc32c(data.data(), data.size()) == c32;
    missed += crc16_ccitt(data.data(), data.size()) == c16;
    data[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
  }
  EXPECT_EQ(missed, 0);
}

}  // namespace
}  // namespace tetrapulse::protocol

#include "tetrapulse/protocol/can_id.hpp"

#include <gtest/gtest.h>

namespace tetrapulse::protocol {
namespace {

TEST(CanId, PacksFieldsAtTheirBits) {
  const Result<uint32_t> raw = pack_can_id(CanId{kCanPriorityRequest, 0x04, kCanBroadcastNode, kCanHostNode});
  ASSERT_TRUE(raw.ok());
  EXPECT_EQ(*raw, 0x1004FF00u);
  EXPECT_EQ(*pack_can_id(CanId{7, 0xAB, 0x12, 0x34}), (7u << 26) | (0xABu << 16) | (0x12u << 8) | 0x34u);
  EXPECT_EQ(*pack_can_id(CanId{0, 0, 0, 0}), 0u);
}

TEST(CanId, RoundTripsEveryFieldValue) {
  for (uint32_t priority = 0; priority < 8; ++priority) {
    for (uint32_t v = 0; v < 256; ++v) {
      const CanId id{static_cast<uint8_t>(priority), static_cast<uint8_t>(v),
                     static_cast<uint8_t>(255 - v), static_cast<uint8_t>(v % 255)};
      const Result<uint32_t> raw = pack_can_id(id);
      ASSERT_TRUE(raw.ok());
      EXPECT_LE(*raw, kCanExtendedIdMask);
      EXPECT_EQ(*raw & kCanReservedBits, 0u);
      const Result<CanId> back = unpack_can_id(*raw);
      ASSERT_TRUE(back.ok());
      EXPECT_EQ(*back, id);
    }
  }
}

TEST(CanId, RejectsInvalidFields) {
  EXPECT_EQ(pack_can_id(CanId{8, 0, 0, 0}).error(), Error::kBadValue);
  EXPECT_EQ(pack_can_id(CanId{0, 0, 0, kCanBroadcastNode}).error(), Error::kBadValue);
  EXPECT_EQ(unpack_can_id(0x20000000u).error(), Error::kBadValue);   // over 29 bits
  EXPECT_EQ(unpack_can_id(0x01000000u).error(), Error::kBadValue);   // reserved bit 24
  EXPECT_EQ(unpack_can_id(0x02000000u).error(), Error::kBadValue);   // reserved bit 25
  EXPECT_EQ(unpack_can_id(0x1004FFFFu).error(), Error::kBadValue);   // source 255
}

TEST(CanNodeFilters, BoardAcceptsItsNodeAndBroadcastOnly) {
  for (uint32_t node = kCanFirstBoardNode; node <= kCanLastBoardNode; node += 37) {
    const CanNodeFilters f = can_node_filters(static_cast<uint8_t>(node));
    for (uint32_t dst = 0; dst < 256; ++dst) {
      const uint32_t raw = *pack_can_id(CanId{3, 0x40, static_cast<uint8_t>(dst), 9});
      const bool accepted = can_filter_matches(f.addressed, raw) || can_filter_matches(f.broadcast, raw);
      EXPECT_EQ(accepted, dst == node || dst == kCanBroadcastNode) << "node " << node << " dst " << dst;
      // A frame with a reserved bit set is never ours.
      EXPECT_FALSE(can_filter_matches(f.addressed, raw | 0x01000000u));
      EXPECT_FALSE(can_filter_matches(f.broadcast, raw | 0x02000000u));
    }
  }
}

TEST(CanNodeFilters, HostAcceptsFramesToNodeZeroAndBroadcast) {
  const CanNodeFilters f = can_node_filters(kCanHostNode);
  const auto accepts = [&](uint8_t dst) {
    const uint32_t raw = *pack_can_id(CanId{4, 0x05, dst, 3});
    return can_filter_matches(f.addressed, raw) || can_filter_matches(f.broadcast, raw);
  };
  EXPECT_TRUE(accepts(kCanHostNode));
  EXPECT_TRUE(accepts(kCanBroadcastNode));
  EXPECT_FALSE(accepts(3));
  EXPECT_FALSE(accepts(254));
}

}  // namespace
}  // namespace tetrapulse::protocol

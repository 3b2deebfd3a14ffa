// The record store on simulated flash: several keys, random write sequences, power cut at
// random steps (exhaustive cuts run in power_cut_test.cpp on the whole board).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <map>
#include <vector>

#include "tetrapulse/fw/storage/record_store.hpp"
#include "tetrapulse/sim_board/sim_flash.hpp"

namespace tetrapulse::fw {
namespace {

const std::array<FlashRegion, 2> kSectors = {FlashRegion{0x0, 0x800}, FlashRegion{0x800, 0x800}};

std::vector<uint8_t> payload_of(uint8_t key, uint32_t n) {
  std::vector<uint8_t> p(1 + (key * 7 + n) % RecordStore::kMaxPayload);
  for (size_t i = 0; i < p.size(); ++i) p[i] = static_cast<uint8_t>(n * 31 + i * 7 + key);
  return p;
}

std::optional<std::vector<uint8_t>> read_key(const RecordStore& s, uint8_t key) {
  uint8_t buf[RecordStore::kMaxPayload];
  const protocol::Result<size_t> n = s.read(key, buf, sizeof(buf));
  if (!n) return std::nullopt;
  return std::vector<uint8_t>(buf, buf + *n);
}

TEST(RecordStore, EmptyFlashHoldsNothingAndFirstWriteCreatesTheStore) {
  sim_board::SimFlash flash({kSectors[0], kSectors[1]});
  RecordStore s(flash, kSectors);
  ASSERT_TRUE(s.open().ok());
  EXPECT_FALSE(s.contains(1));
  EXPECT_EQ(s.read(1, nullptr, 0).error(), protocol::Error::kInvalidState);
  const std::vector<uint8_t> p = payload_of(1, 1);
  ASSERT_TRUE(s.write(1, protocol::ByteView{p.data(), p.size()}).ok());
  RecordStore reopened(flash, kSectors);
  ASSERT_TRUE(reopened.open().ok());
  EXPECT_EQ(read_key(reopened, 1), p);
  EXPECT_EQ(s.write(0, protocol::ByteView{p.data(), p.size()}).error(), protocol::Error::kBadValue);
  EXPECT_EQ(s.write(RecordStore::kMaxKeys + 1, protocol::ByteView{p.data(), p.size()}).error(), protocol::Error::kBadValue);
}

// Any sequence of writes to several keys, cut at any step: every key reads its last
// completed value or the value being written when the power went, and the store keeps
// working afterwards.
RC_GTEST_PROP(RecordStore, PowerCutLeavesEveryKeyOldOrNew, ()) {
  const auto writes = *rc::gen::container<std::vector<uint8_t>>(rc::gen::inRange<uint8_t>(1, 4));
  const uint64_t cut = *rc::gen::inRange<uint64_t>(0, 40'000);
  sim_board::SimFlash flash({kSectors[0], kSectors[1]});
  std::map<uint8_t, std::vector<uint8_t>> done;
  std::optional<std::pair<uint8_t, std::vector<uint8_t>>> in_flight;
  {
    RecordStore s(flash, kSectors);
    RC_ASSERT(s.open().ok());
    flash.cut_power_after(cut);
    for (size_t i = 0; i < writes.size(); ++i) {
      const std::vector<uint8_t> p = payload_of(writes[i], static_cast<uint32_t>(i));
      if (!s.write(writes[i], protocol::ByteView{p.data(), p.size()})) {
        in_flight = std::make_pair(writes[i], p);
        break;
      }
      done[writes[i]] = p;
    }
  }
  flash.restore_power();
  RecordStore s(flash, kSectors);
  RC_ASSERT(s.open().ok());
  for (uint8_t key = 1; key <= 4; ++key) {
    const auto got = read_key(s, key);
    const auto old = done.count(key) ? std::optional<std::vector<uint8_t>>(done[key]) : std::nullopt;
    const bool is_new = in_flight && in_flight->first == key && got == in_flight->second;
    RC_ASSERT(got == old || is_new);
  }
  const std::vector<uint8_t> p = payload_of(2, 999);
  RC_ASSERT(s.write(2, protocol::ByteView{p.data(), p.size()}).ok());
  RecordStore again(flash, kSectors);
  RC_ASSERT(again.open().ok());
  RC_ASSERT(read_key(again, 2) == p);
}

TEST(RecordStore, FlashErrorKeepsTheOldValue) {
  sim_board::SimFlash flash({kSectors[0], kSectors[1]});
  RecordStore s(flash, kSectors);
  ASSERT_TRUE(s.open().ok());
  const std::vector<uint8_t> a = payload_of(1, 1), b = payload_of(1, 2);
  ASSERT_TRUE(s.write(1, protocol::ByteView{a.data(), a.size()}).ok());
  flash.fail_next(1);
  EXPECT_EQ(s.write(1, protocol::ByteView{b.data(), b.size()}).error(), protocol::Error::kFlashError);
  EXPECT_EQ(read_key(s, 1), a);
  ASSERT_TRUE(s.write(1, protocol::ByteView{b.data(), b.size()}).ok());
  EXPECT_EQ(read_key(s, 1), b);
}

}  // namespace
}  // namespace tetrapulse::fw

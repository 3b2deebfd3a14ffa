// ExposureMatcher: dropped frames, a late first frame, transfer latency, mismatches
// and the camera-clock offset.
#include <gtest/gtest.h>

#include "tetrapulse/host/exposure_matcher.hpp"

namespace tetrapulse::host {
namespace {

constexpr int64_t kPeriod = 10'000'000;
constexpr int64_t kExposure = 2'000'000;

Exposure exposure(int64_t k) { return Exposure{k, 1'000'000'000 + k * kPeriod, kExposure}; }
int64_t end_of(int64_t k) { return exposure(k).timestamp_ns + kExposure; }

TEST(ExposureMatcher, MatchesEachFrameToItsExposureDespiteTransferLatency) {
  ExposureMatcher m(true, {});
  for (int64_t k = 0; k < 5; ++k) m.add_exposure(exposure(k));
  // 7 ms transfer: the frame arrives after the next exposure started, not ended.
  for (int64_t k = 0; k < 5; ++k) {
    auto s = m.match(end_of(k) + 7'000'000, 0);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->exposure.frame, k);
    EXPECT_EQ(s->exposure.timestamp_ns, exposure(k).timestamp_ns);
    EXPECT_FALSE(s->estimated);
  }
  EXPECT_EQ(m.counters().matched, 5u);
  EXPECT_EQ(m.counters().dropped, 0u);
}

TEST(ExposureMatcher, DroppedFramesAndLateFirstFrameAreCountedAndNumbered) {
  ExposureMatcher m(true, {});
  for (int64_t k = 0; k < 8; ++k) m.add_exposure(exposure(k));
  // The camera's first frame is exposure 2; it drops 4 and 5.
  auto first = m.match(end_of(2) + 1'000'000, 0);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->exposure.frame, 0);  // renumbered from the first frame
  ASSERT_TRUE(m.match(end_of(3) + 1'000'000, 0));
  auto after_gap = m.match(end_of(6) + 1'000'000, 0);
  ASSERT_TRUE(after_gap);
  EXPECT_EQ(after_gap->exposure.frame, 4);  // skips the numbers of 4 and 5
  EXPECT_EQ(m.counters().before_first, 2u);
  EXPECT_EQ(m.counters().dropped, 2u);
}

TEST(ExposureMatcher, FrameWithoutExposureIsAMismatch) {
  ExposureMatcher m(true, {});
  m.add_exposure(exposure(0));
  EXPECT_FALSE(m.match(exposure(0).timestamp_ns + 1'000'000, 0));  // before its exposure ended
  EXPECT_FALSE(m.match(end_of(0) + 60'000'000, 0));                // later than max_delay_ns
  EXPECT_EQ(m.counters().unmatched_frames, 2u);
  EXPECT_EQ(m.counters().matched, 0u);
}

TEST(ExposureMatcher, CameraClockOffsetIsTheFastestTransfer) {
  ExposureMatcher::Options o;
  o.exposure_ns = kExposure;
  o.frame_period_ns = kPeriod;
  ExposureMatcher m(false, o);
  const int64_t camera0 = 5'000'000'000, rig_minus_camera = -3'000'000'000;
  const int64_t transfer[] = {4'000'000, 1'500'000, 3'000'000};
  std::optional<MatchedStamp> last;
  for (int k = 0; k < 3; ++k) {
    const int64_t cam = camera0 + k * kPeriod;
    last = m.match(cam + rig_minus_camera + kExposure + transfer[k], cam);
    ASSERT_TRUE(last);
    EXPECT_TRUE(last->estimated);
    EXPECT_EQ(last->exposure.frame, k);
  }
  ASSERT_TRUE(m.offset_ns());
  EXPECT_EQ(*m.offset_ns(), rig_minus_camera + 1'500'000);
  EXPECT_EQ(last->exposure.timestamp_ns, camera0 + 2 * kPeriod + rig_minus_camera + 1'500'000);
  // A frame the camera dropped skips a number.
  const int64_t cam4 = camera0 + 4 * kPeriod;
  auto s = m.match(cam4 + rig_minus_camera + kExposure + 2'000'000, cam4);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->exposure.frame, 4);
}

}  // namespace
}  // namespace tetrapulse::host

// A tracked marker's window holds its whole blob: a bloomed streak's window is
// sized by the longest streak of the last frames (a two_level 0 bit blooms
// shorter than the 1 that follows), and grows when the last window cut one.
#include <gtest/gtest.h>

#include "../src/roi_planner.hpp"

namespace tetrapulse::localizer_internal {
namespace {

constexpr int64_t kFramePeriod = 10'000'000;

Blob spot(int height_px, bool bloomed, bool clipped = false) {
  Blob b;
  b.centroid = Eigen::Vector2d(200, 150);
  b.intensity = 5000;
  b.area = 60;
  b.radius = 4.4;
  b.bbox = cv::Rect(196, 150 - height_px / 2, 9, height_px);
  b.saturated = bloomed;
  b.bloomed = bloomed;
  b.clipped = clipped;
  return b;
}

// One track fed `blobs`, one a frame.
BlobTracker track_of(const std::vector<Blob>& blobs) {
  BlobTracker tracker;
  for (size_t k = 0; k < blobs.size(); ++k) {
    BlobExtraction e;
    e.blobs.push_back(blobs[k]);
    tracker.update(ExposureStamp{int64_t(k), int64_t(k) * kFramePeriod, 2'000'000}, e);
  }
  return tracker;
}

TEST(RoiAperture, ARoundSpotGetsItsRadiusAndAMargin) {
  const BlobTracker tracker = track_of({spot(9, false), spot(9, false)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_DOUBLE_EQ(aperture_radius_for(tracker.tracks()[0]), 4.4 + 2.5);
}

TEST(RoiAperture, AStreakAfterADimBitStillFitsTheLongestRecentStreak) {
  // 1 bits bloom 40 px long, 0 bits 18: after a 0 the window must still hold a 1.
  const BlobTracker tracker = track_of({spot(40, true), spot(18, true), spot(18, true)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_GE(aperture_radius_for(tracker.tracks()[0]), 20 + 2.5);
}

TEST(RoiAperture, AStreakTheWindowCutGrowsTheWindow) {
  const BlobTracker tracker = track_of({spot(30, true, /*clipped=*/true)});
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_GE(aperture_radius_for(tracker.tracks()[0]), 1.5 * 15 + 2.5);
}

TEST(RoiAperture, AStreakLongAgoNoLongerWidensTheWindow) {
  std::vector<Blob> blobs{spot(40, true)};
  for (int k = 0; k < 20; ++k) blobs.push_back(spot(9, false));
  const BlobTracker tracker = track_of(blobs);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_DOUBLE_EQ(aperture_radius_for(tracker.tracks()[0]), 4.4 + 2.5);
}

}  // namespace
}  // namespace tetrapulse::localizer_internal

// An identified target's tracks against their codes (code_checks.hpp): a track
// whose bits stop matching its marker's code leaves the marker, unless geometry
// vouched for it (one of four markers fitting one pose) and it has been followed
// without a merge since; a merge ends the vouching.
#include <gtest/gtest.h>

#include "../src/code_checks.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse::localizer_internal {
namespace {

constexpr int64_t kFrameNs = 10'000'000;  // a bit a frame
constexpr int64_t kExposureNs = 2'000'000;

class Checks : public ::testing::Test {
 protected:
  Checks() {
    targets.timebase = Timebase{0, kFrameNs, true};
    targets.modulation = Modulation{ModulationKind::kTwoLevel, 0.3};
    Target t = testing::hardware_target("paper-large.yaml");
    t.markers[0].code = *parse_code("010011100101", nullptr);
    targets.targets.push_back(t);
  }

  // One track, lit as `played` (a 12-bit code) plays it, for `frames` frames;
  // the samples of the listed frames are marked merged. The roster's target
  // holds the track as marker 0, vouched at `vouched` (-1: never). Returns
  // whether marker 0 still has the track after the code check of each frame.
  bool keeps(const char* played, int frames, int64_t vouched, std::vector<int64_t> merged = {}) {
    const Code code = *parse_code(played, nullptr);
    const CodeClock clock = CodeClock::from(targets.timebase);
    BlobTracker tracker;
    CodeReading reading(targets, BitReading{}, FrequencyIdentifierOptions{}, 48, false);
    TargetRoster roster(camera, targets, PredictionOptions{}, 4);
    CodeChecks checks(targets, {{-1, -1, -1, -1}}, CodeCheckOptions{});
    for (int k = 0; k < frames; ++k) {
      const ExposureStamp stamp{k, 4'000'000 + k * kFrameNs, kExposureNs};
      BlobExtraction e;
      Blob b;
      b.centroid = Eigen::Vector2d(300, 200);
      b.radius = 5;
      b.area = 80;
      b.intensity = 4000 * mean_emission(clock, targets.modulation, code, stamp.timestamp_ns, kExposureNs);
      b.merged = std::count(merged.begin(), merged.end(), int64_t(k)) > 0;
      e.blobs.push_back(b);
      tracker.update(stamp, e);
      if (k == 0) {
        roster[0].identify({tracker.tracks()[0].id(), -1, -1, -1}, clock, Pose{}, 0.1, stamp.middle_ns());
        roster[0].vouched_frame[0] = vouched;
      }
      reading.update(tracker, k);
      checks.check(tracker, reading, k, stamp.middle_ns(), &roster);
      if (roster[0].track_of[0] < 0) return false;
    }
    return true;
  }

  CameraModel camera{testing::wide_plumb_bob_camera()};
  TargetsFile targets;
};

TEST_F(Checks, ATrackPlayingItsCodeKeepsItsMarker) { EXPECT_TRUE(keeps("010011100101", 48, -1)); }

TEST_F(Checks, ATrackPlayingAnotherCodeLeavesItsMarker) { EXPECT_FALSE(keeps("101100011010", 48, -1)); }

TEST_F(Checks, GeometryVouchesForATrackFollowedSince) {
  // The same unreadable light, but four markers fitted one pose in frame 0 and
  // the blob was followed alone since: it stays (both levels clipped read wrong).
  EXPECT_TRUE(keeps("101100011010", 48, 0));
}

TEST_F(Checks, AMergeSinceTheFitEndsTheVouching) {
  EXPECT_FALSE(keeps("101100011010", 48, 0, {20}));
}

}  // namespace
}  // namespace tetrapulse::localizer_internal

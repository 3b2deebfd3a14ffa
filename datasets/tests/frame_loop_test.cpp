// localize_frames over a source like a live camera's: a bad buffer (Frame::unreadable)
// and a frame the localizer refuses each cost only themselves, and the stop flag
// ends the loop between frames (docs/reliability.md).
#include <gtest/gtest.h>

#include <atomic>
#include <deque>
#include <string>
#include <vector>

#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

// Frames handed out in order; "bad" ones come unreadable, "small" ones are of the wrong size.
class ScriptedFrames : public FrameSource {
 public:
  ScriptedFrames(const CameraInfo& camera, std::vector<std::string> script) : camera_(camera) {
    for (std::string& s : script) script_.push_back(std::move(s));
  }
  DatasetResult<std::optional<Frame>> next() override {
    if (script_.empty()) return std::optional<Frame>();
    const std::string kind = script_.front();
    script_.pop_front();
    Frame f{frame_, frame_ * 10'000'000, 2'000'000, {}, "cam frame " + std::to_string(frame_), std::nullopt};
    ++frame_;
    if (kind == "bad") {
      f.unreadable = DatasetError{"cam", 0, "frame " + std::to_string(f.frame) + ": 3 bytes, not a frame"};
    } else {
      const int rows = kind == "small" ? camera_.height / 2 : camera_.height;
      f.image = cv::Mat(rows, camera_.width, CV_8UC1, cv::Scalar(5));
    }
    return f;
  }
  std::optional<size_t> count() const override { return std::nullopt; }

 private:
  CameraInfo camera_;
  std::deque<std::string> script_;
  int64_t frame_ = 0;
};

TEST(FrameLoop, BadBuffersAndRefusedFramesAreSkippedAndNamed) {
  const CameraInfo camera = testing::wide_plumb_bob_camera();
  Localizer localizer(camera, TargetsFile{});
  ScriptedFrames source(camera, {"good", "bad", "good", "small", "bad", "good"});
  std::vector<int64_t> localized;
  std::vector<std::string> skipped;
  LocalizeHooks hooks;
  hooks.on_skip = [&](const Frame& f, const DatasetError& why) { skipped.push_back(f.name + ": " + why.what()); };
  auto r = localize_frames(
      source, localizer,
      [&](const Frame& f, const std::vector<TargetPose>&) {
        localized.push_back(f.frame);
        return DatasetResult<void>{};
      },
      hooks);
  ASSERT_TRUE(r) << r.error().what();
  EXPECT_EQ(r->frames, 3u);
  EXPECT_EQ(r->skipped, 3u);
  EXPECT_FALSE(r->stopped);
  EXPECT_EQ(localized, (std::vector<int64_t>{0, 2, 5}));
  ASSERT_EQ(skipped.size(), 3u);
  EXPECT_NE(skipped[0].find("cam: frame 1: 3 bytes"), std::string::npos) << skipped[0];
  EXPECT_NE(skipped[1].find("cam frame 3"), std::string::npos) << skipped[1];
  EXPECT_NE(skipped[2].find("frame 4"), std::string::npos) << skipped[2];
}

TEST(FrameLoop, StopFlagEndsTheLoopBetweenFrames) {
  const CameraInfo camera = testing::wide_plumb_bob_camera();
  Localizer localizer(camera, TargetsFile{});
  ScriptedFrames source(camera, {"good", "good", "good", "good"});
  std::atomic<bool> stop{false};
  LocalizeHooks hooks;
  hooks.stop = &stop;
  size_t seen = 0;
  auto r = localize_frames(
      source, localizer,
      [&](const Frame&, const std::vector<TargetPose>&) {
        if (++seen == 2) stop = true;  // as the signal handler would
        return DatasetResult<void>{};
      },
      hooks);
  ASSERT_TRUE(r) << r.error().what();
  EXPECT_EQ(r->frames, 2u);
  EXPECT_TRUE(r->stopped);
}

}  // namespace
}  // namespace tetrapulse

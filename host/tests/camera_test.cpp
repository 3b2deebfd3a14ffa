// Camera specs, the NVI counters and the V4L2 backend's errors (no device needed).
#include <gtest/gtest.h>

#include <deque>

#include "tetrapulse/host/camera.hpp"

namespace tetrapulse::host {
namespace {

class ScriptedCamera final : public Camera {
 public:
  explicit ScriptedCamera(std::deque<CameraFrame> frames) : Camera("scripted"), frames_(std::move(frames)) {}

 private:
  HostResult<std::vector<std::string>> do_configure(const CameraSettings&) override { return std::vector<std::string>{}; }
  HostResult<void> do_start() override { return {}; }
  HostResult<std::optional<CameraFrame>> do_grab(int) override {
    if (frames_.empty()) return std::optional<CameraFrame>{};
    CameraFrame f = std::move(frames_.front());
    frames_.pop_front();
    return std::optional<CameraFrame>(std::move(f));
  }
  void do_stop() override {}
  std::deque<CameraFrame> frames_;
};

TEST(CameraSpec, NamesBackendAndAddress) {
  auto a = parse_camera_spec("aravis:127.0.0.1");
  ASSERT_TRUE(a);
  EXPECT_EQ(a->backend, "aravis");
  EXPECT_EQ(a->address, "127.0.0.1");
  auto v = parse_camera_spec("v4l2:/dev/video3");
  ASSERT_TRUE(v);
  EXPECT_EQ(v->backend, "v4l2");
  EXPECT_EQ(v->address, "/dev/video3");
}

TEST(CameraSpec, RejectsWhatIsNotOne) {
  for (const char* bad : {"", "/dev/video0", "aravis:", "usb:1234"}) {
    auto s = parse_camera_spec(bad);
    ASSERT_FALSE(s) << bad;
    EXPECT_EQ(s.error().kind, HostErrorKind::kBadInput);
    EXPECT_EQ(s.error().device, bad);
  }
}

TEST(Camera, CountsBadBuffersWithoutStopping) {
  std::deque<CameraFrame> frames(3);
  frames[1].bad = "missing packets";
  ScriptedCamera camera(std::move(frames));
  int got = 0;
  while (true) {
    auto f = camera.grab(0);
    ASSERT_TRUE(f);
    if (!*f) break;
    ++got;
  }
  EXPECT_EQ(got, 3);
  EXPECT_EQ(camera.counters().frames, 3u);
  EXPECT_EQ(camera.counters().bad_buffers, 1u);
}

TEST(V4l2Camera, MissingDeviceIsNotFound) {
  auto c = open_camera("v4l2:/dev/no-such-video-device");
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().kind, HostErrorKind::kNotFound);
  EXPECT_EQ(c.error().device, "v4l2:/dev/no-such-video-device");
}

TEST(V4l2Camera, NonCaptureDeviceIsRefused) {
  auto c = open_camera("v4l2:/dev/null");
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().kind, HostErrorKind::kOpenFailed);
}

}  // namespace
}  // namespace tetrapulse::host

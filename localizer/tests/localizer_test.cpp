// The Localizer's API on inputs it must refuse (errors are values, never a
// crash) and on the image types it accepts.
#include "tetrapulse/localizer/localizer.hpp"

#include <gtest/gtest.h>

#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

class LocalizerApi : public ::testing::Test {
 protected:
  LocalizerApi() {
    Target t = testing::hardware_target("paper-large.yaml");
    t.id = 4;
    for (Marker& m : t.markers) m.code = parse_code("010011100101", nullptr);
    targets.targets.push_back(t);
    targets.modulation = Modulation{ModulationKind::kTwoLevel, 0.3};
  }
  cv::Mat grey(int type = CV_8UC1) const { return cv::Mat(camera.height, camera.width, type, cv::Scalar::all(5)); }

  CameraInfo camera = testing::wide_plumb_bob_camera();
  TargetsFile targets;
};

TEST_F(LocalizerApi, RefusesAnImageOfAnotherSize) {
  Localizer localizer(camera, targets);
  const auto r = localizer.process(cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), 0, 2'000'000);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("640x480"), std::string::npos) << r.error().message;
  // It still works afterwards.
  EXPECT_TRUE(localizer.process(grey(), 0, 2'000'000));
}

TEST_F(LocalizerApi, RefusesTimeThatDoesNotAdvanceAndEmptyExposures) {
  Localizer localizer(camera, targets);
  ASSERT_TRUE(localizer.process(grey(), 10'000'000, 2'000'000));
  EXPECT_FALSE(localizer.process(grey(), 10'000'000, 2'000'000));  // same start
  EXPECT_FALSE(localizer.process(grey(), 5'000'000, 2'000'000));   // earlier
  EXPECT_FALSE(localizer.process(grey(), 20'000'000, 0));          // no exposure
  EXPECT_TRUE(localizer.process(grey(), 20'000'000, 2'000'000));
}

TEST_F(LocalizerApi, AcceptsGrey16AndColourAndReportsNothingInAnEmptyScene) {
  for (int type : {CV_8UC1, CV_16UC1, CV_8UC3}) {
    Localizer localizer(camera, targets);
    for (int k = 0; k < 5; ++k) {
      const auto r = localizer.process(grey(type), k * 10'000'000, 2'000'000);
      ASSERT_TRUE(r) << r.error().message;
      EXPECT_TRUE(r->empty());
    }
  }
}

TEST_F(LocalizerApi, RefusesUnsupportedImageTypes) {
  Localizer localizer(camera, targets);
  const auto r = localizer.process(grey(CV_32FC1), 0, 2'000'000);
  EXPECT_FALSE(r);
}

}  // namespace
}  // namespace tetrapulse

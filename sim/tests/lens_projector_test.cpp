// The simulator's lens (OpenCV) against the localizer's CameraModel: both claim
// OpenCV's conventions, so on every point both project they must agree; a shared
// convention that OpenCV does not share (pixel centre, axis order, the fisheye
// angle) would show up here, not cancel in a round trip sim -> localizer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/sim/lens_projector.hpp"
#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {
namespace {

CameraInfo camera(DistortionModel model, double hfov_deg, std::array<double, 5> d) {
  CameraInfo c;
  c.width = 1280;
  c.height = 960;
  const double half = hfov_deg * M_PI / 360;
  c.fx = c.fy = model == DistortionModel::kEquidistant ? 640 / half : 640 / std::tan(half);
  c.cx = 639.5;
  c.cy = 479.5;
  c.model = model;
  c.distortion = d;
  return c;
}

// Worst |sim - localizer| over points spread over the front hemisphere, and how
// many both project (points near the fold limit may differ in validity: skipped).
struct Agreement {
  int both = 0;
  double worst_px = 0;
  double worst_roundtrip_px = 0;
};

Agreement compare(const CameraInfo& info, double max_angle_deg) {
  const LensProjector sim(info);
  const CameraModel loc(info);
  Random rng(7);
  Agreement a;
  for (int k = 0; k < 4000; ++k) {
    const double theta = max_angle_deg * M_PI / 180 * std::sqrt(rng.uniform());
    const double phi = 2 * M_PI * rng.uniform();
    const double dist = 0.2 + 10 * rng.uniform();
    const Eigen::Vector3d p = dist * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                                     std::cos(theta));
    Eigen::Vector2d ps, pl;
    const bool s = sim.project(p, &ps), l = loc.project(p, &pl);
    if (!s || !l) continue;
    ++a.both;
    a.worst_px = std::max(a.worst_px, (ps - pl).norm());
    if (!sim.in_image(ps)) continue;
    Eigen::Vector3d b;
    if (!sim.unproject(ps, &b)) continue;
    Eigen::Vector2d back;
    if (loc.project(b, &back)) a.worst_roundtrip_px = std::max(a.worst_roundtrip_px, (back - ps).norm());
  }
  return a;
}

void check(const char* what, const CameraInfo& info, double max_angle_deg) {
  const Agreement a = compare(info, max_angle_deg);
  std::printf("%s: %d points, worst |OpenCV - CameraModel| %.3g px, unproject round trip %.3g px\n", what, a.both,
              a.worst_px, a.worst_roundtrip_px);
  EXPECT_GE(a.both, 3000) << what;
  EXPECT_LT(a.worst_px, 1e-9) << what;
  EXPECT_LT(a.worst_roundtrip_px, 1e-6) << what;
}

TEST(LensProjector, PlumbBobAgreesWithCameraModel) {
  check("plumb_bob mild", camera(DistortionModel::kPlumbBob, 90, {-0.05, 0.01, 0, 0, 0}), 44);
  check("plumb_bob tangential", camera(DistortionModel::kPlumbBob, 90, {-0.1, 0.02, 0.001, -0.0005, 0.001}), 44);
  check("plumb_bob k1 -0.3", camera(DistortionModel::kPlumbBob, 100, {-0.3, 0.0, 0, 0, 0}), 45);
}

TEST(LensProjector, FisheyeAgreesWithCameraModel) {
  check("equidistant 150", camera(DistortionModel::kEquidistant, 150, {0.02, -0.01, 0.003, -0.001, 0}), 74);
  check("equidistant 180", camera(DistortionModel::kEquidistant, 180, {-0.02, 0.004, 0, 0, 0}), 89.5);
}

TEST(LensProjector, RefusesWhatNoLensShows) {
  const LensProjector pinhole(camera(DistortionModel::kPlumbBob, 100, {-0.3, 0, 0, 0, 0}));
  Eigen::Vector2d px;
  EXPECT_FALSE(pinhole.project(Eigen::Vector3d(0, 0, -1), &px));
  EXPECT_FALSE(pinhole.project(Eigen::Vector3d(1, 0, 0), &px));
  // k1 = -0.3: r (1 - 0.3 r^2) stops growing at r^2 = 1/0.9 (46.5 degrees off axis).
  EXPECT_TRUE(pinhole.project(Eigen::Vector3d(std::tan(45.5 * M_PI / 180), 0, 1), &px));
  EXPECT_FALSE(pinhole.project(Eigen::Vector3d(std::tan(47.5 * M_PI / 180), 0, 1), &px));
  const LensProjector fisheye(camera(DistortionModel::kEquidistant, 180, {0, 0, 0, 0, 0}));
  EXPECT_TRUE(fisheye.project(Eigen::Vector3d(1, 0, 0.01), &px));
  EXPECT_NEAR(px.x(), 639.5 + 640 * std::atan2(1, 0.01) / (M_PI / 2), 1e-6);
  EXPECT_FALSE(fisheye.project(Eigen::Vector3d(1, 0, -0.01), &px));
}

}  // namespace
}  // namespace tetrapulse::sim

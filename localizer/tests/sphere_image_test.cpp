// The sphere-image centroid against the pinhole closed form and against a
// supersampled rendering of the sphere's image through each camera model.
#include "tetrapulse/localizer/sphere_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

// Area centroid of the pixels (sampled every `step` px) whose ray meets the sphere:
// an independent rendering that uses unproject, not project.
Eigen::Vector2d rendered_centroid(const CameraModel& camera, const Eigen::Vector3d& centre, double radius,
                                  double step) {
  const Eigen::Vector3d c = centre.normalized();
  const double cos_alpha = std::sqrt(1 - radius * radius / centre.squaredNorm());
  Eigen::Vector2d middle;
  EXPECT_TRUE(camera.project(centre, &middle));
  // The window: the projected rim's extent, plus a pixel.
  double half_width_px = 0;
  const Eigen::Vector3d e1 = c.unitOrthogonal(), e2 = c.cross(e1);
  for (int k = 0; k < 64; ++k) {
    const double phi = 2 * M_PI * k / 64, sin_alpha = radius / centre.norm();
    Eigen::Vector2d q;
    EXPECT_TRUE(camera.project(cos_alpha * c + sin_alpha * (std::cos(phi) * e1 + std::sin(phi) * e2), &q));
    half_width_px = std::max(half_width_px, (q - middle).cwiseAbs().maxCoeff() + 1);
  }
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  long count = 0;
  for (double y = middle.y() - half_width_px; y <= middle.y() + half_width_px; y += step) {
    for (double x = middle.x() - half_width_px; x <= middle.x() + half_width_px; x += step) {
      Eigen::Vector3d ray;
      if (camera.unproject({x, y}, &ray) && ray.dot(c) >= cos_alpha) sum += Eigen::Vector2d(x, y), ++count;
    }
  }
  return sum / count;
}

// Where the ray of the pinhole ellipse's centre c_z c_xy / (c_z^2 - sin^2 alpha)
// projects: the same correction carried through the distortion to first order.
Eigen::Vector2d first_order_centroid(const CameraModel& camera, const Eigen::Vector3d& centre, double radius) {
  const Eigen::Vector3d c = centre.normalized();
  const Eigen::Vector2d m = c.head<2>() * c.z() / (c.z() * c.z() - radius * radius / centre.squaredNorm());
  Eigen::Vector2d px;
  EXPECT_TRUE(camera.project(Eigen::Vector3d(m.x(), m.y(), 1.0), &px));
  return px;
}

// A 3 cm sphere 1 m away along the ray of each of these pixels (centre, mid-field,
// corners) of the 752 x 480 test cameras.
const Eigen::Vector2d kPixels[] = {{375, 240}, {600, 300}, {150, 400}, {740, 470}, {20, 15}};

TEST(SphereImage, MatchesThePinholeEllipseCentre) {
  CameraInfo info = testing::wide_plumb_bob_camera();
  info.distortion = {};
  const CameraModel camera(info);
  double largest_offset = 0;
  for (const auto& pixel : kPixels) {
    Eigen::Vector3d ray;
    ASSERT_TRUE(camera.unproject(pixel, &ray));
    Eigen::Vector2d exact, centre;
    ASSERT_TRUE(sphere_image_centroid(camera, ray, 0.015, &exact));
    ASSERT_TRUE(camera.project(ray, &centre));
    EXPECT_LT((exact - first_order_centroid(camera, ray, 0.015)).norm(), 1e-5);
    largest_offset = std::max(largest_offset, (exact - centre).norm());
  }
  std::printf("undistorted 90 degree camera: silhouette centre up to %.3f px from the centre's projection\n",
              largest_offset);
  EXPECT_GT(largest_offset, 0.1);  // the effect the model exists for
}

class SphereImageRendered : public ::testing::TestWithParam<CameraInfo> {};

TEST_P(SphereImageRendered, AgreesWithASupersampledRendering) {
  const CameraModel camera(GetParam());
  double worst = 0, worst_first_order = 0, largest_offset = 0;
  for (const auto& pixel : kPixels) {
    Eigen::Vector3d ray;
    if (!camera.unproject(pixel, &ray) || ray.z() < 0.2) continue;  // beyond the lens's field
    Eigen::Vector2d exact, centre;
    ASSERT_TRUE(sphere_image_centroid(camera, ray, 0.015, &exact));
    ASSERT_TRUE(camera.project(ray, &centre));
    const Eigen::Vector2d rendered = rendered_centroid(camera, ray, 0.015, 0.025);
    worst = std::max(worst, (exact - rendered).norm());
    worst_first_order = std::max(worst_first_order, (first_order_centroid(camera, ray, 0.015) - rendered).norm());
    largest_offset = std::max(largest_offset, (rendered - centre).norm());
  }
  std::printf("%s: offset up to %.3f px; model within %.4f px of the rendering, first-order pinhole "
              "correction within %.3f px\n",
              GetParam().name.c_str(), largest_offset, worst, worst_first_order);
  EXPECT_LT(worst, 0.002);  // the rendering's own sampling error is about 1e-3 px
}

INSTANTIATE_TEST_SUITE_P(Cameras, SphereImageRendered,
                         ::testing::Values(testing::wide_plumb_bob_camera(), testing::fisheye_camera()),
                         [](const ::testing::TestParamInfo<CameraInfo>& camera) { return camera.param.name; });

TEST(SphereImage, RefusesACameraInsideTheSphereOrBehindIt) {
  const CameraModel camera(testing::wide_plumb_bob_camera());
  Eigen::Vector2d px;
  EXPECT_FALSE(sphere_image_centroid(camera, Eigen::Vector3d(0, 0, 0.01), 0.015, &px));
  EXPECT_FALSE(sphere_image_centroid(camera, Eigen::Vector3d(0, 0, -1), 0.015, &px));
  EXPECT_FALSE(sphere_image_centroid(camera, Eigen::Vector3d(0, 0, 1), -0.015, &px));
  EXPECT_TRUE(sphere_image_centroid(camera, Eigen::Vector3d(0, 0, 1), 0.0, &px));
}

}  // namespace
}  // namespace tetrapulse

#include "tetrapulse/localizer/camera_model.hpp"

#include <gtest/gtest.h>

#include <random>

#include <opencv2/calib3d.hpp>

namespace tetrapulse {
namespace {

CameraInfo pinhole() {
  CameraInfo c;
  c.width = 752;
  c.height = 480;
  c.fx = 376.0;
  c.fy = 377.5;
  c.cx = 375.3;
  c.cy = 241.1;
  c.model = DistortionModel::kPlumbBob;
  c.distortion = {-0.28, 0.09, 0.0011, -0.0007, -0.012};
  return c;
}

CameraInfo fisheye() {
  CameraInfo c;
  c.width = 752;
  c.height = 480;
  c.fx = 210.0;
  c.fy = 210.5;
  c.cx = 376.2;
  c.cy = 239.4;
  c.model = DistortionModel::kEquidistant;
  c.distortion = {0.02, -0.01, 0.003, -0.0005, 0};
  return c;
}

std::vector<Eigen::Vector3d> random_points(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> pts;
  while (pts.size() < 500) {
    Eigen::Vector3d p(u(rng), u(rng), 0.2 + 3 * std::abs(u(rng)));
    if (std::atan2(p.head<2>().norm(), p.z()) < max_angle) pts.push_back(p);
  }
  return pts;
}

void expect_matches_opencv(const CameraInfo& info) {
  const CameraModel cam(info);
  std::mt19937 rng(3);
  const auto pts = random_points(rng, info.model == DistortionModel::kPlumbBob ? 0.75 : 1.3);
  std::vector<cv::Point3d> obj;
  for (const auto& p : pts) obj.emplace_back(p.x(), p.y(), p.z());
  cv::Mat K = (cv::Mat_<double>(3, 3) << info.fx, 0, info.cx, 0, info.fy, info.cy, 0, 0, 1);
  std::vector<cv::Point2d> img;
  if (info.model == DistortionModel::kPlumbBob) {
    cv::Mat D = (cv::Mat_<double>(1, 5) << info.distortion[0], info.distortion[1], info.distortion[2],
                 info.distortion[3], info.distortion[4]);
    cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, img);
  } else {
    cv::Mat D = (cv::Mat_<double>(1, 4) << info.distortion[0], info.distortion[1], info.distortion[2],
                 info.distortion[3]);
    cv::fisheye::projectPoints(obj, img, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  }
  double worst = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    Eigen::Vector2d px;
    ASSERT_TRUE(cam.project(pts[i], &px));
    worst = std::max(worst, (px - Eigen::Vector2d(img[i].x, img[i].y)).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(CameraModel, PlumbBobMatchesOpenCvProjectPoints) { expect_matches_opencv(pinhole()); }
TEST(CameraModel, EquidistantMatchesOpenCvFisheyeProjectPoints) { expect_matches_opencv(fisheye()); }

void expect_jacobian_matches_finite_differences(const CameraInfo& info) {
  const CameraModel cam(info);
  std::mt19937 rng(5);
  int bad = 0;
  for (const auto& p : random_points(rng, 0.7)) {
    Eigen::Vector2d px;
    Eigen::Matrix<double, 2, 3> J;
    ASSERT_TRUE(cam.project(p, &px, &J));
    Eigen::Matrix<double, 2, 3> Jn;
    for (int k = 0; k < 3; ++k) {
      const double h = 1e-6;
      Eigen::Vector3d a = p, b = p;
      a[k] += h;
      b[k] -= h;
      Eigen::Vector2d pa, pb;
      cam.project(a, &pa);
      cam.project(b, &pb);
      Jn.col(k) = (pa - pb) / (2 * h);
    }
    bad += (J - Jn).norm() > 1e-5 * std::max(1.0, J.norm());
  }
  EXPECT_EQ(bad, 0);
}

TEST(CameraModel, PlumbBobJacobianMatchesFiniteDifferences) { expect_jacobian_matches_finite_differences(pinhole()); }
TEST(CameraModel, EquidistantJacobianMatchesFiniteDifferences) {
  expect_jacobian_matches_finite_differences(fisheye());
}

// project_along is J dp without J: the same pixel, and the Jacobian's product
// with the direction to rounding; it refuses exactly where project does.
void expect_derivative_along_is_jacobian_times_direction(const CameraInfo& info) {
  const CameraModel cam(info);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int bad = 0, compared = 0;
  for (const auto& p : random_points(rng, 1.5)) {
    const Eigen::Vector3d dp(u(rng), u(rng), u(rng));
    Eigen::Vector2d px, px_along, dpx;
    Eigen::Matrix<double, 2, 3> J;
    const bool projects = cam.project(p, &px, &J);
    ASSERT_EQ(cam.project_along(p, dp, &px_along, &dpx), projects);
    if (!projects) continue;
    ++compared;
    bad += px_along != px;
    bad += (dpx - J * dp).norm() > 1e-12 * std::max(1.0, J.norm() * dp.norm());
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(compared, 300);
  Eigen::Vector2d px, dpx;
  EXPECT_FALSE(cam.project_along(Eigen::Vector3d(0.1, 0.1, -1), Eigen::Vector3d(1, 0, 0), &px, &dpx));
  EXPECT_FALSE(cam.project_along(Eigen::Vector3d(NAN, 0.1, 1), Eigen::Vector3d(1, 0, 0), &px, &dpx));
}

TEST(CameraModel, PlumbBobDerivativeAlongADirectionIsTheJacobianTimesIt) {
  expect_derivative_along_is_jacobian_times_direction(pinhole());
}
TEST(CameraModel, EquidistantDerivativeAlongADirectionIsTheJacobianTimesIt) {
  expect_derivative_along_is_jacobian_times_direction(fisheye());
}

void expect_unproject_inverts_project(const CameraInfo& info, double max_angle) {
  const CameraModel cam(info);
  std::mt19937 rng(9);
  int bad = 0;
  for (const auto& p : random_points(rng, max_angle)) {
    Eigen::Vector2d px;
    Eigen::Vector3d b;
    ASSERT_TRUE(cam.project(p, &px));
    ASSERT_TRUE(cam.unproject(px, &b));
    bad += (b - p.normalized()).norm() > 1e-9;
  }
  EXPECT_EQ(bad, 0);
}

TEST(CameraModel, PlumbBobUnprojectInvertsProject) { expect_unproject_inverts_project(pinhole(), 0.75); }
TEST(CameraModel, EquidistantUnprojectInvertsProjectTo75Degrees) {
  expect_unproject_inverts_project(fisheye(), 75.0 * M_PI / 180.0);
}

TEST(CameraModel, PointsBehindTheCameraDoNotProject) {
  const CameraModel cam(pinhole());
  Eigen::Vector2d px;
  EXPECT_FALSE(cam.project(Eigen::Vector3d(0.1, 0.1, -1), &px));
  EXPECT_FALSE(cam.project(Eigen::Vector3d(0.1, 0.1, 0), &px));
}

// Strong barrel distortion: r (1 - 0.4 r^2) peaks at r^2 = 1/1.2 and then folds back,
// so a point 60 degrees off-axis would land 0.2 focal lengths from the centre.
CameraInfo folding_plumb_bob() {
  CameraInfo c = pinhole();
  c.distortion = {-0.4, 0.0, 0.0, 0.0, 0.0};
  return c;
}

TEST(CameraModel, PlumbBobRangeIsWhereTheRadialMapIncreases) {
  const CameraModel cam(folding_plumb_bob());
  EXPECT_NEAR(cam.max_radius2(), 1.0 / 1.2, 1e-12);
  // Without the range check this point would project inside the image.
  const Eigen::Vector3d far_off_axis(std::tan(60 * M_PI / 180), 0, 1);
  const double r = far_off_axis.x(), folded_u = 376.0 * r * (1 - 0.4 * r * r) + 375.3;
  ASSERT_TRUE(cam.in_image(Eigen::Vector2d(folded_u, 241.1)));
  Eigen::Vector2d px;
  EXPECT_FALSE(cam.project(far_off_axis, &px));
  // Just inside the range it projects; just outside it does not, in every direction.
  const double edge = std::sqrt(cam.max_radius2());
  for (int k = 0; k < 16; ++k) {
    const double a = 2 * M_PI * k / 16;
    EXPECT_TRUE(cam.project(Eigen::Vector3d(0.999 * edge * std::cos(a), 0.999 * edge * std::sin(a), 1), &px));
    EXPECT_FALSE(cam.project(Eigen::Vector3d(1.001 * edge * std::cos(a), 1.001 * edge * std::sin(a), 1), &px));
  }
}

TEST(CameraModel, ProjectionIsMonotonicAlongEveryRayWithinItsRange) {
  // Sweep coefficient sets, some of which fold: along a ray from the axis, every
  // projected point lies further from the principal point than the one before.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> k(-0.5, 0.2);
  int folds = 0;
  for (int trial = 0; trial < 200; ++trial) {
    CameraInfo info = pinhole();
    info.distortion = {k(rng), k(rng), 0.0, 0.0, 0.2 * k(rng)};
    const CameraModel cam(info);
    folds += std::isfinite(cam.max_radius2());
    double last = -1;
    for (double r = 0; r < 4; r += 0.01) {
      Eigen::Vector2d px;
      if (!cam.project(Eigen::Vector3d(r, 0.3 * r, 1), &px)) break;
      const double from_centre = (px - Eigen::Vector2d(info.cx, info.cy)).norm();
      ASSERT_GT(from_centre, last) << "trial " << trial << " r " << r;
      last = from_centre;
    }
  }
  EXPECT_GT(folds, 20);  // the sweep did meet folding models
}

TEST(CameraModel, EquidistantRangeIsWhereThetaDIncreases) {
  CameraInfo info = fisheye();
  info.distortion = {-0.3, 0.0, 0.0, 0.0, 0.0};  // d theta_d / d theta = 1 - 0.9 theta^2
  const CameraModel cam(info);
  EXPECT_NEAR(cam.max_theta(), std::sqrt(1 / 0.9), 1e-12);
  Eigen::Vector2d px;
  const double t = cam.max_theta();
  EXPECT_TRUE(cam.project(Eigen::Vector3d(std::sin(0.999 * t), 0, std::cos(0.999 * t)), &px));
  EXPECT_FALSE(cam.project(Eigen::Vector3d(std::sin(1.001 * t), 0, std::cos(1.001 * t)), &px));
  EXPECT_EQ(CameraModel(fisheye()).max_theta(), M_PI / 2);  // the test lens never folds
}

TEST(CameraModel, PixelCentresAreIntegers) {
  const CameraModel cam(pinhole());
  EXPECT_TRUE(cam.in_image(Eigen::Vector2d(-0.5, -0.5)));
  EXPECT_FALSE(cam.in_image(Eigen::Vector2d(-0.51, 0)));
  EXPECT_TRUE(cam.in_image(Eigen::Vector2d(751.49, 479.49)));
  EXPECT_FALSE(cam.in_image(Eigen::Vector2d(751.5, 0)));
}

}  // namespace
}  // namespace tetrapulse

// The renderer against closed forms: exact coverage, the silhouette's true
// centroid (pinhole), and OpenCV's projection where the silhouette bias is negligible.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdio>

#include <opencv2/calib3d.hpp>

#include "tetrapulse/sim/coverage_patch.hpp"
#include "tetrapulse/sim/flicker_emitter.hpp"
#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/silhouette_centroid.hpp"

namespace tetrapulse::sim {
namespace {

CameraInfo pinhole_752(double k1 = 0, double k2 = 0, double p1 = 0, double p2 = 0, double k3 = 0) {
  CameraInfo c;
  c.width = 752;
  c.height = 480;
  c.fx = c.fy = 376.0;  // 90 degrees horizontal field of view
  c.cx = 375.5;
  c.cy = 239.5;
  c.model = DistortionModel::kPlumbBob;
  c.distortion = {k1, k2, p1, p2, k3};
  return c;
}

CameraInfo fisheye_752(double k1 = 0, double k2 = 0, double k3 = 0, double k4 = 0) {
  CameraInfo c = pinhole_752();
  c.fx = c.fy = 376.0 / (75.0 * M_PI / 180.0);  // 150 degrees horizontal field of view
  c.model = DistortionModel::kEquidistant;
  c.distortion = {k1, k2, k3, k4, 0};
  return c;
}

// One still sphere at C (camera frame), full emission, 1 electron per fully covered pixel.
cv::Mat render_sphere(const CameraInfo& info, const Eigen::Vector3d& C, double radius, double psf_sigma,
                      double beam_exponent = 0, const Eigen::Vector3d& beam_axis = Eigen::Vector3d::UnitZ()) {
  Scene scene;
  scene.camera = LensProjector(info);
  scene.bodies.emplace_back();
  scene.emitters.push_back(std::make_unique<FlickerEmitter>(Flicker{}));
  LightSphere light;
  light.position_m = C;
  light.radius_m = radius;
  light.radiance_e_per_ms = 1.0;
  light.beam_exponent = beam_exponent;
  light.beam_axis_B = beam_axis;
  scene.lights.push_back(light);
  // Only the light is read; the sensor is never asked to expose.
  static SensorModel sensor(info.width, info.height, SensorConfig{}, 1);
  RenderSettings settings;
  settings.psf_sigma_px = psf_sigma;
  FrameRenderer renderer(scene, settings, sensor);
  cv::Mat light_e(info.height, info.width, CV_32F, cv::Scalar(0));
  renderer.add_light(0, 1'000'000, &light_e);
  return light_e;
}

struct Moments {
  double sum = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

Moments moments(const cv::Mat& img) {
  double s = 0, sx = 0, sy = 0;
  for (int y = 0; y < img.rows; ++y) {
    const float* row = img.ptr<float>(y);
    for (int x = 0; x < img.cols; ++x) {
      const double v = row[x];
      s += v;
      sx += v * x;
      sy += v * y;
    }
  }
  return Moments{s, Eigen::Vector2d(sx / s, sy / s)};
}

Eigen::Vector2d opencv_projection(const CameraInfo& info, const Eigen::Vector3d& C) {
  const cv::Matx33d K(info.fx, 0, info.cx, 0, info.fy, info.cy, 0, 0, 1);
  std::vector<cv::Point3d> object{cv::Point3d(C.x(), C.y(), C.z())};
  std::vector<cv::Point2d> image;
  const cv::Vec3d zero(0, 0, 0);
  if (info.model == DistortionModel::kPlumbBob) {
    const std::vector<double> D(info.distortion.begin(), info.distortion.begin() + 5);
    cv::projectPoints(object, zero, zero, K, D, image);
  } else {
    const std::vector<double> D(info.distortion.begin(), info.distortion.begin() + 4);
    cv::fisheye::projectPoints(object, image, zero, zero, K, D);
  }
  return Eigen::Vector2d(image[0].x, image[0].y);
}

// A sphere centre whose image lands at pixel `px` at distance `dist` from the camera.
Eigen::Vector3d centre_at_pixel(const CameraInfo& info, const Eigen::Vector2d& px, double dist) {
  Eigen::Vector3d bearing;
  EXPECT_TRUE(CameraModel(info).unproject(px, &bearing));
  return bearing * dist;
}

TEST(CoveragePatch, SquareCoversExactlyItsArea) {
  CoveragePatch patch;
  patch.reset(0, 0, 6, 5);
  // A 2.5 x 1.75 rectangle from (0.75, 1.0) (pixel coordinates).
  patch.add_polygon({{0.75, 1.0}, {3.25, 1.0}, {3.25, 2.75}, {0.75, 2.75}}, 1.0);
  patch.resolve();
  double sum = 0;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 6; ++i) sum += patch.at(i, j);
  }
  EXPECT_NEAR(sum, 2.5 * 1.75, 1e-12);
  // Pixel (2, 2) spans [1.5, 2.5) x [1.5, 2.5): fully inside; pixel (1, 2) three quarters.
  EXPECT_NEAR(patch.at(2, 2), 1.0, 1e-12);
  EXPECT_NEAR(patch.at(1, 2), 0.75, 1e-12);
  // Pixel (0, 1) spans [-0.5, 0.5) x [0.5, 1.5): x from 0.75? no overlap in x.
  EXPECT_NEAR(patch.at(0, 1), 0.0, 1e-12);
  // Pixel (3, 1): x [2.5, 3.5) ∩ [0.75, 3.25] = 0.75; y [0.5, 1.5) ∩ [1, 2.75] = 0.5.
  EXPECT_NEAR(patch.at(3, 1), 0.375, 1e-12);
}

TEST(CoveragePatch, ClipsPolygonsThatCrossTheBorder) {
  // A triangle far larger than the patch: every pixel of the patch lies inside it.
  CoveragePatch patch;
  patch.reset(10, 20, 4, 3);
  patch.add_polygon({{-100, -100}, {300, -100}, {0, 300}}, 2.0);
  patch.resolve();
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(patch.at(i, j), 2.0, 1e-9) << i << "," << j;
  }
}

RC_GTEST_PROP(CoveragePatch, AreaOfRandomConvexPolygonsIsExact, ()) {
  const int n = *rc::gen::inRange(3, 40);
  const double cx = *rc::gen::inRange(0, 1000) / 100.0, cy = *rc::gen::inRange(0, 1000) / 100.0;
  const double rad = *rc::gen::inRange(5, 400) / 100.0;
  const double turn = *rc::gen::inRange(0, 628) / 100.0;
  std::vector<Eigen::Vector2d> poly;
  for (int k = 0; k < n; ++k) {
    const double phi = turn + 2 * M_PI * k / n;
    poly.emplace_back(cx + rad * std::cos(phi), cy + rad * std::sin(phi));
  }
  if (*rc::gen::arbitrary<bool>()) std::reverse(poly.begin(), poly.end());
  double area = 0;
  for (int k = 0; k < n; ++k) area += poly[k].x() * poly[(k + 1) % n].y() - poly[(k + 1) % n].x() * poly[k].y();
  area = std::abs(area) / 2;
  CoveragePatch patch;
  patch.reset(-6, -6, 30, 30);
  patch.add_polygon(poly, 1.0);
  patch.resolve();
  double sum = 0, cmin = 0, cmax = 0;
  for (int j = 0; j < 30; ++j) {
    for (int i = 0; i < 30; ++i) {
      sum += patch.at(i, j);
      cmin = std::min(cmin, patch.at(i, j));
      cmax = std::max(cmax, patch.at(i, j));
    }
  }
  RC_ASSERT(std::abs(sum - area) < 1e-9 * (1 + area));
  RC_ASSERT(cmin > -1e-12);
  RC_ASSERT(cmax < 1 + 1e-12);
}

// (a) Distortion-free pinhole: the rendered centroid is the closed-form silhouette
// centre, and the light is the ellipse's area, anywhere in the image.
RC_GTEST_PROP(SphereRender, PinholeCentroidIsTheSilhouetteCentre, ()) {
  const CameraInfo info = pinhole_752();
  const double dist = *rc::gen::inRange(30, 300) / 100.0;
  const double radius = *rc::gen::element(0.005, 0.015, 0.03);
  const double sigma = *rc::gen::element(0.5, 0.8, 1.2);
  const double f = info.fx * radius / dist;  // image radius on the axis; up to 2.3 times more in the corners
  const double margin = 3 * f + 6 * sigma + 3;
  const Eigen::Vector2d px(*rc::gen::inRange(0, 10000) / 10000.0 * (info.width - 2 * margin) + margin,
                           *rc::gen::inRange(0, 10000) / 10000.0 * (info.height - 2 * margin) + margin);
  const Eigen::Vector3d C = centre_at_pixel(info, px, dist);
  const Moments m = moments(render_sphere(info, C, radius, sigma));
  Eigen::Vector2d centre;
  double area = 0;
  RC_ASSERT(pinhole_silhouette_ellipse(info, C, radius, &centre, &area));
  RC_ASSERT((m.centroid - centre).norm() < 1e-3);
  RC_ASSERT(std::abs(m.sum - area) < 2e-4 * area);
}

// Bias of the silhouette centre over the projection of the sphere's centre, in a
// corner of a 90-degree camera at 1 m for a 3 cm sphere: about 0.17 px.
TEST(SphereRender, PinholeCornerBiasIsAsLargeAsTheFormulaSays) {
  const CameraInfo info = pinhole_752();
  const Eigen::Vector3d C = centre_at_pixel(info, {30.0, 30.0}, 1.0);
  Eigen::Vector2d centre;
  double area = 0;
  ASSERT_TRUE(pinhole_silhouette_ellipse(info, C, 0.015, &centre, &area));
  Eigen::Vector2d proj;
  ASSERT_TRUE(CameraModel(info).project(C, &proj));
  const double bias = (centre - proj).norm();
  const Moments m = moments(render_sphere(info, C, 0.015, 0.6));
  std::printf("pinhole 90deg, 3 cm sphere at 1 m near the corner: bias %.4f px, rendered %.4f px\n", bias,
              (m.centroid - proj).norm());
  EXPECT_GT(bias, 0.12);
  EXPECT_LT(bias, 0.25);
  EXPECT_NEAR((m.centroid - proj).norm(), bias, 1e-3);
  // The second-order expansion agrees with the exact formula.
  Eigen::Vector2d second_order;
  ASSERT_TRUE(silhouette_centroid_bias(LensProjector(info), C, 0.015, &second_order));
  EXPECT_NEAR((second_order - (centre - proj)).norm(), 0.0, 0.01 * bias);
}

struct BiasSweep {
  int compared = 0;        // cases where the bias is below 0.005 px
  double worst_error = 0;  // largest |centroid - OpenCV projection| among them
  double worst_model_error = 0;  // largest |centroid - (projection + bias)| / (0.01 px + 0.2 |bias|)
  double largest_bias = 0;
};

BiasSweep sweep(const CameraInfo& info) {
  BiasSweep out;
  const LensProjector model(info);
  for (double dist : {0.3, 0.7, 1.5, 3.0}) {
    for (double radius : {0.005, 0.015}) {
      const double margin = 2 * info.fx * radius / dist + 8;
      for (int iy = 0; iy <= 4; ++iy) {
        for (int ix = 0; ix <= 6; ++ix) {
          // Sub-pixel offsets that differ from cell to cell.
          const Eigen::Vector2d px(margin + (info.width - 2 * margin) * ix / 6.0 + 0.137 * ix,
                                   margin + (info.height - 2 * margin) * iy / 4.0 + 0.291 * iy);
          Eigen::Vector3d bearing;
          if (!model.unproject(px, &bearing)) continue;
          const Eigen::Vector3d C = bearing * dist;
          Eigen::Vector2d bias;
          if (!silhouette_centroid_bias(model, C, radius, &bias)) continue;
          const Moments m = moments(render_sphere(info, C, radius, 0.6));
          const Eigen::Vector2d cv_px = opencv_projection(info, C);
          out.largest_bias = std::max(out.largest_bias, bias.norm());
          // Relative to the bias: the expansion drops terms of order rho^4 and strong distortion's higher derivatives.
          out.worst_model_error =
              std::max(out.worst_model_error, (m.centroid - cv_px - bias).norm() / (0.01 + 0.2 * bias.norm()));
          if (bias.norm() < 0.005) {
            ++out.compared;
            out.worst_error = std::max(out.worst_error, (m.centroid - cv_px).norm());
          }
        }
      }
    }
  }
  return out;
}

// (b) With distortion, both models: within 0.02 px of OpenCV's projection of the
// centre wherever the closed-form bias is below 0.005 px; (c) the bias elsewhere.
void check_sweep(const char* model, const CameraInfo& info) {
  const BiasSweep s = sweep(info);
  std::printf("%s: %d cases with bias < 0.005 px, worst |centroid - OpenCV projection| %.5f px; "
              "largest bias %.4f px; worst |centroid - (projection + bias)| / (0.01 px + 0.2 |bias|) %.3f\n",
              model, s.compared, s.worst_error, s.largest_bias, s.worst_model_error);
  EXPECT_GE(s.compared, 50);
  EXPECT_LT(s.worst_error, 0.02);
  EXPECT_LT(s.worst_model_error, 1.0);
}

TEST(SphereRender, DistortedPinholeMatchesOpenCvWhereBiasIsSmall) {
  check_sweep("plumb_bob", pinhole_752(-0.28, 0.07, 0.001, -0.0005, 0.0));
}

TEST(SphereRender, FisheyeMatchesOpenCvWhereBiasIsSmall) {
  check_sweep("equidistant", fisheye_752(0.02, -0.01, 0.003, -0.001));
}

// The LED beam: flux scales with cos(view angle)^m, none from behind.
TEST(SphereRender, BeamPatternScalesTheFluxWithTheViewAngle) {
  const CameraInfo info = pinhole_752();
  const Eigen::Vector3d C(0, 0, 1);
  const double uniform = cv::sum(render_sphere(info, C, 0.015, 0.6))[0];
  const Eigen::Vector3d at_camera(0, 0, -1);
  const Eigen::Vector3d at_60(std::sin(M_PI / 3), 0, -std::cos(M_PI / 3));
  EXPECT_NEAR(cv::sum(render_sphere(info, C, 0.015, 0.6, 1, at_camera))[0], uniform, 1e-6 * uniform);
  EXPECT_NEAR(cv::sum(render_sphere(info, C, 0.015, 0.6, 1, at_60))[0], 0.5 * uniform, 1e-6 * uniform);
  EXPECT_NEAR(cv::sum(render_sphere(info, C, 0.015, 0.6, 2, at_60))[0], 0.25 * uniform, 1e-6 * uniform);
  EXPECT_EQ(cv::sum(render_sphere(info, C, 0.015, 0.6, 1, -at_camera))[0], 0.0);
}

// A painted ball (issue 19): lit by a distant light from +x (camera frame), ambient
// 0.2, 100 e/ms where it faces the light; the floor behind it gives 50 e/ms. Inside
// its image each pixel must hold 1 ms x (100 (0.2 + 0.8 max(0, n.x)) - 50): the
// floor it hides taken off, the side towards the light brighter, the far side at
// the ambient level; outside it, nothing.
TEST(SphereRender, APaintedBallIsShadedByTheLightAndHidesTheFloor) {
  const CameraInfo info = pinhole_752();
  const Eigen::Vector3d C(0, 0, 1);
  const double r = 0.05;  // an image radius of ~19 px
  Scene scene;
  scene.camera = LensProjector(info);
  scene.bodies.emplace_back();
  scene.emitters.push_back(std::make_unique<FlickerEmitter>(Flicker{}));
  scene.light_direction_W = Eigen::Vector3d::UnitX();
  scene.ambient = 0.2;
  LightSphere ball;
  ball.position_m = C;
  ball.radius_m = r;
  ball.painted = true;
  ball.paint_e_per_ms = 100;
  scene.lights.push_back(ball);
  SensorConfig flat;
  flat.background_e_per_ms = 50;
  flat.texture_contrast = 0;
  flat.prnu = 0;
  SensorModel sensor(info.width, info.height, flat, 1);
  FrameRenderer renderer(scene, RenderSettings{}, sensor);
  cv::Mat light_e(info.height, info.width, CV_32F, cv::Scalar(0));
  renderer.add_light(0, 1'000'000, &light_e);

  // The normal where pixel (x, y)'s ray meets the ball (pinhole, no distortion).
  const auto expected = [&](int x, int y) {
    const Eigen::Vector3d d = Eigen::Vector3d((x - info.cx) / info.fx, (y - info.cy) / info.fy, 1).normalized();
    const double along = d.dot(C), miss2 = C.squaredNorm() - along * along;
    const Eigen::Vector3d n = (d * (along - std::sqrt(r * r - miss2)) - C).normalized();
    return 100 * (0.2 + 0.8 * std::max(0.0, n.x())) - 50;
  };
  const int cx = 376, cy = 240;
  for (int dx : {-12, -6, 0, 6, 12}) {
    EXPECT_NEAR(light_e.at<float>(cy, cx + dx), expected(cx + dx, cy), 1.5) << "pixel " << dx << " right of the centre";
  }
  EXPECT_GT(light_e.at<float>(cy, cx + 12), 15.0f);   // the lit side, brighter than the floor
  EXPECT_NEAR(light_e.at<float>(cy, cx - 12), -30.0f, 1.5f);  // the shadowed side: ambient only
  EXPECT_EQ(light_e.at<float>(cy, cx + 40), 0.0f);   // beside the ball: the floor as it is
}

// Through a Bayer sensor (RGGB, demosaiced): a red painted ball stays red at its
// centre, the grey floor stays grey, and the frame is 8-bit BGR.
TEST(SphereRender, ABayerSensorSeesARedBallRedOnAGreyFloor) {
  const CameraInfo info = pinhole_752();
  Scene scene;
  scene.camera = LensProjector(info);
  scene.bodies.emplace_back();
  scene.emitters.push_back(std::make_unique<FlickerEmitter>(Flicker{}));
  scene.light_direction_W = Eigen::Vector3d(0, 0, -1);  // from the camera's side
  LightSphere ball;
  ball.position_m = Eigen::Vector3d(0, 0, 1);
  ball.radius_m = 0.03;
  ball.painted = true;
  ball.paint_e_per_ms = 600;
  ball.rgb = Eigen::Vector3d(0.9, 0.15, 0.1);
  scene.lights.push_back(ball);
  SensorConfig bayer;
  bayer.bayer = true;
  bayer.noise = false;
  bayer.background_e_per_ms = 200;
  bayer.texture_contrast = 0;
  bayer.prnu = 0;
  bayer.dsnu_e = 0;
  SensorModel sensor(info.width, info.height, bayer, 1);
  FrameRenderer renderer(scene, RenderSettings{}, sensor);
  cv::Mat image;
  renderer.render(0, 5'000'000, 1, &image);
  ASSERT_EQ(image.type(), CV_8UC3);
  const cv::Vec3b centre = image.at<cv::Vec3b>(240, 376), floor = image.at<cv::Vec3b>(100, 100);
  // 600 e/ms x 5 ms x 0.9 / 16 e/DN + 2: R ~170 DN facing the light; G, B ~30 and ~21.
  EXPECT_GT(centre[2], 150);
  EXPECT_LT(centre[1], 45);
  EXPECT_LT(centre[0], 35);
  // The floor: 200 e/ms x 5 ms / 16 + 2 = 64.5 DN in every channel.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(floor[c], 64, 1) << "channel " << c;
}

}  // namespace
}  // namespace tetrapulse::sim

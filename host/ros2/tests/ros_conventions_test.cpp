// ROS 2 conventions without DDS: the covariance of a known pose read the ROS way,
// stamps, names, the status as diagnostics.
#include "tetrapulse/ros2/ros_conventions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"
#include "tetrapulse/ros2/ros_names.hpp"
#include "tetrapulse/ros2/status_diagnostics.hpp"

namespace tetrapulse::ros2 {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

Matrix6 matrix(const std::array<double, 36>& row_major) {
  Matrix6 m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = row_major[size_t(r * 6 + c)];
  return m;
}

// A pose's error the way a ROS consumer reads PoseWithCovariance: position error
// (m) in the parent (camera) frame, then the small rotation about the parent's
// fixed X, Y, Z axes that takes the true orientation to the estimate (rad).
Vector6 ros_error(const Pose& estimate, const Pose& truth) {
  Vector6 e;
  e.head<3>() = estimate.t - truth.t;
  e.tail<3>() = so3_log(estimate.R * truth.R.transpose());
  return e;
}

// The same rotation read about the target's own (moving) axes: not what ROS means.
Vector6 body_frame_error(const Pose& estimate, const Pose& truth) {
  Vector6 e = ros_error(estimate, truth);
  e.tail<3>() = so3_log(truth.R.transpose() * estimate.R);
  return e;
}

TEST(RosPoseCovariance, MatchesTheScatterOfAKnownPoseInRosOrderAndUnits) {
  // The paper's large target 2 m in front of the wide camera, turned 120 degrees
  // about a skew axis (so that camera and target axes differ); 0.5 px of centroid
  // noise; 2000 refinements. The predicted covariance, converted, must match the
  // scatter of (position, rotation about the camera's axes) of the estimates.
  const CameraModel camera(testing::wide_plumb_bob_camera());
  const Target target = testing::hardware_target("paper-large.yaml");
  const Pose truth{so3_exp(2.0944 * Eigen::Vector3d(1, 2, 3).normalized()), Eigen::Vector3d(0.1, -0.05, 2.0)};
  const double sigma = 0.5;
  RefinementOptions options;
  options.sigma_px = sigma;

  std::mt19937_64 rng(16);
  const auto observations = [&](double noise_px) {
    const auto px = testing::observe(rng, camera, target, truth, noise_px);
    std::vector<MarkerObservation> obs;
    for (size_t i = 0; i < 4; ++i) obs.push_back({target.markers[i].position_m, px[i]});
    return obs;
  };
  const auto at_truth = refine_pose(camera, observations(0.0), truth, options);
  ASSERT_TRUE(at_truth && at_truth->has_covariance);
  const Matrix6 predicted = matrix(ros_pose_covariance(at_truth->covariance));

  const int trials = 2000;
  Matrix6 scatter = Matrix6::Zero(), body_scatter = Matrix6::Zero();
  for (int k = 0; k < trials; ++k) {
    const auto r = refine_pose(camera, observations(sigma), truth, options);
    ASSERT_TRUE(r);
    const Vector6 e = ros_error(r->pose, truth), b = body_frame_error(r->pose, truth);
    scatter += e * e.transpose() / trials;
    body_scatter += b * b.transpose() / trials;
  }
  // Variances within 20 % (2000 samples: about 3 % standard error), correlations within 0.1.
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(scatter(i, i) / predicted(i, i), 1.0, 0.2) << "ROS parameter " << i;
    for (int j = 0; j < i; ++j) {
      const double rho_s = scatter(i, j) / std::sqrt(scatter(i, i) * scatter(j, j));
      const double rho_p = predicted(i, j) / std::sqrt(predicted(i, i) * predicted(j, j));
      EXPECT_NEAR(rho_s, rho_p, 0.1) << "ROS parameters " << i << ", " << j;
    }
  }
  // Units and order as a ROS user expects: metres then radians, depth (z) the least
  // certain position straight ahead, and m^2 values of millimetre scale.
  EXPECT_GT(predicted(2, 2), 10 * predicted(0, 0));
  EXPECT_GT(predicted(2, 2), 10 * predicted(1, 1));
  EXPECT_GT(std::sqrt(predicted(2, 2)), 1e-4);
  EXPECT_LT(std::sqrt(predicted(2, 2)), 0.05);
  // The test tells conventions apart: the (w, v) order unconverted, or rotations
  // read about the target's axes, miss by far more than the tolerance.
  const Matrix6 unconverted = at_truth->covariance;
  EXPECT_GT(std::abs(scatter(2, 2) / unconverted(2, 2) - 1.0), 1.0);
  double worst_body = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < i; ++j) {
      const double rho_b = body_scatter(i, j) / std::sqrt(body_scatter(i, i) * body_scatter(j, j));
      const double rho_p = predicted(i, j) / std::sqrt(predicted(i, i) * predicted(j, j));
      worst_body = std::max(worst_body, std::abs(rho_b - rho_p));
    }
  }
  EXPECT_GT(worst_body, 0.3) << "rotations about the target's axes correlate with position differently";
}

TEST(RosPoseCovariance, IsABlockSwapWithItsInverse) {
  Matrix6 c;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) c(r, k) = 10 * r + k;
  const std::array<double, 36> ros = ros_pose_covariance(c);
  EXPECT_EQ(ros[0], c(3, 3));   // x, x  <- v_x, v_x
  EXPECT_EQ(ros[5], c(3, 2));   // x, rotation about Z  <- v_x, w_z
  EXPECT_EQ(ros[21], c(0, 0));  // rotation about X, X  <- w_x, w_x
  EXPECT_EQ(ros[35], c(2, 2));
  EXPECT_EQ(wv_covariance(ros), c);
}

TEST(RosTime, SplitsNanosecondsWithFloorDivision) {
  EXPECT_EQ(ros_time(0).sec, 0);
  EXPECT_EQ(ros_time(1'500'000'001).sec, 1);
  EXPECT_EQ(ros_time(1'500'000'001).nanosec, 500'000'001u);
  EXPECT_EQ(ros_time(-1).sec, -1);
  EXPECT_EQ(ros_time(-1).nanosec, 999'999'999u);
  for (int64_t ns : {int64_t(0), int64_t(4'000'000), int64_t(-2'999'999'999), int64_t(1'767'225'600'123'456'789)}) {
    EXPECT_EQ(nanoseconds(ros_time(ns)), ns) << ns;
  }
  EXPECT_EQ(ros_time(int64_t(1) << 62).sec, std::numeric_limits<int32_t>::max());
}

TEST(RosNames, TopicsFramesAndNodesOfANamespace) {
  EXPECT_EQ(pose_topic("/", 3), "/tetrapulse/target_3/pose");
  EXPECT_EQ(pose_topic("/cam_b", 3), "/cam_b/tetrapulse/target_3/pose");
  EXPECT_EQ(status_topic("/"), "/tetrapulse/status");
  EXPECT_EQ(status_topic("/robot/cam"), "/robot/cam/tetrapulse/status");
  EXPECT_EQ(child_frame_id("/", 12), "tetrapulse/target_12");
  EXPECT_EQ(child_frame_id("/cam_b", 12), "cam_b/tetrapulse/target_12");
  EXPECT_EQ(dds_topic(kTfTopic), "rt/tf");
  EXPECT_EQ(dds_topic(pose_topic("/", 1)), "rt/tetrapulse/target_1/pose");
  EXPECT_EQ(default_node_name("cam-0.left"), "tetrapulse_cam_0_left");
  EXPECT_EQ(default_node_name(""), "tetrapulse_camera");
}

TEST(RosNames, RefusesWhatRos2Refuses) {
  EXPECT_TRUE(check_node_name("tetrapulse_cam0"));
  for (const char* bad : {"", "0cam", "cam-0", "cam/0", "cam 0"}) EXPECT_FALSE(check_node_name(bad)) << bad;
  EXPECT_TRUE(check_namespace("/"));
  EXPECT_TRUE(check_namespace("/robot/cam_b"));
  for (const char* bad : {"", "cam", "/cam/", "//", "/1cam", "/cam-b"}) EXPECT_FALSE(check_namespace(bad)) << bad;
  EXPECT_TRUE(check_frame_id("paper_cam"));
  EXPECT_TRUE(check_frame_id("robot/cam_0"));
  for (const char* bad : {"", "/cam", "a b", "cam\t"}) EXPECT_FALSE(check_frame_id(bad)) << bad;
  const auto e = check_namespace("cam");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("'cam'"), std::string::npos) << e.error().message;
}

TEST(StatusDiagnostics, OneEntryForTheLocalizerAndOnePerBoard) {
  LocalizerStatus s;
  s.rig_time_ns = 5'000'000'000;
  s.frames_matched = 500;
  s.frames_dropped = 2;
  s.targets_with_pose = {1, 3};
  DurationStats d;
  d.add(2'000'000);
  d.add(4'000'000);
  s.processing = d;
  s.boards.push_back({1, "can:can0:1", BoardSyncState::kSynchronized, int64_t(-1200), 3.5});
  s.boards.push_back({3, "can:can0:3", BoardSyncState::kLost, std::nullopt, std::nullopt});
  const auto e = status_diagnostics(s, "tetrapulse_cam", "cam", 0);
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].name, "tetrapulse_cam: localizer");
  EXPECT_EQ(e[0].hardware_id, "cam");
  EXPECT_EQ(e[0].level, kDiagnosticOk);
  const auto value = [](const DiagnosticEntry& x, const std::string& key) {
    for (const auto& [k, v] : x.values)
      if (k == key) return v;
    return std::string("(none)");
  };
  EXPECT_EQ(value(e[0], "frames_matched"), "500");
  EXPECT_EQ(value(e[0], "frames_dropped"), "2");
  EXPECT_EQ(value(e[0], "targets_with_pose"), "1 3");
  EXPECT_EQ(value(e[0], "processing_mean_ms"), "3.000");
  EXPECT_EQ(value(e[0], "processing_max_ms"), "4.000");
  EXPECT_EQ(value(e[0], "latency_mean_ms"), "(none)");
  EXPECT_EQ(value(e[0], "queue_drops"), "(none)") << "a replay has no live counters";
  EXPECT_EQ(e[1].name, "tetrapulse_cam: board can:can0:1");
  EXPECT_EQ(e[1].level, kDiagnosticOk);
  EXPECT_EQ(value(e[1], "offset_ns"), "-1200");
  EXPECT_EQ(value(e[1], "rate_ppm"), "3.500");
  EXPECT_EQ(e[2].level, kDiagnosticError);
  EXPECT_EQ(value(e[2], "offset_ns"), "(none)");
  // Frames dropped in this window make the localizer WARN.
  EXPECT_EQ(status_diagnostics(s, "n", "cam", 1)[0].level, kDiagnosticWarn);

  // Live: the loop's counters beside the totals, and its latency.
  s.live = LiveFrameCounters{497, 1, 2, 3, 4};
  s.latency = d;
  const auto live = status_diagnostics(s, "n", "cam", 0)[0];
  EXPECT_EQ(value(live, "frames_localized"), "497");
  EXPECT_EQ(value(live, "queue_drops"), "1");
  EXPECT_EQ(value(live, "bad_buffers"), "2");
  EXPECT_EQ(value(live, "exposures_without_frame"), "3");
  EXPECT_EQ(value(live, "frames_without_exposure"), "4");
  EXPECT_EQ(value(live, "latency_last_ms"), "4.000");
}

}  // namespace
}  // namespace tetrapulse::ros2

// Evaluation against ground truth: errors, misidentified rows, coverage and
// identification latency, on a small dataset whose truth is known.
#include "tetrapulse/datasets/pose_evaluation.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>

#include <unistd.h>

#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 20;
constexpr int64_t kPeriod = 10'000'000;

// Two passive targets side by side, 1.2 m in front of the camera, for 20 frames.
class PoseEvaluationTest : public ::testing::Test {
 protected:
  PoseEvaluationTest() {
    TargetsFile targets;
    targets.modulation.kind = ModulationKind::kConstant;
    for (int id : {1, 2}) {
      Target t = testing::hardware_target("paper-large.yaml");
      t.id = id;
      targets.targets.push_back(t);
    }
    const CameraInfo camera = testing::wide_plumb_bob_camera();
    auto w = RigDatasetWriter::create(dir.string(), camera, targets);
    EXPECT_TRUE(w);
    const cv::Mat dark(camera.height, camera.width, CV_8UC1, cv::Scalar(0));
    for (int k = 0; k < kFrames; ++k) {
      EXPECT_TRUE(w->add_frame(k, k * kPeriod, 2'000'000, dark));
      for (int id : {1, 2}) w->add_groundtruth(GroundTruthRecord{k, id, PoseFields::from(truth(id))});
    }
    EXPECT_TRUE(w->finish());
    auto d = RigDataset::open(dir.string());
    EXPECT_TRUE(d) << d.error().what();
    if (d) dataset = std::move(*d);
  }
  ~PoseEvaluationTest() override { fs::remove_all(dir); }

  static Pose truth(int id) {
    return Pose{so3_exp(Eigen::Vector3d(M_PI, 0, 0)), Eigen::Vector3d(id == 1 ? -0.3 : 0.3, 0, 1.2)};
  }
  static PoseRecord row(int64_t frame, int id, const Pose& pose) {
    return PoseRecord{frame, frame * kPeriod + 1'000'000, id, PoseFields::from(pose), 4, 0.1};
  }

  fs::path dir = fs::temp_directory_path() / ("tp_pose_evaluation_" + std::to_string(::getpid()));
  std::optional<RigDataset> dataset;
};

TEST_F(PoseEvaluationTest, ErrorsCoverageAndLatencyOfAPerfectRunStartingLate) {
  std::vector<PoseRecord> rows;
  for (int k = 3; k < kFrames; ++k) {
    Pose p = truth(1);
    p.t.x() += 0.002;  // 2 mm off
    rows.push_back(row(k, 1, p));
  }
  ASSERT_TRUE(dataset);
  auto e = evaluate_poses(*dataset, rows, "poses.csv");
  ASSERT_TRUE(e) << e.error().what();
  const TargetEvaluation& one = e->targets[0];
  EXPECT_EQ(one.rows, size_t(kFrames - 3));
  EXPECT_NEAR(one.position_m.mean, 0.002, 1e-9);
  EXPECT_NEAR(one.orientation_rad.max, 0, 1e-9);
  EXPECT_EQ(one.misidentified, 0u);
  EXPECT_EQ(one.first_latency_frames.value_or(-1), 3);
  EXPECT_DOUBLE_EQ(one.coverage(), 1.0);
  // Target 2 was never reported: its whole visibility is latency, nothing covered.
  const TargetEvaluation& two = e->targets[1];
  EXPECT_EQ(two.rows, 0u);
  EXPECT_EQ(two.first_latency_frames.value_or(-1), kFrames);
  EXPECT_EQ(two.max_latency_frames, kFrames);
}

TEST_F(PoseEvaluationTest, SwappedIdentitiesAreMisidentifications) {
  std::vector<PoseRecord> rows;
  for (int k = 0; k < kFrames; ++k) {
    rows.push_back(row(k, 1, truth(k == 7 ? 2 : 1)));  // frame 7: target 2's pose named 1
    rows.push_back(row(k, 2, truth(2)));
  }
  rows.push_back(row(9, 5, truth(1)));  // a target not in targets.yaml
  ASSERT_TRUE(dataset);
  auto e = evaluate_poses(*dataset, rows, "poses.csv");
  ASSERT_TRUE(e) << e.error().what();
  EXPECT_EQ(e->targets[0].misidentified, 1u);
  EXPECT_EQ(e->targets[1].misidentified, 0u);
  EXPECT_EQ(e->overall.misidentified, 2u);
}

TEST_F(PoseEvaluationTest, ARowForAFrameNotInTheDatasetIsAnError) {
  ASSERT_TRUE(dataset);
  auto e = evaluate_poses(*dataset, {row(kFrames + 5, 1, truth(1))}, "poses.csv");
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().what().find("poses.csv"), std::string::npos) << e.error().what();
}

}  // namespace
}  // namespace tetrapulse

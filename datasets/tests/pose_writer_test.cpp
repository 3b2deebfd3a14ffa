// Writing poses: poses.csv reads back exactly (the contract), TUM splits by
// target, JSON lines carry status and covariance; nothing is left half-written.
#include "tetrapulse/datasets/pose_writer.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class PoseWriterTest : public ::testing::Test {
 protected:
  PoseWriterTest() {
    fs::create_directories(dir);
    for (int id : {3, 8}) {
      Target t;
      t.id = id;
      targets.targets.push_back(t);
    }
  }
  ~PoseWriterTest() override { fs::remove_all(dir); }

  static TargetPose pose(int id, double x) {
    TargetPose p;
    p.target_id = id;
    p.pose = Pose{so3_exp(Eigen::Vector3d(0.1, -0.2, 0.3 + x)), Eigen::Vector3d(x, 0.25, 1.5)};
    p.markers = 4 - (id == 8);
    p.status = id == 8 ? PoseStatus::kThreeMarkers : PoseStatus::kAllMarkers;
    p.rms_px = 0.125 + x;
    if (id == 3) {
      p.covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e-6;
      p.has_covariance = true;
    }
    return p;
  }

  static TargetPose at(int64_t mid_exposure_ns, TargetPose p) {
    p.mid_exposure_ns = mid_exposure_ns;
    return p;
  }

  fs::path dir = fs::temp_directory_path() / ("tp_pose_writer_" + std::to_string(::getpid()));
  TargetsFile targets;
};

TEST_F(PoseWriterTest, CsvReadsBackExactly) {
  const std::string path = (dir / "poses.csv").string();
  auto w = PoseWriter::open(path, PoseFormat::kCsv, targets);
  ASSERT_TRUE(w) << w.error().what();
  ASSERT_TRUE(w->write(0, at(5'000'000, pose(3, 0.1))));
  ASSERT_TRUE(w->write(1, at(15'000'000, pose(8, 0.2))));
  // Nothing but the header reaches the file until the frame is flushed; then whole rows.
  EXPECT_EQ(read_poses_csv(path).value_or(std::vector<PoseRecord>(9)).size(), 0u);
  ASSERT_TRUE(w->flush());
  auto flushed = read_poses_csv(path);
  ASSERT_TRUE(flushed) << flushed.error().what();
  EXPECT_EQ(flushed->size(), 2u);
  ASSERT_TRUE(w->close());
  auto rows = read_poses_csv(path);
  ASSERT_TRUE(rows) << rows.error().what();
  ASSERT_EQ(rows->size(), 2u);
  const PoseRecord& r = (*rows)[1];
  EXPECT_EQ(r.frame, 1);
  EXPECT_EQ(r.timestamp_ns, 15'000'000);
  EXPECT_EQ(r.target, 8);
  EXPECT_EQ(r.markers, 3);
  EXPECT_DOUBLE_EQ(r.reprojection_px, 0.325);
  const Pose p = pose(8, 0.2).pose;
  EXPECT_EQ(r.pose.t, p.t);
  EXPECT_LT(rotation_angle_between(r.pose.pose().R, p.R), 1e-12);
}

TEST_F(PoseWriterTest, TumWritesOneTrajectoryPerTarget) {
  const std::string path = (dir / "traj.txt").string();
  auto w = PoseWriter::open(path, PoseFormat::kTum, targets);
  ASSERT_TRUE(w) << w.error().what();
  ASSERT_TRUE(w->write(0, at(5'000'000, pose(3, 0.1))));
  ASSERT_TRUE(w->write(0, at(5'000'000, pose(8, 0.2))));
  ASSERT_TRUE(w->write(1, at(15'000'000, pose(3, 0.3))));
  ASSERT_TRUE(w->close());
  const std::string three = read(dir / "traj.target3.txt"), eight = read(dir / "traj.target8.txt");
  EXPECT_EQ(std::count(three.begin(), three.end(), '\n') - (three.rfind('#', 0) == 0), 2);
  EXPECT_NE(three.find("0.015"), std::string::npos) << three;  // seconds of mid-exposure
  EXPECT_NE(eight.find("0.2"), std::string::npos) << eight;
}

TEST_F(PoseWriterTest, JsonLinesCarryStatusAndCovariance) {
  const std::string path = (dir / "poses.jsonl").string();
  auto w = PoseWriter::open(path, PoseFormat::kJsonLines, targets);
  ASSERT_TRUE(w) << w.error().what();
  ASSERT_TRUE(w->write(0, at(5'000'000, pose(3, 0.1))));
  ASSERT_TRUE(w->write(0, at(5'000'000, pose(8, 0.2))));
  ASSERT_TRUE(w->close());
  std::istringstream in(read(path));
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_NE(first.find("\"target\":3"), std::string::npos) << first;
  EXPECT_NE(first.find("\"covariance\":["), std::string::npos) << first;
  EXPECT_NE(second.find("\"covariance\":null"), std::string::npos) << second;
  EXPECT_NE(second.find("three"), std::string::npos) << second;  // status of a three-marker pose
}

TEST_F(PoseWriterTest, AnUnwritableFolderIsAnError) {
  auto w = PoseWriter::open((dir / "no" / "such" / "poses.csv").string(), PoseFormat::kCsv, targets);
  ASSERT_FALSE(w);
  EXPECT_NE(w.error().what().find("poses.csv"), std::string::npos) << w.error().what();
}

}  // namespace
}  // namespace tetrapulse

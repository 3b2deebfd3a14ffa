// tetrapulse demo as users run it: --scenario picks the scenarios (built-in names or
// files), a bad name is refused before anything is simulated, and passive, colour
// and mixed rigs run end to end with their overlays in colour.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "cli_run.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;
using cli::testing::CliRun;
using TempDir = cli::testing::CliTempDir;

CliRun run_cli(const std::string& args) {
  static const TempDir io("demo_io");
  return cli::testing::run_cli(io, args);
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DemoCommand, UnknownScenarioIsRefusedBeforeAnythingRuns) {
  const TempDir dir("demo_bad");
  const CliRun r = run_cli("demo --scenario paper-exp1 --scenario no-such-rig --seconds 0.2 --out " + dir.path("out"));
  EXPECT_EQ(r.exit, 2) << r.out << r.err;
  EXPECT_EQ(r.err_lines(), 1u) << r.err;
  EXPECT_NE(r.err.find("no-such-rig"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path("out/paper-exp1"))) << "simulated before the list was checked";
}

// The colour rig's frames are BGR: the overlay keeps them in colour (the red
// painted balls stay red), the mixed rig names its three robots, each found.
TEST(DemoCommand, RunsColourAndMixedRigsEndToEnd) {
  const TempDir dir("demo_rigs");
  const std::string out = dir.path("out");
  const CliRun r = run_cli("demo --quiet --scenario colour --scenario mixed --seconds 1 --out " + out);
  ASSERT_EQ(r.exit, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("colour (30 frames)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mixed (30 frames)"), std::string::npos) << r.out;
  for (const char* name : {"colour", "mixed"})
    for (const char* file : {"poses.csv", "trajectory.png", "overlay.png", "overlay.avi"})
      EXPECT_TRUE(fs::exists(fs::path(out) / name / file)) << name << "/" << file;
  const std::string table = read(out + "/accuracy.md");
  EXPECT_NE(table.find("colour"), std::string::npos) << table;
  EXPECT_NE(table.find("mixed"), std::string::npos) << table;
  // Every mixed robot has poses.
  const std::string poses = read(out + "/mixed/poses.csv");
  for (const char* id : {",1,", ",2,", ",3,"}) EXPECT_NE(poses.find(id), std::string::npos) << "target" << id;
  // Red pixels (R well above G and B) in the colour overlay strip: the frames kept their colour.
  const cv::Mat strip = cv::imread(out + "/colour/overlay.png");
  ASSERT_FALSE(strip.empty());
  int red = 0;
  for (int y = 0; y < strip.rows; ++y)
    for (int x = 0; x < strip.cols; ++x) {
      const cv::Vec3b p = strip.at<cv::Vec3b>(y, x);
      red += p[2] > p[1] + 40 && p[2] > p[0] + 40;
    }
  EXPECT_GT(red, 100);
}

}  // namespace
}  // namespace tetrapulse

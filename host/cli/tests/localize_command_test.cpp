// `tetrapulse localize` and `eval` as users run them: a dataset localizes; bad
// input (missing or garbled camera.yaml or targets.yaml) gives one line naming
// the file and line, exit code 3, and never a crash; a broken frame (wrong image
// size, a duplicate, unsorted or garbled frames.csv line) costs only itself:
// named on stderr, the rest localized, exit code 8.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "cli_run.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;
using TempDir = cli::testing::CliTempDir;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout, then stderr
};

CliRun run_cli(const std::string& args) {
  static const TempDir io("localize_io");
  const cli::testing::CliRun r = cli::testing::run_cli(io, args);
  return CliRun{r.exit, r.out + r.err};
}

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t lines(const std::string& text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

// One small dataset rendered once (paper-exp1, 24 frames: the target is identified
// within its 12-bit codes), copied for each case.
class LocalizeCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    source_ = new TempDir("localize_source");
    const CliRun r = run_cli("sim paper-exp1 --frames 24 --seed 3 --out " + source_->path("data"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete source_;
    source_ = nullptr;
  }

  // A fresh copy of the dataset.
  std::string copy() {
    const std::string to = dir_.path("data" + std::to_string(copies_++));
    fs::copy(source_->path("data"), to, fs::copy_options::recursive);
    return to;
  }

  // localize on `data` must fail with exit 3 and one line that contains every `needle`.
  void expect_bad_input(const std::string& data, std::initializer_list<std::string> needles) {
    const CliRun r = run_cli("localize " + data + " --quiet --out " + dir_.path("poses.csv"));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_EQ(r.output.rfind("tetrapulse localize: ", 0), 0u) << r.output;
    for (const std::string& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << n << " in " << r.output;
  }

  // localize on `data` must skip one frame naming every `needle` on one line, exit 8,
  // and write the poses of the other frames.
  void expect_skipped(const std::string& data, std::initializer_list<std::string> needles) {
    const std::string poses = dir_.path("poses.csv");
    const CliRun r = run_cli("localize " + data + " --quiet --out " + poses);
    EXPECT_EQ(r.exit_code, 8) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_EQ(r.output.rfind("tetrapulse localize: skipped ", 0), 0u) << r.output;
    for (const std::string& n : needles) EXPECT_NE(r.output.find(n), std::string::npos) << n << " in " << r.output;
    auto rows = read_poses_csv(poses);
    ASSERT_TRUE(rows) << rows.error().what();
    EXPECT_GT(rows->size(), 0u);
  }

  static TempDir* source_;
  TempDir dir_{"localize"};
  int copies_ = 0;
};
TempDir* LocalizeCommand::source_ = nullptr;

TEST_F(LocalizeCommand, LocalizesAndEvaluatesADataset) {
  const std::string data = copy(), poses = dir_.path("poses.csv");
  const CliRun r = run_cli("localize " + data + " --quiet --out " + poses);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read(poses).rfind("frame,timestamp_ns,target,x,y,z,qx,qy,qz,qw,markers,reprojection_px\n", 0), 0u);
  EXPECT_GT(lines(read(poses)), 10u);
  const CliRun e = run_cli("eval " + data + " " + poses + " --max-misidentified 0 --max-position-error 0.01");
  EXPECT_EQ(e.exit_code, 0) << e.output;
  // Other formats.
  for (const char* format : {"tum", "jsonl"}) {
    const CliRun f = run_cli("localize " + data + " --quiet --format " + format + " --out " + dir_.path(format));
    EXPECT_EQ(f.exit_code, 0) << f.output;
    EXPECT_GT(lines(read(dir_.path(format))), 10u) << format;
  }
}

// --overlay: a video with one frame per frame localized, the poses drawn in colour
// over the grey frames (the measured markers and id in blue: B well above R).
TEST_F(LocalizeCommand, OverlayVideoHasEveryFrameWithThePosesDrawn) {
  const std::string data = copy(), video = dir_.path("overlay.avi");
  const CliRun r = run_cli("localize " + data + " --out " + dir_.path("poses.csv") + " --overlay " + video);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("overlay video: 24 frames written to " + video), std::string::npos) << r.output;
  cv::VideoCapture in(video);
  ASSERT_TRUE(in.isOpened()) << video;
  EXPECT_EQ(in.get(cv::CAP_PROP_FRAME_COUNT), 24.0);
  int frames = 0, drawn = 0;
  for (cv::Mat f; in.read(f); ++frames) {
    ASSERT_EQ(f.size(), cv::Size(752, 480));
    ASSERT_EQ(f.channels(), 3);
    int blue = 0;
    for (int y = 0; y < f.rows; ++y)
      for (int x = 0; x < f.cols; ++x) {
        const cv::Vec3b p = f.at<cv::Vec3b>(y, x);
        blue += p[0] > p[2] + 80;
      }
    drawn += blue > 50;
  }
  EXPECT_EQ(frames, 24);
  EXPECT_GT(drawn, 10) << "frames with poses drawn";
  const CliRun bad = run_cli("localize " + data + " --quiet --out " + dir_.path("p2.csv") + " --overlay " + dir_.path("x.txt"));
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("x.txt"), std::string::npos) << bad.output;
}

TEST_F(LocalizeCommand, MissingFilesAreNamed) {
  for (const char* file : {"camera.yaml", "targets.yaml", "frames.csv"}) {
    const std::string data = copy();
    fs::remove(data + "/" + file);
    expect_bad_input(data, {file});
  }
  expect_bad_input(dir_.path("no-such-folder"), {"no-such-folder"});
}

TEST_F(LocalizeCommand, GarbledCameraYamlNamesFileAndLine) {
  const std::string data = copy();
  std::string text = read(data + "/camera.yaml");
  const size_t at = text.find("image_width:");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at) - at, "image_width: wide");
  const int line = int(std::count(text.begin(), text.begin() + long(at), '\n')) + 1;
  std::ofstream(data + "/camera.yaml") << text;
  expect_bad_input(data, {"camera.yaml:" + std::to_string(line), "image_width"});
}

TEST_F(LocalizeCommand, GarbledTargetsYamlNamesFileAndLine) {
  const std::string data = copy();
  std::string text = read(data + "/targets.yaml");
  const size_t at = text.find("code:");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at) - at, "code: \"10x1\"");
  const int line = int(std::count(text.begin(), text.begin() + long(at), '\n')) + 1;
  std::ofstream(data + "/targets.yaml") << text;
  expect_bad_input(data, {"targets.yaml:" + std::to_string(line), "code"});
}

// Keeps the first `count` rows of frames.csv.
void keep_frames(const std::string& data, int count) {
  std::istringstream in(read(data + "/frames.csv"));
  std::string out, line;
  for (int n = 0; n <= count && std::getline(in, line); ++n) out += line + "\n";
  std::ofstream(data + "/frames.csv") << out;
}

TEST_F(LocalizeCommand, EveryTruncationOfTheYamlFilesIsRefusedCleanly) {
  // Cut each file after every line: a clear error (exit 3, one line naming the
  // file) or, where the cut leaves a complete file, success; never a crash.
  for (const char* file : {"camera.yaml", "targets.yaml"}) {
    const std::string data = copy();
    keep_frames(data, 2);  // quick runs where the cut leaves a complete file
    const std::string text = read(data + "/" + file);
    for (size_t end = text.find('\n'); end != std::string::npos; end = text.find('\n', end + 1)) {
      std::ofstream(data + "/" + file) << text.substr(0, end + 1);
      const CliRun r = run_cli("localize " + data + " --quiet --out " + dir_.path("poses.csv"));
      ASSERT_TRUE(r.exit_code == 3 || r.exit_code == 0 || r.exit_code == 1) << file << " to " << end << ": " << r.output;
      if (r.exit_code == 3) {
        EXPECT_EQ(lines(r.output), 1u) << r.output;
        EXPECT_NE(r.output.find(file), std::string::npos) << r.output;
      }
    }
  }
}

TEST_F(LocalizeCommand, WrongImageSizeNamesTheImage) {
  const std::string data = copy();
  cv::imwrite(data + "/frames/000005.png", cv::Mat(480, 640, CV_8UC1, cv::Scalar(10)));
  expect_skipped(data, {"000005.png", "640x480", "752x480"});
}

// frames.csv with row `row` (1 = the first after the header) rewritten by `edit`.
void edit_frames(const std::string& data, int row, const std::function<std::string(const std::string&)>& edit) {
  std::istringstream in(read(data + "/frames.csv"));
  std::string out, line;
  for (int n = 0; std::getline(in, line); ++n) out += (n == row ? edit(line) : line) + "\n";
  std::ofstream(data + "/frames.csv") << out;
}

// Replaces the timestamp (second field) of a frames.csv row.
std::string with_timestamp(const std::string& row, const std::string& timestamp) {
  const size_t a = row.find(','), b = row.find(',', a + 1);
  return row.substr(0, a + 1) + timestamp + row.substr(b);
}

std::string timestamp_of(const std::string& data, int row) {
  std::istringstream in(read(data + "/frames.csv"));
  std::string line;
  for (int n = 0; n <= row; ++n) std::getline(in, line);
  const size_t a = line.find(','), b = line.find(',', a + 1);
  return line.substr(a + 1, b - a - 1);
}

TEST_F(LocalizeCommand, DuplicateTimestampNamesFramesCsvLine) {
  const std::string data = copy();
  const std::string previous = timestamp_of(data, 3);
  edit_frames(data, 4, [&](const std::string& row) { return with_timestamp(row, previous); });
  expect_skipped(data, {"frames.csv:5", "timestamp_ns", "duplicates"});
}

TEST_F(LocalizeCommand, UnsortedTimestampsNameFramesCsvLine) {
  const std::string data = copy();
  const std::string earlier = timestamp_of(data, 2);
  edit_frames(data, 6, [&](const std::string& row) { return with_timestamp(row, earlier); });
  expect_skipped(data, {"frames.csv:7", "timestamp_ns", "earlier"});
}

TEST_F(LocalizeCommand, GarbledTimestampNamesFramesCsvLine) {
  const std::string data = copy();
  edit_frames(data, 2, [&](const std::string& row) { return with_timestamp(row, "soon"); });
  expect_skipped(data, {"frames.csv:3", "timestamp_ns"});
}

TEST_F(LocalizeCommand, EvalRefusesAGarbledPosesFile) {
  const std::string data = copy();
  const std::string poses = dir_.file("poses.csv",
                                       "frame,timestamp_ns,target,x,y,z,qx,qy,qz,qw,markers,reprojection_px\n"
                                       "0,5000000,1,0.1,0.2,nan?,0,0,0,1,4,0.2\n");
  const CliRun r = run_cli("eval " + data + " " + poses);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_EQ(lines(r.output), 1u) << r.output;
  EXPECT_NE(r.output.find("poses.csv:2"), std::string::npos) << r.output;
}

// Boards that run free (frequency: up to 200 ppm off): over 300 frames their
// square waves drift off the nominal clock, so the frames that truly have three
// markers lit are known only from the clocks in the scenario.yaml sim writes.
// Counted by the nominal clocks the coverage reads about 80 %.
TEST(EvalCommand, CountsFreeRunningBoardsByTheClocksOfTheScenarioTheDatasetKeeps) {
  const TempDir dir("eval_clocks");
  const std::string data = dir.path("data"), poses = dir.path("poses.csv");
  ASSERT_EQ(run_cli("sim frequency --frames 300 --out " + data).exit_code, 0);
  ASSERT_EQ(run_cli("localize " + data + " --quiet --out " + poses).exit_code, 0);
  const CliRun with_clocks = run_cli("eval " + data + " " + poses + " --min-coverage 0.99 --max-misidentified 0");
  EXPECT_EQ(with_clocks.exit_code, 0) << with_clocks.output;
  fs::rename(data + "/scenario.yaml", dir.path("scenario.yaml"));
  const CliRun nominal = run_cli("eval " + data + " " + poses + " --min-coverage 0.99");
  EXPECT_EQ(nominal.exit_code, 6) << "the nominal clocks should miscount the lit frames:\n" << nominal.output;
  // A scenario.yaml that does not load is named; the evaluation goes on by the nominal clocks.
  std::ofstream(data + "/scenario.yaml") << "frames: [unclosed\n";
  const CliRun garbled = run_cli("eval " + data + " " + poses);
  EXPECT_EQ(garbled.exit_code, 0) << garbled.output;
  EXPECT_NE(garbled.output.find("scenario.yaml"), std::string::npos) << garbled.output;
  EXPECT_NE(garbled.output.find("nominal clocks"), std::string::npos) << garbled.output;
}

}  // namespace
}  // namespace tetrapulse

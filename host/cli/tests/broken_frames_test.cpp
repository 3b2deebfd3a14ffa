// Reliability (docs/reliability.md): broken input costs only itself and output is
// never lost, through the real `tetrapulse` binary on a simulated dataset.
//  - BrokenFrames: a 300-frame dataset with an undecodable, a truncated, an empty
//    and a missing image and a garbled frames.csv line: each named on stderr,
//    counted, exit 8, and the poses of nearly every other frame.
//  - StopSignal: SIGINT 2.5 s into a long localize (SIGTERM at the first row):
//    the process ends on its own, exit 0, and poses.csv has whole rows only.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;
using cli::testing::CliRun;
using cli::testing::CliTempDir;
using cli::testing::run_cli;
using cli::testing::slurp;

constexpr int kFrames = 300;

// paper-exp1, 300 frames, rendered once for the suite.
class BrokenInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new CliTempDir("broken_frames");
    const CliRun r = run_cli(*dir_, "sim paper-exp1 --frames " + std::to_string(kFrames) + " --seed 5 --out " +
                                        dir_->path("intact"));
    ASSERT_EQ(r.exit, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string copy(const std::string& name) {
    const std::string to = dir_->path(name);
    fs::remove_all(to);
    fs::copy(dir_->path("intact"), to, fs::copy_options::recursive);
    return to;
  }
  static CliTempDir* dir_;
};
CliTempDir* BrokenInput::dir_ = nullptr;

std::string image(const std::string& data, int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "/frames/%06d.png", frame);
  return data + name;
}

// Rows of a poses file; fails the test when it does not parse.
size_t pose_rows(const std::string& path) {
  auto rows = read_poses_csv(path);
  EXPECT_TRUE(rows) << rows.error().what();
  return rows ? rows->size() : 0;
}

TEST_F(BrokenInput, BrokenFramesCostOnlyThemselves) {
  const CliRun intact = run_cli(*dir_, "localize " + dir_->path("intact") + " --out " + dir_->path("intact.csv"));
  ASSERT_EQ(intact.exit, 0) << intact.err;
  const size_t intact_rows = pose_rows(dir_->path("intact.csv"));
  ASSERT_GT(intact_rows, size_t(kFrames) * 9 / 10) << intact.err;

  const std::string data = copy("broken");
  {
    std::ofstream garbage(image(data, 60), std::ios::binary | std::ios::trunc);  // undecodable
    for (int i = 0; i < 4096; ++i) garbage.put(char((i * 7919) & 0xff));
  }
  const std::string png = slurp(image(data, 120));  // truncated: half a PNG
  std::ofstream(image(data, 120), std::ios::binary | std::ios::trunc) << png.substr(0, png.size() / 2);
  std::ofstream(image(data, 180), std::ios::trunc).close();  // empty
  fs::remove(image(data, 240));                               // missing
  // frames.csv line 272 (frame 270): a garbled timestamp.
  std::istringstream in(slurp(data + "/frames.csv"));
  std::string csv, line;
  for (int n = 1; std::getline(in, line); ++n) {
    const size_t a = line.find(','), b = line.find(',', a + 1);
    if (n == 272) line = line.substr(0, a + 1) + "soon" + line.substr(b);
    csv += line + "\n";
  }
  std::ofstream(data + "/frames.csv", std::ios::trunc) << csv;

  const CliRun r = run_cli(*dir_, "localize " + data + " --out " + dir_->path("broken.csv"));
  EXPECT_EQ(r.exit, 8) << r.err;
  for (const std::string& named : {image(data, 60) + ": cannot decode", image(data, 120) + ": cannot decode",
                                   image(data, 180) + ": image of frame 180 is empty",
                                   image(data, 240) + ": image of frame 240 is missing",
                                   data + "/frames.csv:272: timestamp_ns"}) {
    EXPECT_NE(r.err.find("skipped " + named), std::string::npos) << named << " in\n" << r.err;
  }
  EXPECT_NE(r.err.find("295 frames, 5 skipped"), std::string::npos) << r.err;
  const size_t rows = pose_rows(dir_->path("broken.csv"));
  const double kept = double(rows) / double(intact_rows);
  std::printf("[measure] broken frames: %zu of the intact set's %zu pose rows (%.1f %%), 5 frames skipped\n", rows,
              intact_rows, 100 * kept);
  EXPECT_GE(kept, 0.97);
}

// Every line of a poses.csv: the header, then rows of 12 fields, each ending in a newline.
void expect_whole_rows(const std::string& path) {
  const std::string text = slurp(path);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n') << "the last row is cut short";
  std::istringstream in(text);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 11) << path << ":" << n + 1 << ": " << line;
    ++n;
  }
  EXPECT_GT(n, 1u);
  auto rows = read_poses_csv(path);  // every field parses
  ASSERT_TRUE(rows) << rows.error().what();
  EXPECT_EQ(rows->size(), n - 1);
}

// A long dataset without rendering one: frames.csv lists the 300 images over and over
// (frame numbers and times go on), 20 000 frames (over a minute of localizing here).
std::string long_dataset(const std::string& data) {
  auto rows = read_frames_csv(data + "/frames.csv");
  EXPECT_TRUE(rows) << rows.error().what();
  if (!rows) return data;
  const std::vector<FrameRecord> once = *rows;
  const int64_t period = once[1].timestamp_ns - once[0].timestamp_ns;
  for (int64_t k = int64_t(once.size()); k < 20'000; ++k) {
    FrameRecord f = once[size_t(k) % once.size()];
    f.frame = k;
    f.timestamp_ns = once[0].timestamp_ns + k * period;
    rows->push_back(f);
  }
  std::ofstream(data + "/frames.csv", std::ios::trunc) << format_frames_csv(*rows);
  return data;
}

struct Stopped {
  int exit = -1;  // -1: killed by the signal instead of ending on its own
  std::string err;
};

// Runs `tetrapulse localize DATA --out POSES`, waits for its first pose row, then
// until `after` has passed since the start, sends `signal` and waits for the end.
Stopped localize_and_signal(const std::string& data, const std::string& poses, const std::string& err_file,
                            int signal, std::chrono::milliseconds after) {
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (!std::freopen(err_file.c_str(), "w", stderr)) std::_Exit(126);
    ::execl(TETRAPULSE_CLI, TETRAPULSE_CLI, "localize", data.c_str(), "--out", poses.c_str(),
            static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  Stopped out;
  if (pid < 0) return out;
  // The event: the header and one row in the file (the process writes whole frames).
  bool running = true;
  for (;;) {
    const std::string text = slurp(poses);
    if (std::count(text.begin(), text.end(), '\n') >= 2) break;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      running = false;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(running) << "localize ended before its first pose row: " << slurp(err_file);
  if (running) {
    std::this_thread::sleep_until(start + after);
    ::kill(pid, signal);
    int status = 0;
    ::waitpid(pid, &status, 0);
    out.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  out.err = slurp(err_file);
  return out;
}

TEST_F(BrokenInput, SigintLeavesWholeRows) {
  const std::string data = long_dataset(copy("long_int"));
  const std::string poses = dir_->path("int.csv");
  const Stopped s = localize_and_signal(data, poses, dir_->path("int.err"), SIGINT, std::chrono::milliseconds(2500));
  EXPECT_EQ(s.exit, 0) << s.err;
  EXPECT_NE(s.err.find("stopped by a signal after "), std::string::npos) << s.err;
  expect_whole_rows(poses);
  EXPECT_NE(s.err.find(std::to_string(pose_rows(poses)) + " poses written"), std::string::npos) << s.err;
  std::printf("[measure] SIGINT after 2.5 s: %zu whole rows\n", pose_rows(poses));
}

TEST_F(BrokenInput, SigtermAtTheFirstRowLeavesWholeRows) {
  const std::string data = long_dataset(copy("long_term"));
  const std::string poses = dir_->path("term.csv");
  const Stopped s = localize_and_signal(data, poses, dir_->path("term.err"), SIGTERM, std::chrono::milliseconds(0));
  EXPECT_EQ(s.exit, 0) << s.err;
  EXPECT_NE(s.err.find("stopped by a signal after "), std::string::npos) << s.err;
  expect_whole_rows(poses);
}

}  // namespace
}  // namespace tetrapulse

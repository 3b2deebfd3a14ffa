// `tetrapulse sim` as users run it: exit codes and one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include "tetrapulse/datasets/rig_dataset.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string cmd = std::string(TETRAPULSE_CLI) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("tp_cli_sim_" + std::to_string(::getpid()) + "_" + std::to_string(n_++))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream((path_ / name).string()) << text;
    return (path_ / name).string();
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  static inline int n_ = 0;
  fs::path path_;
};

TEST(SimCommand, ListsAndPrintsTheBuiltins) {
  const CliRun list = run("sim --list");
  EXPECT_EQ(list.exit_code, 0) << list.output;
  for (const sim::BuiltinScenario& b : sim::builtin_scenarios()) EXPECT_NE(list.output.find(b.name), std::string::npos);
  const CliRun print = run("sim --print swarm");
  EXPECT_EQ(print.exit_code, 0);
  EXPECT_EQ(print.output, sim::find_builtin_scenario("swarm")->text);
  EXPECT_EQ(run("sim --print nothing-like-this").exit_code, 2);
}

TEST(SimCommand, WritesADatasetFromAPrintedScenarioFile) {
  TempDir dir;
  const std::string file = dir.file("mine.yaml", run("sim --print unsync").output);
  const CliRun r = run("sim " + file + " --out " + dir.path("out") + " --frames 5 --seed 9");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto d = RigDataset::open(dir.path("out"));
  ASSERT_TRUE(d) << d.error().what();
  EXPECT_EQ(d->frames().size(), 5u);
  EXPECT_FALSE(d->targets().timebase.synchronized);
  // A second run into the same folder needs --force.
  EXPECT_EQ(run("sim " + file + " --out " + dir.path("out") + " --frames 5").exit_code, 2);
  EXPECT_EQ(run("sim " + file + " --out " + dir.path("out") + " --frames 3 --force").exit_code, 0);
  d = RigDataset::open(dir.path("out"));
  ASSERT_TRUE(d) << d.error().what();
  EXPECT_EQ(d->frames().size(), 3u);
}

TEST(SimCommand, BadScenarioFilesGiveOneLineNamingFileLineAndField) {
  TempDir dir;
  const std::string good = sim::find_builtin_scenario("paper-exp1")->text;
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {edit("  period_ns: 10000000", "  period_ns: ten"), "frames.period_ns: expected an integer, got 'ten'"},
      {edit("kind: smooth_random", "kind: jump"), "camera.motion.kind: 'jump'"},
      {edit("  image_height: 480\n", ""), "camera.image_height: missing required field"},
      {edit("timebase:", "time_base:"), "time_base: unknown field"},
      {edit("low: 0.3", "low: 1.3"), "modulation.low: must be in [0, 1)"},
      {"frames: [", "YAML syntax"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string file = dir.file("bad" + std::to_string(i) + ".yaml", cases[i].text);
    const CliRun r = run("sim " + file + " --out " + dir.path("out" + std::to_string(i)));
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_NE(r.output.find(file + ":"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(cases[i].expected), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(dir.path("out" + std::to_string(i)))) << "nothing is written for a bad scenario";
  }
  EXPECT_EQ(run("sim " + dir.path("missing.yaml") + " --out " + dir.path("o")).exit_code, 3);
  EXPECT_EQ(run("sim paper-exp1").exit_code, 2);  // no --out
}


TEST(SimCommand, HostBoardsGiveTheSameDataset) {
  TempDir dir;
  const CliRun direct = run("sim paper-exp1 --frames 3 --out " + dir.path("direct"));
  ASSERT_EQ(direct.exit_code, 0) << direct.output;
  const CliRun host = run("sim paper-exp1 --frames 3 --host-boards --out " + dir.path("host"));
  ASSERT_EQ(host.exit_code, 0) << host.output;
  for (const char* file : {"frames.csv", "groundtruth.csv", "frames/000000.png", "frames/000002.png"}) {
    std::ifstream a(dir.path("direct") + "/" + file, std::ios::binary), b(dir.path("host") + "/" + file, std::ios::binary);
    const std::string da((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
    const std::string db((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    EXPECT_FALSE(da.empty()) << file;
    EXPECT_EQ(da, db) << file;
  }
}

}  // namespace
}  // namespace tetrapulse

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tetrapulse/datasets/dataset_io.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

class TargetCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tp_target_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliRun run(const std::string& args) const {
    const fs::path out = dir_ / "stdout", err = dir_ / "stderr";
    const std::string command = std::string(TETRAPULSE_CLI) + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(command.c_str());
    CliRun r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string source(const std::string& relative) { return std::string(TETRAPULSE_SOURCE_DIR) + "/" + relative; }

  fs::path dir_;
};

TEST_F(TargetCommand, ChecksThePapersTargetAndSaysItOvershootsD2) {
  const CliRun r = run("target check " + source("hardware/targets/paper-large.yaml"));
  EXPECT_EQ(r.exit_code, 6) << r.out << r.err;  // kExitCheckFailed: 30.0058 cm > D2 = 30 cm
  EXPECT_NE(r.out.find("s_min 0.029840 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("distances 0.150559 .. 0.300058 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL: target 0 (paper-large): d01 = 0.300058 m > D2 = 0.3 m"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("FAIL: target 0 (paper-large): h"), std::string::npos) << r.out;  // heights hold
  const CliRun json = run("target check --json " + source("hardware/targets/paper-large.yaml"));
  EXPECT_EQ(json.exit_code, 6);
  EXPECT_NE(json.out.find("\"ok\": false"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"quantity\": \"d01\""), std::string::npos) << json.out;
}

// The half-size targets (paper Sec. III-A: same proportions, half the size) at half the
// paper's limits: every distance, s_min and face height halves, and the one violation is
// the large target's d01, halved.
TEST_F(TargetCommand, ChecksThePapersHalfSizeTargetsAtHalfTheLimits) {
  for (const char* name : {"paper-half-active", "paper-half-passive"}) {
    const std::string file = source(std::string("hardware/targets/") + name + ".yaml");
    const CliRun r = run("target check --d1 0.075 --d2 0.15 --h 0.06 " + file);
    EXPECT_EQ(r.exit_code, 6) << name << "\n" << r.out << r.err;  // d01 = 15.003 cm > D2 = 15 cm
    EXPECT_NE(r.out.find("s_min 0.014920 m"), std::string::npos) << r.out;  // 0.029840 / 2
    EXPECT_NE(r.out.find("distances 0.075280 .. 0.150029 m"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("min 0.063172 m"), std::string::npos) << r.out;  // face height 0.126343 / 2 >= H
    EXPECT_NE(r.out.find(std::string("FAIL: target 0 (") + name + "): d01 = 0.150029 m > D2 = 0.15 m"),
              std::string::npos)
        << r.out;
    const size_t fail = r.out.find("FAIL");
    ASSERT_NE(fail, std::string::npos) << r.out;
    EXPECT_EQ(lines(r.out.substr(fail)), 1) << r.out;  // nothing else fails
  }
  // Marker size is the only difference between the two files: larger discs overlap more often.
  const auto overlap = [&](const char* name) {
    const CliRun r = run("target check --views 500 --d1 0.075 --d2 0.15 --h 0.06 " +
                         source(std::string("hardware/targets/") + name + ".yaml"));
    const size_t at = r.out.find("discs overlap in ");
    return at == std::string::npos ? -1.0 : std::stod(r.out.substr(at + 17));
  };
  const double active = overlap("paper-half-active"), passive = overlap("paper-half-passive");
  EXPECT_GE(active, 0.0);
  EXPECT_GT(passive, active);
}

TEST_F(TargetCommand, OptimisesAValidTargetsFileThatPassesCheck) {
  const CliRun r = run("target optimize --targets 2 --restarts 30 --seed 3 --threads 2 --out " + path("t.yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto file = read_targets_yaml(path("t.yaml"));
  ASSERT_TRUE(file) << file.error().what();
  ASSERT_EQ(file->targets.size(), 2u);
  EXPECT_EQ(file->modulation.kind, ModulationKind::kConstant);
  for (const Target& t : file->targets) {
    EXPECT_DOUBLE_EQ(t.marker_diameter_m, 0.03);
    for (const Marker& m : t.markers) EXPECT_FALSE(m.code);  // codes come from `tetrapulse codebook`
  }
  // The first line is the command that reproduces the file, with every setting.
  const std::string text = slurp(path("t.yaml"));
  EXPECT_EQ(text.rfind("# tetrapulse target optimize --targets 2 --d1 0.15 --d2 0.3 --h 0.12 --w", 0), 0u) << text;
  EXPECT_NE(text.find("--restarts 30 --seed 3 --marker-diameter 0.03 --out"), std::string::npos);
  const CliRun check = run("target check " + path("t.yaml"));
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_NE(check.out.find("OK: every distance in [D1, D2]"), std::string::npos);
}

TEST_F(TargetCommand, SameSeedWritesTheSameFileOnAnyThreadCount) {
  ASSERT_EQ(run("target optimize --restarts 40 --seed 9 --threads 1 --out " + path("a.yaml")).exit_code, 0);
  ASSERT_EQ(run("target optimize --restarts 40 --seed 9 --threads 2 --out " + path("b.yaml")).exit_code, 0);
  const std::string a = slurp(path("a.yaml")), b = slurp(path("b.yaml"));
  // Only the --out path differs.
  EXPECT_EQ(a.substr(a.find('\n')), b.substr(b.find('\n')));
}

TEST_F(TargetCommand, CommittedOptimisedTargetsPassCheck) {
  for (const char* name : {"optimised-1.yaml", "optimised-4.yaml", "optimised-8.yaml", "optimised-16.yaml"}) {
    const std::string file = source(std::string("hardware/targets/") + name);
    const CliRun r = run("target check --views 200 " + file);
    EXPECT_EQ(r.exit_code, 0) << name << "\n" << r.out << r.err;
    EXPECT_EQ(slurp(file).rfind("# tetrapulse target optimize ", 0), 0u) << name;
  }
}

TEST_F(TargetCommand, ReproducesTheCommittedSingleTarget) {
  // The first line of the file is the command that wrote it; run it again.
  const std::string committed = source("hardware/targets/optimised-1.yaml");
  std::string command = slurp(committed);
  command = command.substr(2, command.find('\n') - 2);  // drop "# "
  const std::string out_flag = "--out ";
  command = command.substr(std::string("tetrapulse ").size(), command.find(out_flag) - std::string("tetrapulse ").size());
  ASSERT_EQ(run(command + out_flag + path("again.yaml")).exit_code, 0);
  const std::string a = slurp(committed), b = slurp(path("again.yaml"));
  EXPECT_EQ(a.substr(a.find('\n')), b.substr(b.find('\n')));
}

void expect_one_line_error(const CliRun& r, int exit_code, const std::string& names) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(TargetCommand, BadInputIsOneLineAndANonZeroExit) {
  expect_one_line_error(run("target check " + path("missing.yaml")), 3, "missing.yaml: cannot open");
  std::ofstream(path("broken.yaml")) << "timebase: [\n";
  expect_one_line_error(run("target check " + path("broken.yaml")), 3, "broken.yaml:2:");
  std::ofstream(path("three.yaml")) << "timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 1}\n"
                                       "modulation: {kind: constant}\n"
                                       "targets:\n  - {id: 0, marker_diameter_m: 0.01, markers: "
                                       "[{position_m: [0, 0, 0]}, {position_m: [1, 0, 0]}, {position_m: [0, 1, 0]}]}\n";
  expect_one_line_error(run("target check " + path("three.yaml")), 3, "expected exactly four markers");
  expect_one_line_error(run("target check --view-distance 0.1 " + source("hardware/targets/paper-large.yaml")), 2,
                        "view distance");
}

TEST_F(TargetCommand, InvalidParametersAreOneLineAndANonZeroExit) {
  const std::string out = " --restarts 5 --out " + path("x.yaml");
  expect_one_line_error(run("target optimize --d1 0.3 --d2 0.2" + out), 2, "d2 must be greater than d1");
  expect_one_line_error(run("target optimize --h 0.4" + out), 2, "h must be");
  expect_one_line_error(run("target optimize --w 1.5" + out), 2, "w must be in [0, 1]");
  expect_one_line_error(run("target optimize --targets 0" + out), 2, "targets must be");
  expect_one_line_error(run("target optimize --restarts 0 --out " + path("x.yaml")), 2, "restarts must be");
  expect_one_line_error(run("target optimize --marker-diameter 0.2" + out), 2, "marker-diameter");
  expect_one_line_error(run("target optimize --top-d1 0.5" + out), 2, "top-d2 must be greater than top-d1");
  expect_one_line_error(run("target optimize --h 0.28" + out), 1, "no restart met the constraints");
  expect_one_line_error(run("target optimize --restarts 5 --out " + path("no/such/dir/x.yaml")), 1, "cannot create");
  EXPECT_FALSE(fs::exists(path("x.yaml")));  // nothing written on failure
}

TEST_F(TargetCommand, WarnsWhenTheWeightFavoursBunchedDistances) {
  const CliRun r = run("target optimize --targets 8 --w 0.667 --restarts 2 --out " + path("w.yaml"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: w = 0.667"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tetrapulse

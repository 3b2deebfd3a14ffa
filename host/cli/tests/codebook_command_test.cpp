// `tetrapulse codebook` and `tetrapulse codebook check`, run as a user runs them:
// the built binary, its exit code, its output and the file it writes.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "exit_codes.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/codebook/codebook.hpp"
#include "tetrapulse/codebook/codebook_frequency.hpp"

namespace tetrapulse::cli {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("tp_codebook_cli_" + std::to_string(::getpid()) + "_" +
                                                  std::to_string(counter_++))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CommandRun {
  int exit = -1;
  std::string out, err;
};

// Runs `tetrapulse codebook ARGS`; arguments are single-quoted for the shell.
CommandRun codebook(const TempDir& dir, const std::vector<std::string>& args) {
  std::string command = std::string("'") + TETRAPULSE_CLI + "' codebook";
  for (const std::string& a : args) command += " '" + a + "'";
  command += " >'" + dir.path("stdout") + "' 2>'" + dir.path("stderr") + "'";
  const int status = std::system(command.c_str());
  CommandRun r;
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir.path("stdout"));
  r.err = slurp(dir.path("stderr"));
  return r;
}

size_t lines(const std::string& text) { return static_cast<size_t>(std::count(text.begin(), text.end(), '\n')); }

std::vector<uint64_t> marker_codes(const TargetsFile& f) {
  std::vector<uint64_t> codes;
  for (const Target& t : f.targets) {
    for (const Marker& m : t.markers) codes.push_back(m.code ? m.code->bits : ~uint64_t{0});
  }
  return codes;
}

TEST(CodebookCommand, WritesSixteenTargetsWithACodePerMarker) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  const CommandRun r = codebook(dir, {"--targets", "16", "--out", out});
  ASSERT_EQ(r.exit, kExitOk) << r.err;
  EXPECT_EQ(lines(r.out), 1u) << r.out;
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file) << file.error().what();
  EXPECT_TRUE(file->timebase.synchronized);
  EXPECT_EQ(file->timebase.bit_period_ns, 10'000'000);
  EXPECT_EQ(file->modulation.kind, ModulationKind::kOnOff);
  ASSERT_EQ(file->targets.size(), 16u);
  for (size_t i = 0; i < 16; ++i) {
    EXPECT_EQ(file->targets[i].id, static_cast<int>(i) + 1);
    EXPECT_DOUBLE_EQ(file->targets[i].marker_diameter_m, 0.01);
    EXPECT_DOUBLE_EQ(file->targets[i].markers[0].position_m.y(), -0.08255);  // paper-half-active
    EXPECT_DOUBLE_EQ(file->targets[i].markers[3].position_m.x(), -0.0401);
  }
  const std::vector<uint64_t> codes = marker_codes(*file);
  ASSERT_EQ(codes.size(), 64u);
  const protocol::CodebookSpec defaults =
      protocol::recommended_spec(protocol::CodeTiming::kSynchronized, protocol::ZeroBit::kDark);
  const protocol::CodebookReport report = protocol::validate(defaults, codes.data(), codes.size());
  EXPECT_TRUE(report.ok()) << protocol::codebook_fault_name(report.fault) << " " << report.code << " "
                           << report.other;

  const CommandRun check = codebook(dir, {"check", out});
  EXPECT_EQ(check.exit, kExitOk) << check.err;
  EXPECT_NE(check.out.find("64 codes (one per marker) pass"), std::string::npos) << check.out;
}

TEST(CodebookCommand, FreeRunningTwoLevelWithACodePerTarget) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  const CommandRun r = codebook(dir, {"--targets", "5", "--per", "target", "--free-running", "--modulation",
                                      "two_level", "--low", "0.25", "--ids", "10,11,12,13,14", "--out", out});
  ASSERT_EQ(r.exit, kExitOk) << r.err;
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file) << file.error().what();
  EXPECT_FALSE(file->timebase.synchronized);
  EXPECT_EQ(file->modulation.kind, ModulationKind::kTwoLevel);
  EXPECT_DOUBLE_EQ(file->modulation.low, 0.25);
  ASSERT_EQ(file->targets.size(), 5u);
  std::vector<uint64_t> codes;
  for (size_t i = 0; i < 5; ++i) {
    const Target& t = file->targets[i];
    EXPECT_EQ(t.id, 10 + static_cast<int>(i));
    for (const Marker& m : t.markers) {
      ASSERT_TRUE(m.code);
      EXPECT_EQ(m.code->length, 15u);
      EXPECT_EQ(*m.code, *t.markers[0].code);
    }
    codes.push_back(t.markers[0].code->bits);
  }
  const protocol::CodebookSpec spec =
      protocol::recommended_spec(protocol::CodeTiming::kFreeRunning, protocol::ZeroBit::kDim);
  EXPECT_TRUE(protocol::validate(spec, codes.data(), codes.size()).ok());
  const CommandRun check = codebook(dir, {"check", out});
  EXPECT_EQ(check.exit, kExitOk) << check.err;
  EXPECT_NE(check.out.find("5 codes (one per target) pass: free-running"), std::string::npos) << check.out;
}

TEST(CodebookCommand, SameSeedSameFileOtherSeedOtherCodes) {
  TempDir dir;
  ASSERT_EQ(codebook(dir, {"--targets", "8", "--seed", "7", "--out", dir.path("a.yaml")}).exit, kExitOk);
  ASSERT_EQ(codebook(dir, {"--targets", "8", "--seed", "7", "--out", dir.path("b.yaml")}).exit, kExitOk);
  ASSERT_EQ(codebook(dir, {"--targets", "8", "--seed", "8", "--out", dir.path("c.yaml")}).exit, kExitOk);
  EXPECT_EQ(slurp(dir.path("a.yaml")), slurp(dir.path("b.yaml")));
  EXPECT_NE(slurp(dir.path("a.yaml")), slurp(dir.path("c.yaml")));
}

TEST(CodebookCommand, UsesEachTargetOfAGeometryWithNTargets) {
  TempDir dir;
  const std::string geometry = dir.file("geometry.yaml", R"(
timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 5000000}
modulation: {kind: constant}
targets:
  - id: 7
    name: left
    marker_diameter_m: 0.02
    markers:
      - position_m: [0.1, 0, 0]
      - position_m: [0, 0.1, 0]
      - position_m: [0, 0, 0.1]
      - position_m: [0.1, 0.1, 0.1]
  - id: 9
    name: right
    marker_diameter_m: 0.03
    markers:
      - position_m: [0.2, 0, 0]
      - position_m: [0, 0.2, 0]
      - position_m: [0, 0, 0.2]
      - position_m: [0.2, 0.2, 0.2]
)");
  const std::string out = dir.path("targets.yaml");
  const CommandRun r = codebook(dir, {"--targets", "2", "--geometry", geometry, "--out", out});
  ASSERT_EQ(r.exit, kExitOk) << r.err;
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file) << file.error().what();
  ASSERT_EQ(file->targets.size(), 2u);
  EXPECT_EQ(file->targets[0].id, 7);
  EXPECT_EQ(file->targets[1].name, "right");
  EXPECT_DOUBLE_EQ(file->targets[1].marker_diameter_m, 0.03);
  EXPECT_DOUBLE_EQ(file->targets[1].markers[3].position_m.z(), 0.2);

  const CommandRun mismatch = codebook(dir, {"--targets", "3", "--geometry", geometry, "--out", out});
  EXPECT_EQ(mismatch.exit, kExitUsage);
  EXPECT_NE(mismatch.err.find("has 2 targets"), std::string::npos) << mismatch.err;
}

TEST(CodebookCommand, ImpossibleRequestSaysHowManyAndWhatToRelax) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  // 8-bit codes: far fewer than the 120 that 30 targets need.
  const CommandRun r = codebook(dir, {"--targets", "30", "--length", "8", "--iterations", "2000", "--out", out});
  EXPECT_EQ(r.exit, kExitCheckFailed);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("found only"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("of the 120 codes"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--length"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CodebookCommand, MalformedGeometryNamesTheFile) {
  TempDir dir;
  const std::string geometry = dir.file("bad.yaml", R"(timebase: {synchronized: true, epoch_ns: 0, bit_period_ns: 1}
modulation: {kind: on_off}
targets:
  - id: 1
    marker_diameter_m: 0.01
    markers:
      - position_m: [0, 0, 0]
      - position_m: [0, 1, 0]
      - position_m: [1, 0, 0]
)");
  const CommandRun r = codebook(dir, {"--targets", "2", "--geometry", geometry, "--out", dir.path("targets.yaml")});
  EXPECT_EQ(r.exit, kExitBadInput);
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("bad.yaml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("markers"), std::string::npos) << r.err;
  const CommandRun missing = codebook(dir, {"--targets", "2", "--geometry", dir.path("nope.yaml"), "--out", "x"});
  EXPECT_EQ(missing.exit, kExitBadInput);
}

TEST(CodebookCommand, BadArgumentsAreUsageErrors) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--targets", "4", "--weights", "7-5", "--out", out},
           {"--targets", "4", "--weights", "five", "--out", out},
           {"--targets", "4", "--distance", "13", "--out", out},
           {"--targets", "4", "--max-zero-run", "-1", "--out", out},
           {"--targets", "4", "--low", "0.3", "--out", out},
           {"--targets", "4", "--ids", "1,2,2,3", "--out", out},
           {"--targets", "4"},
       }) {
    const CommandRun r = codebook(dir, args);
    EXPECT_EQ(r.exit, kExitUsage) << args[2] << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  // Malformed values CLI11 itself rejects: non-zero, no file.
  EXPECT_EQ(codebook(dir, {"--targets", "0", "--out", out}).exit, kExitUsage);
  EXPECT_EQ(codebook(dir, {"--targets", "2", "--per", "led", "--out", out}).exit, kExitUsage);
  EXPECT_FALSE(fs::exists(out));
}

TEST(CodebookCommand, CheckSaysWhichCodesFailWhichConstraint) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  ASSERT_EQ(codebook(dir, {"--targets", "3", "--out", out}).exit, kExitOk);
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file);
  // targets[2] marker 1 becomes targets[0] marker 0 with one bit flipped, and
  // targets[1] marker 2 gets a run of five zeros.
  Code near = *file->targets[0].markers[0].code;
  near.bits ^= 1u << 4;
  file->targets[2].markers[1].code = near;
  std::string why;
  file->targets[1].markers[2].code = parse_code("110000011011", &why);
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));

  const CommandRun r = codebook(dir, {"check", out});
  EXPECT_EQ(r.exit, kExitCheckFailed);
  EXPECT_NE(r.err.find("targets[1] (id 2) marker 2 '110000011011': 5 zeros in a row"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("targets[0] (id 1) marker 0 '" + code_text(*file->targets[0].markers[0].code) +
                       "' and targets[2] (id 3) marker 1 '" + code_text(near) + "' differ in only 1 bits"),
            std::string::npos)
      << r.err;
  // Relaxed enough, the run passes; the close pair does not.
  const CommandRun relaxed = codebook(dir, {"check", out, "--max-zero-run", "5", "--weights", "any"});
  EXPECT_EQ(relaxed.exit, kExitCheckFailed);
  EXPECT_EQ(relaxed.err.find("zeros in a row"), std::string::npos) << relaxed.err;
  EXPECT_NE(relaxed.err.find("differ in only 1 bits"), std::string::npos) << relaxed.err;
}

TEST(CodebookCommand, CheckOfFreeRunningCodesNamesTheShift) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  ASSERT_EQ(codebook(dir, {"--targets", "2", "--free-running", "--out", out}).exit, kExitOk);
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file);
  // targets[1] marker 3 plays targets[0] marker 0 started 4 bits late.
  const Code a = *file->targets[0].markers[0].code;
  const std::string text = code_text(a);
  std::string why;
  file->targets[1].markers[3].code = parse_code(text.substr(4) + text.substr(0, 4), &why);
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));
  const CommandRun r = codebook(dir, {"check", out});
  EXPECT_EQ(r.exit, kExitCheckFailed);
  EXPECT_NE(r.err.find("are at distance 0 under shift 11"), std::string::npos) << r.err;
}

TEST(CodebookCommand, CheckRejectsMissingCodesAndUnreadableFiles) {
  TempDir dir;
  const std::string plain =
      dir.file("plain.yaml", slurp(TETRAPULSE_SOURCE_DIR "/hardware/targets/paper-half-active.yaml"));
  const CommandRun constant = codebook(dir, {"check", plain});
  EXPECT_EQ(constant.exit, kExitCheckFailed);
  EXPECT_NE(constant.err.find("constant"), std::string::npos) << constant.err;
  EXPECT_EQ(codebook(dir, {"check", dir.path("missing.yaml")}).exit, kExitBadInput);
}

TEST(CodebookCommand, CapacityReportsWhatTheSearchFound) {
  TempDir dir;
  const CommandRun r = codebook(dir, {"--capacity", "--length", "7", "--weights", "any", "--max-zero-run", "none"});
  ASSERT_EQ(r.exit, kExitOk) << r.err;
  EXPECT_NE(r.out.find("found 16 codes"), std::string::npos) << r.out;  // A(7,3) = 16
  EXPECT_NE(r.out.find("more may exist"), std::string::npos) << r.out;   // 128 candidates: no proof
  // 32 candidates: the exact step proves the maximum, A(5,3) = 4.
  const CommandRun small = codebook(dir, {"--capacity", "--length", "5", "--weights", "any", "--max-zero-run", "none"});
  ASSERT_EQ(small.exit, kExitOk) << small.err;
  EXPECT_NE(small.out.find("found 4 codes"), std::string::npos) << small.out;
  EXPECT_NE(small.out.find("no larger set exists"), std::string::npos) << small.out;
}

// --family frequency: square waves of different lengths for one camera, separable at it.
TEST(CodebookCommand, FrequencyFamilyWritesSeparableSquareWaves) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  const CommandRun r = codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "2ms", "--targets", "8",
                                      "--per", "target", "--free-running", "--out", out});
  ASSERT_EQ(r.exit, kExitOk) << r.err;
  EXPECT_EQ(lines(r.out), 1u) << r.out;
  EXPECT_NE(r.out.find("frequency codes"), std::string::npos) << r.out;
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file) << file.error().what();
  EXPECT_FALSE(file->timebase.synchronized);
  ASSERT_EQ(file->targets.size(), 8u);
  std::vector<uint64_t> words;
  std::vector<uint8_t> lengths;
  for (const Target& t : file->targets) {
    for (const Marker& m : t.markers) EXPECT_EQ(m.code, t.markers[0].code);  // one code per target
    words.push_back(t.markers[0].code->bits);
    lengths.push_back(static_cast<uint8_t>(t.markers[0].code->length));
  }
  EXPECT_GT(std::set<uint8_t>(lengths.begin(), lengths.end()).size(), 1u) << "codes of different lengths";
  protocol::FrequencySpec spec;
  spec.camera = protocol::CameraTiming{10'000'000, 2'000'000};
  spec.bit_period_ns = file->timebase.bit_period_ns;
  const protocol::FrequencyReport report = protocol::check_frequency_codes(spec, words.data(), lengths.data(), 8);
  EXPECT_TRUE(report.ok()) << protocol::frequency_fault_name(report.fault) << " " << report.code;
}

TEST(CodebookCommand, FrequencyFamilyRefusesBeyondTheCameraAndSaysTheMost) {
  TempDir dir;
  const CommandRun cap = codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "1ms", "--capacity"});
  ASSERT_EQ(cap.exit, kExitOk) << cap.err;
  const size_t at = cap.out.find(" separable frequency codes");
  ASSERT_NE(at, std::string::npos) << cap.out;
  const int most = std::stoi(cap.out.substr(cap.out.rfind(' ', at - 1) + 1));
  EXPECT_GE(most, 8) << cap.out;  // acceptance: a 100 fps camera separates at least 8
  const std::string out = dir.path("targets.yaml");
  const CommandRun over = codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "1ms", "--targets",
                                         std::to_string(most + 1), "--per", "target", "--out", out});
  EXPECT_EQ(over.exit, kExitCheckFailed);
  EXPECT_EQ(lines(over.err), 1u) << over.err;
  EXPECT_NE(over.err.find("separates at most " + std::to_string(most)), std::string::npos) << over.err;
  EXPECT_FALSE(fs::exists(out));
  const CommandRun fits = codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "1ms", "--targets",
                                         std::to_string(most), "--per", "target", "--out", out});
  EXPECT_EQ(fits.exit, kExitOk) << fits.err;
  // Bad camera options are command-line errors.
  EXPECT_EQ(codebook(dir, {"--family", "frequency", "--targets", "2", "--out", out}).exit, kExitUsage);
  EXPECT_EQ(codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "11ms", "--targets", "2", "--out",
                           out}).exit,
            kExitUsage);
  EXPECT_EQ(codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "1 fortnight", "--targets", "2",
                           "--out", out}).exit,
            kExitUsage);
}

// `codebook check` of a frequency codebook: it needs the camera, passes the codebook's own
// codes at it, and names each code that fails and why.
TEST(CodebookCommand, CheckOfFrequencyCodesAtTheCamera) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  ASSERT_EQ(codebook(dir, {"--family", "frequency", "--fps", "100", "--exposure", "2ms", "--targets", "8", "--per",
                           "target", "--free-running", "--out", out})
                .exit,
            kExitOk);
  const CommandRun blind = codebook(dir, {"check", out});
  EXPECT_EQ(blind.exit, kExitUsage);
  EXPECT_EQ(lines(blind.err), 1u) << blind.err;
  EXPECT_NE(blind.err.find("8 codes (one per target) are square waves (frequency codes"), std::string::npos)
      << blind.err;
  EXPECT_NE(blind.err.find("give --fps and --exposure"), std::string::npos) << blind.err;
  EXPECT_EQ(codebook(dir, {"check", out, "--fps", "100"}).exit, kExitUsage);

  const CommandRun ok = codebook(dir, {"check", out, "--fps", "100", "--exposure", "2ms"});
  EXPECT_EQ(ok.exit, kExitOk) << ok.err;
  EXPECT_EQ(lines(ok.out), 1u) << ok.out;
  EXPECT_NE(ok.out.find("8 codes (one per target) pass: 100 fps, 2 ms exposure"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("closest pair"), std::string::npos) << ok.out;

  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file);
  const int64_t T = file->timebase.bit_period_ns;
  // targets[1] plays targets[0]'s square wave one bit late: the same frequency. targets[2]
  // repeats once a frame (k bits of P / k): it looks constant.
  const Code first = *file->targets[0].markers[0].code;
  const std::string text = code_text(first);
  const Code late = *parse_code(text.substr(text.size() - 1) + text.substr(0, text.size() - 1), nullptr);
  const int64_t k = (10'000'000 + T / 2) / T;
  ASSERT_GE(k, 2);
  ASSERT_LE(k, 64);
  const Code constant = *parse_code(std::string(static_cast<size_t>(k / 2), '1') +
                                         std::string(static_cast<size_t>(k - k / 2), '0'),
                                     nullptr);
  for (Marker& m : file->targets[1].markers) m.code = late;
  for (Marker& m : file->targets[2].markers) m.code = constant;
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));
  const CommandRun bad = codebook(dir, {"check", out, "--fps", "100", "--exposure", "2ms"});
  EXPECT_EQ(bad.exit, kExitCheckFailed);
  EXPECT_NE(bad.err.find("targets[2] (id 3) '" + code_text(constant) + "': seen at 0.0"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("it looks constant"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("targets[0] (id 1) '" + text + "' seen at"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("and targets[1] (id 2) '" + code_text(late) + "' seen at"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("too close to tell apart"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("2 faults in 8 codes (one per target)"), std::string::npos) << bad.err;
  EXPECT_EQ(lines(bad.err), 3u) << bad.err;
  // A camera option the camera cannot have is a usage error.
  EXPECT_EQ(codebook(dir, {"check", out, "--fps", "100", "--exposure", "11ms"}).exit, kExitUsage);
}

// A mixed file: binary words by the binary rules, square waves by the frequency rules,
// and no binary word seen at the apparent frequency of a square wave.
TEST(CodebookCommand, CheckOfAMixedFileChecksEachFamilyAndBetweenThem) {
  TempDir dir;
  const std::string out = dir.path("targets.yaml");
  ASSERT_EQ(codebook(dir, {"--targets", "4", "--per", "target", "--out", out}).exit, kExitOk);
  auto file = read_targets_yaml(out);
  ASSERT_TRUE(file);
  // 100 fps, T = 2.5 ms. "1110000": 17.5 ms, 0.429 cycle per frame; "111100000000": 30 ms,
  // 1/3. 14-bit words: 35 ms, 0.286, at least 0.048 from both (> 1/24 + drifts).
  file->timebase.bit_period_ns = 2'500'000;
  const char* codes[] = {"1110000", "111100000000", "11010011000101", "10011101001100"};
  auto set = [&](size_t target, const std::string& code) {
    for (Marker& m : file->targets[target].markers) m.code = *parse_code(code, nullptr);
  };
  for (size_t i = 0; i < 4; ++i) set(i, codes[i]);
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));
  const std::vector<std::string> camera = {"--fps", "100", "--exposure", "1ms", "--weights", "any",
                                           "--max-zero-run", "none"};
  auto check = [&]() {
    std::vector<std::string> args = {"check", out};
    args.insert(args.end(), camera.begin(), camera.end());
    return codebook(dir, args);
  };
  const CommandRun ok = check();
  EXPECT_EQ(ok.exit, kExitOk) << ok.err;
  EXPECT_NE(ok.out.find("2 binary codes (one per target) pass: synchronized, 14 bits"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("2 frequency codes (one per target) pass: 100 fps"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("the 2 binary codes stay apart from them"), std::string::npos) << ok.out;
  EXPECT_EQ(lines(ok.out), 2u) << ok.out;

  // "11100001110000" is "1110000" twice: not a square wave, so a binary word, but the
  // camera sees it exactly where it sees targets[0].
  set(3, "11100001110000");
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));
  const CommandRun twin = check();
  EXPECT_EQ(twin.exit, kExitCheckFailed);
  EXPECT_NE(twin.err.find("binary targets[3] (id 4) '11100001110000' repeats every 7 bits"), std::string::npos)
      << twin.err;
  EXPECT_NE(twin.err.find("and frequency targets[0] (id 1) '1110000' at 0.4286"), std::string::npos) << twin.err;
  EXPECT_NE(twin.err.find("a reader may take one for the other"), std::string::npos) << twin.err;
  EXPECT_NE(twin.err.find("1 faults in 2 frequency codes (one per target) and beside the binary codes"),
            std::string::npos)
      << twin.err;
  EXPECT_NE(twin.out.find("2 binary codes (one per target) pass"), std::string::npos) << twin.out;

  // Each family by its own rules: binary words of two lengths, and a square wave too close to another.
  set(3, "1001110100110");
  set(1, "111111000000000");  // 15 bits: 37.5 ms, 0.267 cycle per frame
  set(0, "1111000000000");    // 13 bits: 32.5 ms, 0.308: 0.041 from it, less than 1/24
  ASSERT_TRUE(write_text_file(out, format_targets_yaml(*file)));
  const CommandRun both = check();
  EXPECT_EQ(both.exit, kExitCheckFailed);
  EXPECT_NE(both.err.find("targets[3] (id 4): 13 bits, but other binary codes have 14"), std::string::npos)
      << both.err;
  EXPECT_NE(both.err.find("targets[0] (id 1) '1111000000000' seen at 0.3077"), std::string::npos) << both.err;
  EXPECT_NE(both.err.find("too close to tell apart"), std::string::npos) << both.err;
  // Without the camera the frequency half cannot be checked, and says so.
  const CommandRun blind = codebook(dir, {"check", out, "--weights", "any", "--max-zero-run", "none"});
  EXPECT_NE(blind.err.find("2 frequency codes (one per target) are square waves"), std::string::npos) << blind.err;
}

}  // namespace
}  // namespace tetrapulse::cli

// The board commands (list, info, config, identify, status, flash, sync) as users run
// them: the built binary against simulated boards (--board sim:N, the firmware core) and a
// protocol responder on a pseudo-terminal; exit codes, one-line errors, JSON output.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "cli_run.hpp"
#include "exit_codes.hpp"
#include "pty_pair.hpp"
#include "tetrapulse/host/board.hpp"
#include "tetrapulse/host/config_text.hpp"
#include "tetrapulse/host/sim_board_link.hpp"
#include "tetrapulse/codebook/codebook_word.hpp"
#include "tetrapulse/protocol/pwm_code.hpp"
#include "tetrapulse/sim_board/sim_image.hpp"
#include "test_images.hpp"
#include "uart_responder.hpp"

namespace tetrapulse::cli {
namespace {

using testing::CliRun;
using testing::CliTempDir;
using testing::run_cli;

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                              static_cast<std::streamsize>(bytes.size()));
}

TEST(BoardCommands, InfoOfASimulatedBoard) {
  CliTempDir dir("board");
  const CliRun human = run_cli(dir, "info --board sim:5");
  ASSERT_EQ(human.exit, kExitOk) << human.err;
  EXPECT_NE(human.out.find("hardware: sim rev 1"), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("node id: 5"), std::string::npos) << human.out;
  const CliRun json = run_cli(dir, "info --board sim:5 --json");
  ASSERT_EQ(json.exit, kExitOk) << json.err;
  EXPECT_EQ(json.out.rfind("{\"address\": \"sim:5\", \"hw_model\": \"sim\"", 0), 0u) << json.out;
}

TEST(BoardCommands, CodebookBoardFilesConfigureABoard) {
  CliTempDir dir("board");
  const CliRun codebook = run_cli(dir, "codebook --targets 2 --out '" + dir.path("targets.yaml") + "'");
  ASSERT_EQ(codebook.exit, kExitOk) << codebook.err;
  const std::string board_file = dir.path("boards/target-2.yaml");
  ASSERT_TRUE(std::filesystem::exists(board_file)) << codebook.out;
  const CliRun config = run_cli(dir, "config --board sim:2 --persist --file '" + board_file + "' --json");
  ASSERT_EQ(config.exit, kExitOk) << config.err;
  EXPECT_NE(config.out.find("\"verified\": true"), std::string::npos) << config.out;
  EXPECT_NE(config.out.find("\"target_id\": 2"), std::string::npos) << config.out;
  EXPECT_NE(config.out.find("\"sync_source\": \"can\""), std::string::npos) << config.out;
}

TEST(BoardCommands, BadInputIsOneLineAndTheDocumentedExitCode) {
  CliTempDir dir("board");
  const std::string broken = dir.file("broken.yaml", "node_id: 3\ncodes: [\"1101\", \"12\", \"\", \"\"]\n");
  struct Case {
    std::string args;
    int exit;
    std::string says;
  };
  for (const Case& c : {
           Case{"info", kExitUsage, "say which board"},
           Case{"info --board bluetooth:7", kExitUsage, "bluetooth:7: a board is usb:SERIAL"},
           Case{"info --can vcan0", kExitUsage, "can:vcan0: expected IFACE:NODE"},
           Case{"info --can tpnosuch0:3", kExitNoDevice, "can:tpnosuch0:3: no such network interface"},
           Case{"info --serial /dev/tp-nosuch", kExitNoDevice, "serial:/dev/tp-nosuch: cannot open"},
           Case{"config --board sim:1 --file '" + broken + "'", kExitBadInput, broken + ":2: codes[1]: '12'"},
           Case{"config --board sim:1 --file /nonexistent/b.yaml", kExitBadInput, "/nonexistent/b.yaml"},
           Case{"config --board sim:1 --code 4=1101", kExitUsage, "--code 4=1101: expected MARKER=BITS"},
           Case{"config --board sim:1 --code 0=1102", kExitUsage, "'1102' character 4 is '2'"},
           Case{"flash --board sim:1 /nonexistent/fw.bin", kExitBadInput, "/nonexistent/fw.bin: cannot read the file"},
           Case{"flash --board sim:1 '" + dir.path("") + "'", kExitBadInput, "is a folder, not a file"},
           Case{"config --board sim:1 --file '" + dir.path("") + "'", kExitBadInput, "is a folder, not a file"},
           Case{"info --usb TPNOSUCH", kExitNoDevice, "usb:TPNOSUCH: no board"},
           Case{"info --board sim:300", kExitUsage, "sim:300: node '300' is not a CAN node id 1..254"},
           Case{"sync", kExitUsage, "give --trigger LINE, --strobe LINE and/or --can IFACE"},
           Case{"sync --trigger gpiochip0:1", kExitUsage, "--out FILE"},
           Case{"sync --can tpnosuch0 --count 1", kExitNoDevice, "no such network interface"},
       }) {
    const CliRun r = run_cli(dir, c.args);
    EXPECT_EQ(r.exit, c.exit) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err_lines(), 1u) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
  }
}

// What a marker's LED did: mean frequency and duty over the whole periods between its first
// and last rising edge at or after `from_ns` (true rig time).
struct MeasuredPwm {
  double hz = 0;
  double duty = 0;
  int periods = 0;
};
MeasuredPwm measure_pwm(const sim_board::SimBoard& board, uint8_t marker, long double from_ns) {
  struct Edge {
    long double at;
    bool on;
  };
  std::vector<Edge> edges;
  bool on = false;  // LEDs are dark at power-up
  for (const sim_board::AppliedLedChange& c : board.leds().log(marker)) {
    if ((c.duty > 0) != on && c.rig_ns >= from_ns) edges.push_back(Edge{c.rig_ns, c.duty > 0});
    on = c.duty > 0;
  }
  std::vector<size_t> rises;
  for (size_t i = 0; i < edges.size(); ++i) {
    if (edges[i].on) rises.push_back(i);
  }
  MeasuredPwm m;
  if (rises.size() < 2) return m;
  long double lit = 0;
  for (size_t i = rises.front(); i + 1 <= rises.back(); ++i) {
    if (edges[i].on) lit += edges[i + 1].at - edges[i].at;
  }
  const long double span = edges[rises.back()].at - edges[rises.front()].at;
  m.periods = static_cast<int>(rises.size()) - 1;
  m.hz = static_cast<double>(m.periods / span * 1e9L);
  m.duty = static_cast<double>(lit / span);
  return m;
}

// `config --pwm-hz F --duty D` on a simulated board: what it prints is what pwm_code gives,
// the board reads back that code on all four markers, and a board so configured blinks its
// LEDs at that frequency and duty (edges from the firmware core's LED log).
TEST(BoardCommands, ConfigPwmPlaysTheFrequencyAndDutyItPrints) {
  CliTempDir dir("board");
  struct Case {
    double hz, duty;
  };
  for (const Case c : {Case{1000, 0.25}, Case{37.5, 0.5}, Case{30000, 0.3}, Case{0.5, 0.9}}) {
    const std::string args = fmt::format("config --board sim:3 --pwm-hz {} --duty {}", c.hz, c.duty);
    const auto pwm = protocol::pwm_code(static_cast<uint64_t>(std::llround(c.hz * 1000)),
                                        static_cast<uint32_t>(std::llround(c.duty * 65536)));
    ASSERT_TRUE(pwm.ok()) << args;
    const std::string code = host::code_text(pwm->code);
    const double duty = double(protocol::word_weight(pwm->code.bits)) / pwm->code.length;  // exactly
    const CliRun human = run_cli(dir, args);
    ASSERT_EQ(human.exit, kExitOk) << args << "\n" << human.err;
    EXPECT_NE(human.out.find(fmt::format("plays {:.3f} Hz duty {:.4f}", pwm->frequency_millihertz / 1000.0, duty)),
              std::string::npos)
        << human.out;
    EXPECT_NE(human.out.find(fmt::format("on a {} ns bit period, duty steps of 1/{}", pwm->bit_period_ns,
                                         int(pwm->code.length))),
              std::string::npos)
        << human.out;
    EXPECT_NE(human.out.find("configured and read back"), std::string::npos) << human.out;
    const CliRun json = run_cli(dir, args + " --json");
    ASSERT_EQ(json.exit, kExitOk) << json.err;
    EXPECT_NE(json.out.find("\"verified\": true"), std::string::npos) << json.out;
    EXPECT_NE(json.out.find(fmt::format("\"codes\": [\"{0}\", \"{0}\", \"{0}\", \"{0}\"]", code)), std::string::npos)
        << json.out;
    EXPECT_NE(json.out.find(fmt::format("\"bit_period_ns\": {}", pwm->bit_period_ns)), std::string::npos) << json.out;
    EXPECT_NE(json.out.find("\"modulation\": \"on_off\""), std::string::npos) << json.out;

    // The board plays it: a free-running simulated board with a perfect crystal, 20 periods.
    auto sim = std::make_shared<sim_board::SimBoard>(sim_board::SimBoardOptions{});
    sim->advance_to(1'000'000);
    host::Board board(std::make_unique<host::SimLink>("sim:1", host::sim_board_port(sim)));
    auto config = board.config();
    ASSERT_TRUE(config) << config.error().what();
    config->codes.fill(pwm->code);
    config->bit_period_ns = pwm->bit_period_ns;
    config->modulation = protocol::Modulation::kOnOff;
    ASSERT_TRUE(board.configure(*config));
    const int64_t start = sim->now() + 2 * static_cast<int64_t>(pwm->bit_period_ns) * pwm->code.length;
    sim->advance_to(start + 21 * static_cast<int64_t>(1e12 / pwm->frequency_millihertz));
    const double tick_ns = 1e9 / sim_board::SimBoardOptions{}.tick_hz;
    for (uint8_t m = 0; m < 4; ++m) {
      const MeasuredPwm got = measure_pwm(*sim, m, start);
      ASSERT_GE(got.periods, 19) << args << " marker " << int(m);
      const double period_ns = 1e12 / pwm->frequency_millihertz;
      // Edges fall on the board's 84 MHz counter: each is within one tick of its time.
      EXPECT_NEAR(got.hz, c.hz, c.hz * (2 * tick_ns / (got.periods * period_ns) + 5e-4)) << args;
      EXPECT_NEAR(got.hz, pwm->frequency_millihertz / 1000.0, pwm->frequency_millihertz / 1000.0 * 2 * tick_ns /
                                                                  (got.periods * period_ns) + 1e-9)
          << args;
      EXPECT_NEAR(got.duty, duty, 2 * tick_ns / period_ns + 1e-9) << args;
      EXPECT_NEAR(got.duty, c.duty, 0.5 / pwm->code.length + 1e-9) << args << ": within half a duty step";
    }
  }
}

TEST(BoardCommands, ConfigPwmRefusesWhatNoBoardPlays) {
  CliTempDir dir("board");
  struct Case {
    std::string args;
    std::string says;
  };
  for (const Case& c : {
           Case{"--pwm-hz 0", "--pwm-hz 0: outside 0.01 Hz .. 50000 Hz"},
           Case{"--pwm-hz=-5", "--pwm-hz -5: outside"},
           Case{"--pwm-hz 50001", "the highest is two bits of the shortest bit period, 10000 ns"},
           Case{"--pwm-hz 1e9", "--pwm-hz 1e+09: outside"},
           Case{"--pwm-hz 100 --duty 0", "--duty 0: must be between 0 and 1"},
           Case{"--pwm-hz 100 --duty 1", "--duty 1: must be between 0 and 1"},
           Case{"--pwm-hz 100 --duty=-0.2", "--duty -0.2: must be between 0 and 1"},
           Case{"--pwm-hz 100 --modulation constant", "--modulation constant plays no code"},
       }) {
    const CliRun r = run_cli(dir, "config --board sim:1 " + c.args);
    EXPECT_EQ(r.exit, kExitUsage) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err_lines(), 1u) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  // Options that do not go together are refused by the command-line parser (with its "Run with --help" line).
  for (const Case& c : {Case{"--duty 0.5", "--duty requires --pwm-hz"},
                        Case{"--pwm-hz 100 --code 0=1101", "--code excludes --pwm-hz"},
                        Case{"--pwm-hz 100 --bit-period-ns 20000", "--bit-period-ns excludes --pwm-hz"}}) {
    const CliRun r = run_cli(dir, "config --board sim:1 " + c.args);
    EXPECT_EQ(r.exit, kExitUsage) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(c.says + "\n", 0), 0u) << c.args << "\n" << r.err;
  }
  // Quantisation and range are stated in --help.
  const CliRun help = run_cli(dir, "config --help");
  EXPECT_NE(help.out.find("duty in steps of 1/L"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("0.01 .. 50000"), std::string::npos) << help.out;
}

TEST(BoardCommands, FlashUpdatesASimulatedBoardAndRefusesImagesThatDoNotFit) {
  CliTempDir dir("board");
  sim_board::SimImageSpec spec;
  spec.fw_version = 0x01070002;
  write_bytes(dir.path("sim-1.7.2.bin"), sim_board::make_sim_image(spec));
  const CliRun flashed = run_cli(dir, "flash --board sim:1 --json '" + dir.path("sim-1.7.2.bin") + "'");
  ASSERT_EQ(flashed.exit, kExitOk) << flashed.err;
  EXPECT_NE(flashed.out.find("{\"stage\": \"write\""), std::string::npos) << flashed.out;
  EXPECT_NE(flashed.out.find("\"running_version\": \"1.7.2\""), std::string::npos) << flashed.out;

  write_bytes(dir.path("linux.bin"), host::testing::make_test_image(host::testing::TestImageSpec{}));
  const CliRun refused = run_cli(dir, "flash --board sim:1 '" + dir.path("linux.bin") + "'");
  EXPECT_EQ(refused.exit, kExitBadInput) << refused.err;
  EXPECT_EQ(refused.err_lines(), 1u) << refused.err;
  EXPECT_NE(refused.err.find("built for linux rev 0..255, the board is sim rev 1"), std::string::npos) << refused.err;

  dir.file("text.bin", "not firmware at all, just text");
  const CliRun text = run_cli(dir, "flash --board sim:1 '" + dir.path("text.bin") + "'");
  EXPECT_EQ(text.exit, kExitBadInput);
  EXPECT_NE(text.err.find("not a tetrapulse firmware image"), std::string::npos) << text.err;
}

TEST(BoardCommands, StatusWatchAndIdentify) {
  CliTempDir dir("board");
  const CliRun watch = run_cli(dir, "status --board sim:1 --watch --count 3 --interval-ms 10 --json");
  ASSERT_EQ(watch.exit, kExitOk) << watch.err;
  EXPECT_EQ(std::count(watch.out.begin(), watch.out.end(), '\n'), 3) << watch.out;
  EXPECT_NE(watch.out.find("\"update_state\": \"idle\""), std::string::npos) << watch.out;
  const CliRun identify = run_cli(dir, "identify --board sim:1 --pattern chase --duration-ms 100");
  ASSERT_EQ(identify.exit, kExitOk) << identify.err;
  EXPECT_EQ(identify.out, "sim:1: identify chase for 100 ms\n");
}

TEST(BoardCommands, ListAndInfoOverASerialLine) {
  host::testing::PtyPair pty;
  ASSERT_TRUE(pty.ok());
  host::testing::UartResponder responder(pty.master());
  CliTempDir dir("board");
  const CliRun list = run_cli(dir, "list --no-usb --serial " + pty.device() + ":230400");
  ASSERT_EQ(list.exit, kExitOk) << list.err;
  EXPECT_NE(list.out.find("serial:" + pty.device() + ":230400"), std::string::npos) << list.out;
  EXPECT_NE(list.out.find("linux rev 1, firmware 1.0.0"), std::string::npos) << list.out;
  const CliRun none = run_cli(dir, "list --no-usb");
  EXPECT_EQ(none.exit, kExitNoDevice);
  const CliRun status = run_cli(dir, "status --serial " + pty.device());
  ASSERT_EQ(status.exit, kExitOk) << status.err;
  EXPECT_EQ(status.out.rfind("serial:" + pty.device() + ": sync free-running (none)", 0), 0u) << status.out;
}

TEST(BoardCommands, EveryCommandHasHelp) {
  CliTempDir dir("board");
  for (const char* command : {"list", "info", "config", "identify", "status", "flash", "sync"}) {
    const CliRun help = run_cli(dir, std::string(command) + " --help");
    EXPECT_EQ(help.exit, kExitOk) << command;
    EXPECT_NE(help.out.find("Usage:"), std::string::npos) << command;
  }
  const CliRun config = run_cli(dir, "config --help");
  EXPECT_NE(config.out.find("--can IFACE:NODE"), std::string::npos) << "addressing is explained";
  EXPECT_NE(config.out.find("--gpio-edge-numbering"), std::string::npos);
}

TEST(BoardCommands, VisionCommandsAreListedAndHandedToTheVisionProgram) {
  CliTempDir dir("vision");
  const CliRun help = run_cli(dir, "--help");
  ASSERT_EQ(help.exit, kExitOk);
  for (const char* command : {"sim", "localize", "eval", "demo", "list", "sync", "codebook", "target"})
    EXPECT_NE(help.out.find(std::string("  ") + command + " "), std::string::npos) << command;
  // Handed over with every argument: the vision program's own help and its usage errors.
  const CliRun localize = run_cli(dir, "localize --help");
  EXPECT_EQ(localize.exit, kExitOk);
  EXPECT_NE(localize.out.find("--p3p"), std::string::npos) << localize.out;
  EXPECT_EQ(run_cli(dir, "eval --no-such-option").exit, kExitUsage);
  // Without tetrapulse-vision beside it: one line that names the program it looked for.
  const std::string alone = dir.path("tetrapulse");
  std::filesystem::copy_file(TETRAPULSE_CLI, alone);
  std::filesystem::permissions(alone, std::filesystem::perms::owner_exec, std::filesystem::perm_options::add);
  const std::string command = "'" + alone + "' sim paper-exp1 --out '" + dir.path("out") + "' 2>'" + dir.path("err") + "'";
  const int status = std::system(command.c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, kExitFailure);
  const std::string err = testing::slurp(dir.path("err"));
  EXPECT_NE(err.find(dir.path("tetrapulse-vision")), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("out")));
}

}  // namespace
}  // namespace tetrapulse::cli

// The virtual rig run by host code (HostSyncedRig): boards configured through host::Board
// over SimLink and synchronised by GpioSync (simulated trigger line) and CanSync (simulated
// bus) play exactly what sim's FirmwareBoardEmitter boards play, LED change for LED change,
// and a dataset made this way is byte for byte the one sim makes directly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tetrapulse/host/sim_rig.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::host {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

sim::Scenario scenario(const std::string& name) {
  auto s = sim::load_scenario(name);
  EXPECT_TRUE(s) << s.error().what();
  return *s;
}

// paper-exp1's target on the given sync (GPIO is the scenario's own).
sim::Scenario paper_exp1(sim::BoardSync sync) {
  sim::Scenario s = scenario("paper-exp1");
  for (sim::TargetSimulation& t : s.simulation) t.clock.sync = sync;
  return s;
}

// Every LED change of both boards from power-up to `until` (rig time): equal in marker,
// duty, local tick and rig time. Returns how many were compared.
size_t expect_same_led_changes(const sim_board::SimBoard& host_run, const sim_board::SimBoard& direct, int64_t until) {
  const auto& a = host_run.leds().log();
  const auto& b = direct.leds().log();
  size_t n = 0;
  for (; n < a.size() && n < b.size() && a[n].rig_ns < static_cast<long double>(until); ++n) {
    const bool same = a[n].marker == b[n].marker && a[n].duty == b[n].duty && a[n].tick == b[n].tick &&
                      a[n].rig_ns == b[n].rig_ns;
    EXPECT_TRUE(same) << "change " << n << ": host marker " << int(a[n].marker) << " duty " << a[n].duty << " at "
                      << static_cast<double>(a[n].rig_ns) << " ns; direct marker " << int(b[n].marker) << " duty "
                      << b[n].duty << " at " << static_cast<double>(b[n].rig_ns) << " ns";
    if (!same) break;
  }
  return n;
}

void expect_boards_match(const sim::Scenario& s, int64_t seconds, protocol::SyncState expected_state) {
  auto rig = HostSyncedRig::create(s);
  ASSERT_TRUE(rig) << rig.error().what();
  const int64_t until = s.frames.start_ns + seconds * kSecond;
  for (size_t i = 0; i < s.targets.targets.size(); ++i) {
    sim::FirmwareBoardEmitter direct(s, i);
    ASSERT_TRUE(direct.configured());
    (*rig)->run_until(until + 10'000'000);
    direct.run_until(until + 10'000'000);
    const size_t compared = expect_same_led_changes((*rig)->board(i), direct.board(), until);
    // Codes of 12 bits at 10 ms: dozens of changes a second per marker.
    EXPECT_GT(compared, static_cast<size_t>(50 * seconds)) << "target " << i;
  }
  ASSERT_FALSE((*rig)->failure()) << (*rig)->failure()->what();
  // The host reads what it did back over the same links.
  for (size_t i = 0; i < s.targets.targets.size(); ++i) {
    auto config = (*rig)->host_board(i).config();
    ASSERT_TRUE(config) << config.error().what();
    const auto& code = s.targets.targets[i].markers[0].code;
    ASSERT_TRUE(code.has_value());
    EXPECT_EQ(config->codes[0].bits, code->bits) << "targets.yaml's code on the board";
    EXPECT_EQ(config->codes[0].length, code->length);
    auto status = (*rig)->host_board(i).status();
    ASSERT_TRUE(status) << status.error().what();
    EXPECT_EQ(status->sync_state, expected_state) << "target " << i;
  }
}

TEST(HostSyncedRig, GpioTriggerSyncedBoardsMatchTheDirectOnesEdgeForEdge) {
  expect_boards_match(paper_exp1(sim::BoardSync::kGpio), 2, protocol::SyncState::kLocked);
}

TEST(HostSyncedRig, CanSyncedBoardsMatchTheDirectOnesEdgeForEdge) {
  expect_boards_match(paper_exp1(sim::BoardSync::kCan), 2, protocol::SyncState::kLocked);
}

TEST(HostSyncedRig, FreeRunningBoardsMatchTheDirectOnesEdgeForEdge) {
  expect_boards_match(scenario("unsync"), 2, protocol::SyncState::kFreeRunning);
}

TEST(HostSyncedRig, TriggerExposuresAreTheScenariosFrames) {
  const sim::Scenario s = paper_exp1(sim::BoardSync::kGpio);
  auto rig = HostSyncedRig::create(s);
  ASSERT_TRUE(rig) << rig.error().what();
  (*rig)->run_until(s.frames.start_ns + 20 * s.frames.period_ns - 1);
  const auto& exposures = (*rig)->exposures();
  ASSERT_EQ(exposures.size(), 20u);
  for (size_t k = 0; k < exposures.size(); ++k) {
    EXPECT_EQ(exposures[k].frame, static_cast<int64_t>(k));
    EXPECT_EQ(exposures[k].timestamp_ns, s.frames.start_ns + static_cast<int64_t>(k) * s.frames.period_ns);
    EXPECT_EQ(exposures[k].exposure_ns, s.frames.exposure_ns);
  }
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(HostSyncedRig, DatasetEqualsTheOneSimMakesDirectly) {
  // Four targets on one trigger line and one bus: two on GPIO (one losing sync for a
  // while), two on CAN.
  sim::Scenario s = scenario("swarm");
  ASSERT_EQ(s.simulation.size(), 4u);
  s.simulation[0].clock.sync = sim::BoardSync::kGpio;
  s.simulation[1].clock.sync = sim::BoardSync::kGpio;
  s.simulation[1].clock.sync_loss = sim::TimeIntervals({{s.frames.start_ns - 3 * kSecond, s.frames.start_ns - 2 * kSecond}});
  s.simulation[2].clock.sync = sim::BoardSync::kCan;
  s.simulation[3].clock.sync = sim::BoardSync::kCan;
  const auto dir = std::filesystem::temp_directory_path() / ("tp_host_rig_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  sim::SimulationOptions options;
  options.frames = 4;
  options.out = (dir / "direct").string();
  auto direct = sim::simulate_dataset(s, options);
  ASSERT_TRUE(direct) << direct.error().what();
  options.out = (dir / "host").string();
  auto host = simulate_with_host_boards(s, options);
  ASSERT_TRUE(host) << host.error().what();
  EXPECT_EQ(host->frames_written, direct->frames_written);
  size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir / "direct")) {
    if (!e.is_regular_file()) continue;
    const auto rel = std::filesystem::relative(e.path(), dir / "direct");
    EXPECT_EQ(slurp(e.path()), slurp(dir / "host" / rel)) << rel;
    ++files;
  }
  EXPECT_GE(files, 5u + 4u) << "camera, targets, frames, groundtruth, scenario and four images";
  std::filesystem::remove_all(dir);
}


TEST(HostSyncedRig, EveryBuiltinScenariosBoardsTakeTheirTargetsYamlThroughTheHost) {
  for (const sim::BuiltinScenario& b : sim::builtin_scenarios()) {
    const sim::Scenario s = scenario(b.name);
    auto rig = HostSyncedRig::create(s);
    ASSERT_TRUE(rig) << b.name << ": " << rig.error().what();
    (*rig)->run_until(s.frames.start_ns + s.frames.period_ns);
    EXPECT_FALSE((*rig)->failure()) << b.name;
    for (size_t i = 0; i < (*rig)->boards(); ++i) {
      sim::FirmwareBoardEmitter direct(s, i);
      EXPECT_TRUE(direct.configured()) << b.name << " target " << i << ": sim plays it with its own board too";
      direct.run_until(s.frames.start_ns + s.frames.period_ns);
      EXPECT_EQ((*rig)->board(i).leds().log().size(), direct.board().leds().log().size()) << b.name << " target " << i;
    }
  }
}

}  // namespace
}  // namespace tetrapulse::host

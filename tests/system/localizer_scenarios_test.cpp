// The localizer on the virtual rig: every built-in scenario, CI-sized (its
// ci_count frames, its own seed), rendered at test time, localized and held to
// issue 4's acceptance lines. Measured numbers go to the test log.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "scenario_run.hpp"
#include "tetrapulse/localizer/frequency_identifier.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"

namespace tetrapulse::system_testing {
namespace {

constexpr double kDeg = M_PI / 180;

struct Acceptance {
  const char* scenario;
  double max_position_m;     // absolute bound on the mean (infinity: none)
  double max_orientation_deg;
  double min_coverage;
};

const Acceptance kScenarios[] = {
    {"paper-exp1", 0.005, 0.3, 0.99}, {"paper-far", 0.02, 0.5, 0.99}, {"passive", INFINITY, INFINITY, 0.95},
    {"swarm", INFINITY, INFINITY, 0.99}, {"unsync", INFINITY, INFINITY, 0.99}, {"clutter", INFINITY, INFINITY, 0.99},
    {"fisheye", INFINITY, INFINITY, 0.99},   {"frequency", INFINITY, INFINITY, 0.99},
    // Issue 14's robustness matrix (localizer/ACCURACY.md): agile flight, strong
    // distortion, LED beams and brightness spread, drop-outs.
    {"agile", INFINITY, INFINITY, 0.99}, {"distortion", INFINITY, INFINITY, 0.99},
    {"beam-spread", INFINITY, INFINITY, 0.99}, {"dropouts", INFINITY, INFINITY, 0.99},
    // Saturation (lit markers 5-20x full well, the two_level low level clipped too,
    // blooming), saturation x motion, and crowds that cross (one code per drone).
    {"sat-exp1-5x", INFINITY, INFINITY, 0.99}, {"sat-exp1-20x", INFINITY, INFINITY, 0.99},
    {"sat-clutter", INFINITY, INFINITY, 0.99}, {"sat-fisheye", INFINITY, INFINITY, 0.99},
    {"agile-sat", INFINITY, INFINITY, 0.99}, {"sat-bloom", INFINITY, INFINITY, 0.99},
    // Constant markers clipped at 10x full well: geometry alone (issue 14: >= 95 %).
    {"sat-passive", INFINITY, INFINITY, 0.95},
    // A drone landing on the target to 0.12 m: both levels clip, the codes become
    // unreadable, geometry keeps the markers (code_checks.hpp).
    {"sat-landing", INFINITY, INFINITY, 0.99},
    // Issue 19: the paper's Experiment 2 with dark painted balls on a lit floor,
    // half in shadow, two robots told apart by geometry alone (>= 95 %).
    {"passive-dark", INFINITY, INFINITY, 0.95},
    // ... and in colour: red painted balls through a Bayer camera, found by chroma.
    {"colour", INFINITY, INFINITY, 0.95},
    // ... and coded LED robots with a dark painted one in one scene (one extractor per look).
    {"mixed", INFINITY, INFINITY, 0.99},
    // Crowds that cross (issue 14): 20 and 32 drones, one code per drone, pairs
    // passing through one image point from different depths.
    {"crowd", INFINITY, INFINITY, 0.99}, {"crowd-on-off", INFINITY, INFINITY, 0.99},
};

// Rows that do not meet the acceptance lines yet: each is run at CI size and held to
// what it reaches today, so a change that makes one worse fails here; a row that
// meets the lines moves up into kScenarios. (climb-colour is issue 19's view, left
// open there; every row of issue 14's robustness matrix is in kScenarios.)
struct OpenRow {
  const char* scenario;
  double min_coverage;       // today's coverage, rounded down
  size_t max_misidentified;  // today's count
  double max_position_m;     // the largest position error today, rounded up
  const char* open;          // which acceptance line it misses
};

const OpenRow kOpenRows[] = {
    // Issue 19: the climbing robot's 150-degree colour view; one robot's balls touch at first.
    {"climb-colour", 0.99, 0, INFINITY, "identification latency 13 frames (geometry bound 2)"},
};

// Frequency codes (square waves, protocol/SPEC.md 8.5) are seen at their apparent
// frequency nu = dist(P / C, Z) cycles per frame; issue 8 bounds their identification by
// two of the rig's longest apparent periods, 2 / min(nu) frames. 0: no frequency codes.
int64_t frequency_latency_bound(const sim::Scenario& scenario) {
  double slowest = 0;
  for (const Target& t : scenario.targets.targets)
    for (const Marker& m : t.markers) {
      if (!m.code || !is_square_wave(*m.code)) continue;
      const double cycles = double(scenario.frames.period_ns) /
                            double(int64_t(m.code->length) * scenario.targets.timebase.bit_period_ns);
      const double nu = std::abs(cycles - std::round(cycles));
      if (nu > 0) slowest = std::max(slowest, 1 / nu);
    }
  return int64_t(std::ceil(2 * slowest));
}

void PrintTo(const Acceptance& a, std::ostream* os) { *os << a.scenario; }

// A row's test name: its scenario's, with '_' for '-'.
template <typename Row>
std::string test_name(const ::testing::TestParamInfo<Row>& param) {
  std::string name = param.param.scenario;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

class Scenarios : public ::testing::TestWithParam<Acceptance> {};

TEST_P(Scenarios, MeetTheAcceptanceLines) {
  const Acceptance& a = GetParam();
  auto scenario = sim::load_scenario(a.scenario);
  ASSERT_TRUE(scenario) << scenario.error().what();
  const auto run = run_scenario(*scenario, scenario->seed, scenario->frames.ci_count);
  ASSERT_TRUE(run) << run.error();
  const Evaluation& e = run->evaluation;
  const TargetEvaluation& all = e.overall;
  const OracleComparison oracle = compare_with_oracle(*run);
  const bool free_running = !scenario->targets.timebase.synchronized;
  const int64_t frequency_bound = frequency_latency_bound(*scenario);
  // Unmodulated markers: identity from geometry, weighed over min_geometry_frames
  // frames when another target's geometry is a rival (target_identifier.hpp).
  const int64_t geometry_bound = LocalizerOptions{}.identification.min_geometry_frames - 1;
  const int64_t latency_bound = frequency_bound > 0             ? frequency_bound
                                : run->code_length_frames == 0 ? geometry_bound
                                : free_running  // issue 14: 1.5 periods when the boards run free
                                    ? (3 * run->code_length_frames + 1) / 2
                                    : run->code_length_frames;
  std::printf(
      "%s: %zu frames, %zu poses; mean error %.2f mm / %.3f deg; oracle over %zu pairs %.2f mm / %.3f deg "
      "(localizer on them %.2f mm / %.3f deg); coverage %.4f (%zu of %zu); misidentified %zu; "
      "max latency %lld frames (bound %lld)\n",
      a.scenario, run->frames.size(), all.rows, 1e3 * all.position_m.mean, all.orientation_rad.mean / kDeg,
      oracle.pairs, 1e3 * oracle.oracle.position_m, oracle.oracle.orientation_rad / kDeg,
      1e3 * oracle.localizer.position_m, oracle.localizer.orientation_rad / kDeg, all.coverage(), all.covered_frames,
      all.visible_frames, all.misidentified, (long long)all.max_latency_frames, (long long)latency_bound);

  EXPECT_EQ(all.misidentified, 0u);
  EXPECT_GE(all.coverage(), a.min_coverage);
  EXPECT_GT(all.rows, 0u);
  EXPECT_GT(all.visible_frames_total, 0u) << "no target visible: the scenario tests nothing";
  // In a rig that mixes them (mixed), a target without codes is held to the geometry bound.
  auto bound_of = [&](int id) {
    for (const Target& t : scenario->targets.targets)
      if (t.id == id && std::none_of(t.markers.begin(), t.markers.end(), [](const Marker& m) { return m.code; }))
        return std::min(latency_bound, geometry_bound);
    return latency_bound;
  };
  for (const TargetEvaluation& t : e.targets) EXPECT_LE(t.max_latency_frames, bound_of(t.target)) << "target " << t.target;
  EXPECT_LE(all.position_m.mean, a.max_position_m);
  EXPECT_LE(all.orientation_rad.mean, a.max_orientation_deg * kDeg);
  ASSERT_GE(oracle.pairs, 5u) << "too few frames where the oracle saw enough markers";
  EXPECT_LE(oracle.localizer.position_m, 1.5 * oracle.oracle.position_m);
  EXPECT_LE(oracle.localizer.orientation_rad, 1.5 * oracle.oracle.orientation_rad);

  // Through an occlusion of one marker, a target tracked before keeps its pose.
  int occluded_frames = 0, occlusions = 0;
  for (size_t t = 0; t < scenario->simulation.size(); ++t) {
    const int id = scenario->targets.targets[t].id;
    for (size_t f = 1; f < run->frames.size(); ++f) {
      const FrameRecord& frame = run->frames[f];
      int hidden = 0;
      for (const sim::TimeIntervals& occluded : scenario->simulation[t].occluded) {
        bool any = false;
        occluded.split(frame.timestamp_ns, frame.timestamp_ns + frame.exposure_ns,
                       [&](int64_t, int64_t, bool inside) { any = any || inside; });
        hidden += any;
      }
      if (f == 1)
        for (const sim::TimeIntervals& occluded : scenario->simulation[t].occluded)
          occlusions += int(occluded.intervals().size());
      if (hidden != 1) continue;
      const auto had = [&](int64_t frame_number) {
        for (const PoseRecord& p : run->poses)
          if (p.frame == frame_number && p.target == id) return true;
        return false;
      };
      if (!had(run->frames[f - 1].frame)) continue;
      ++occluded_frames;
      EXPECT_TRUE(had(frame.frame)) << "target " << id << " lost in frame " << frame.frame << " (one marker hidden)";
    }
  }
  std::printf("%s: %d frames with one marker of a tracked target occluded\n", a.scenario, occluded_frames);
  if (occlusions > 0) {
    EXPECT_GT(occluded_frames, 0) << "the occlusions fall outside the CI-sized run";
  }
}

INSTANTIATE_TEST_SUITE_P(Builtin, Scenarios, ::testing::ValuesIn(kScenarios), test_name<Acceptance>);

void PrintTo(const OpenRow& r, std::ostream* os) { *os << r.scenario; }

class OpenScenarios : public ::testing::TestWithParam<OpenRow> {};

TEST_P(OpenScenarios, HoldWhatTheyReachToday) {
  const OpenRow& r = GetParam();
  auto scenario = sim::load_scenario(r.scenario);
  ASSERT_TRUE(scenario) << scenario.error().what();
  const auto run = run_scenario(*scenario, scenario->seed, scenario->frames.ci_count);
  ASSERT_TRUE(run) << run.error();
  const TargetEvaluation& all = run->evaluation.overall;
  std::printf("%s (open: %s): %zu frames, %zu poses; mean error %.2f mm / %.3f deg; coverage %.4f (%zu of %zu); "
              "misidentified %zu; max latency %lld frames; largest error %.1f mm\n",
              r.scenario, r.open, run->frames.size(), all.rows, 1e3 * all.position_m.mean,
              all.orientation_rad.mean / kDeg, all.coverage(), all.covered_frames, all.visible_frames,
              all.misidentified, (long long)all.max_latency_frames, 1e3 * all.position_m.max);
  EXPECT_GT(all.visible_frames_total, 0u) << "no target visible: the scenario tests nothing";
  EXPECT_GE(all.coverage(), r.min_coverage);
  EXPECT_LE(all.misidentified, r.max_misidentified);
  EXPECT_LE(all.position_m.max, r.max_position_m);
}

INSTANTIATE_TEST_SUITE_P(Open, OpenScenarios, ::testing::ValuesIn(kOpenRows), test_name<OpenRow>);

TEST(Scenarios, PaperExp1WithKalmanPredictionAndKneipP3P) {
  // The options beside the defaults: the constant-velocity Kalman filter and the
  // paper's P3P solver (Kneip 2011) hold the same lines as the defaults.
  auto scenario = sim::load_scenario("paper-exp1");
  ASSERT_TRUE(scenario) << scenario.error().what();
  LocalizerOptions options;
  options.prediction.model = PredictionModel::kConstantVelocity;
  options.p3p = P3PSolver::kKneip;
  const auto run = run_scenario(*scenario, scenario->seed, scenario->frames.ci_count, options);
  ASSERT_TRUE(run) << run.error();
  const TargetEvaluation& all = run->evaluation.overall;
  std::printf("paper-exp1 (kalman, kneip): %zu poses; mean error %.2f mm / %.3f deg; coverage %.4f; misidentified %zu\n",
              all.rows, 1e3 * all.position_m.mean, all.orientation_rad.mean / kDeg, all.coverage(), all.misidentified);
  EXPECT_EQ(all.misidentified, 0u);
  EXPECT_GE(all.coverage(), 0.99);
  EXPECT_LE(all.max_latency_frames, run->code_length_frames);
  EXPECT_LE(all.position_m.mean, 0.005);
  EXPECT_LE(all.orientation_rad.mean, 0.3 * kDeg);
}

TEST(Scenarios, SwarmWithFrequencyAndBinaryCodesNeverConfusesThem) {
  // Issue 8: both code families in one rig. swarm (synchronized, a bit a frame, on_off)
  // with robots 3 and 4 blinking square waves on all four markers instead of binary
  // words: 1100 (0.25 cycle per frame) and 111000 (1/6). Each robot is found by its
  // own family, and no track is ever given a code of the other.
  auto scenario = sim::load_scenario("swarm");
  ASSERT_TRUE(scenario) << scenario.error().what();
  ASSERT_EQ(scenario->targets.targets.size(), 4u);
  const char* const waves[] = {"1100", "111000"};
  for (size_t t = 2; t < 4; ++t) {
    std::string why;
    const auto code = parse_code(waves[t - 2], &why);
    ASSERT_TRUE(code) << why;
    for (Marker& m : scenario->targets.targets[t].markers) m.code = *code;
  }
  const auto run = run_scenario(*scenario, scenario->seed, 90);
  ASSERT_TRUE(run) << run.error();
  const Evaluation& e = run->evaluation;
  for (const TargetEvaluation& t : e.targets) {
    std::printf("mixed swarm, target %d: %zu poses, coverage %.4f, first latency %lld frames, misidentified %zu\n",
                t.target, t.rows, t.coverage(), (long long)t.first_latency_frames.value_or(-1), t.misidentified);
    EXPECT_GT(t.rows, 0u) << "target " << t.target << " never identified";
    EXPECT_EQ(t.misidentified, 0u) << "target " << t.target;
    EXPECT_GE(t.coverage(), 0.99) << "target " << t.target;
  }
  // Binary words within one code length; square waves within two of the slowest apparent period (6 frames).
  EXPECT_LE(e.targets[0].max_latency_frames, run->code_length_frames);
  EXPECT_LE(e.targets[1].max_latency_frames, run->code_length_frames);
  EXPECT_LE(e.targets[2].max_latency_frames, frequency_latency_bound(*scenario));
  EXPECT_LE(e.targets[3].max_latency_frames, frequency_latency_bound(*scenario));
}

TEST(Scenarios, EveryBuiltinIsCovered) {
  for (const sim::BuiltinScenario& b : sim::builtin_scenarios()) {
    bool found = false;
    for (const Acceptance& a : kScenarios) found = found || b.name == a.scenario;
    for (const OpenRow& r : kOpenRows) {
      EXPECT_FALSE(found && b.name == r.scenario) << b.name << " is both accepted and open";
      found = found || b.name == r.scenario;
    }
    EXPECT_TRUE(found) << b.name << ": neither in kScenarios nor in kOpenRows";
  }
}

}  // namespace
}  // namespace tetrapulse::system_testing

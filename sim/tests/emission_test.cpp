// Emission over exposure windows: the contract's bit formula, board clocks that
// drift, occlusions, flickering lamps, and a rendered exposure that straddles a bit edge.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "tetrapulse/protocol/timebase.hpp"
#include "tetrapulse/sim/code_emitter.hpp"
#include "tetrapulse/sim/flicker_emitter.hpp"
#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/occluded_emitter.hpp"

namespace tetrapulse::sim {
namespace {

Target target_with_codes(const char* c0, const char* c1 = "10", const char* c2 = "1100", const char* c3 = "1") {
  Target t;
  t.id = 1;
  t.marker_diameter_m = 0.03;
  const char* codes[] = {c0, c1, c2, c3};
  for (int m = 0; m < 4; ++m) t.markers[static_cast<size_t>(m)].code = parse_code(codes[m], nullptr);
  return t;
}

Timebase timebase(int64_t epoch, int64_t period) {
  Timebase tb;
  tb.epoch_ns = epoch;
  tb.bit_period_ns = period;
  return tb;
}

Modulation two_level(double low) { return Modulation{ModulationKind::kTwoLevel, low}; }

// Mean emission by summing the contract's formula at `steps` evenly spaced instants (midpoint rule).
double brute_force_mean(const Code& code, const Timebase& tb, double low, const BoardClock& clock, int64_t t0,
                        int64_t t1, int steps) {
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double t = t0 + (t1 - t0) * (i + 0.5) / steps;
    const double b = clock.board_time(t);
    const auto n = static_cast<int64_t>(std::floor((b - tb.epoch_ns) / tb.bit_period_ns));
    sum += code.bit(static_cast<uint32_t>(protocol::floor_mod(n, code.length))) ? 1.0 : low;
  }
  return sum / steps;
}

TEST(CodeEmitter, AWindowInsideOneBitPlaysThatBit) {
  const Timebase tb = timebase(-3'000'000, 10'000'000);
  const CodeEmitter e(tb, two_level(0.25), target_with_codes("1101001110"), BoardClock{});
  const protocol::TimeBase ptb{tb.epoch_ns, tb.bit_period_ns};
  const Code code = *parse_code("1101001110", nullptr);
  for (int64_t k = -25; k < 25; ++k) {
    const int64_t t0 = k * 10'000'000 + 1'000'000;  // [t0, t0 + 2 ms) lies inside one bit
    const double expected = code.bit(protocol::bit_index(ptb, t0, code.length)) ? 1.0 : 0.25;
    EXPECT_DOUBLE_EQ(e.mean_emission(0, t0, t0 + 2'000'000), expected) << "frame " << k;
  }
}

TEST(CodeEmitter, ConstantModulationAndMarkersWithoutCodeEmitFully) {
  Target t = target_with_codes("0000000001");
  t.markers[3].code.reset();
  const CodeEmitter constant(timebase(0, 1000), Modulation{ModulationKind::kConstant, 0}, t, BoardClock{});
  EXPECT_DOUBLE_EQ(constant.mean_emission(0, 0, 5000), 1.0);
  const CodeEmitter on_off(timebase(0, 1000), Modulation{ModulationKind::kOnOff, 0}, t, BoardClock{});
  EXPECT_DOUBLE_EQ(on_off.mean_emission(0, 0, 1000), 0.0);
  EXPECT_DOUBLE_EQ(on_off.mean_emission(3, 0, 1000), 1.0);
}

// Any window, any clock: the exact mean equals the formula integrated by brute force.
RC_GTEST_PROP(CodeEmitter, MeanIsTheFormulaIntegrated, ()) {
  const int64_t period = *rc::gen::inRange<int64_t>(1000, 20000);
  const int64_t epoch = *rc::gen::inRange<int64_t>(-50000, 50000);
  const Timebase tb = timebase(epoch, period);
  const char* code_text = *rc::gen::element("110100111001", "10", "111000111111010", "0110");
  BoardClockSpec spec;
  spec.free_running = *rc::gen::arbitrary<bool>();
  spec.drift_ppm = *rc::gen::inRange(-200, 201) * 100.0;  // exaggerated so that drift shows within the window
  spec.offset_ns = *rc::gen::inRange<int64_t>(-30000, 30000);
  if (!spec.free_running) spec.sync_loss = TimeIntervals({{*rc::gen::inRange<int64_t>(0, 40000), 90000}});
  const BoardClock clock(spec);
  const double low = 0.3;
  const CodeEmitter e(tb, two_level(low), target_with_codes(code_text), clock);
  const int64_t t0 = *rc::gen::inRange<int64_t>(-100000, 100000);
  const int64_t t1 = t0 + *rc::gen::inRange<int64_t>(1, 80000);
  const double exact = e.mean_emission(0, t0, t1);
  const int steps = 200000;
  const double brute = brute_force_mean(*parse_code(code_text, nullptr), tb, low, clock, t0, t1, steps);
  // The midpoint rule misplaces each edge by at most half a step.
  const double edges = static_cast<double>(t1 - t0) / (period * (1 - 0.021)) + 3;
  RC_ASSERT(std::abs(exact - brute) <= edges * (1 - low) / steps + 1e-12);
}

TEST(CodeEmitter, LongWindowsAverageTheWholeCode) {
  const CodeEmitter e(timebase(0, 1000), two_level(0.5), target_with_codes("1100000000"), BoardClock{});
  // 1000 whole cycles of 10 bits: two at 1, eight at 0.5.
  EXPECT_NEAR(e.mean_emission(0, 123, 123 + 10'000'000), 0.6, 1e-9);
}

TEST(BoardClock, FreeRunningBoardPlaysBitsOffByItsCrystalError) {
  BoardClockSpec spec;
  spec.free_running = true;
  spec.drift_ppm = 150;
  spec.offset_ns = 3'712'345;
  const BoardClock clock(spec);
  // Board time runs 150 ppm fast: its bit edges come every T / (1 + 150e-6) of rig time.
  const double T = 10'000'000;
  const double rig_period = T / (1 + 150e-6);
  const double t_edge0 = (0 - spec.offset_ns) / (1 + 150e-6);  // rig time of board time 0
  for (int n = 1; n < 1000; n += 97) {
    const double rig_edge = t_edge0 + n * rig_period;
    EXPECT_NEAR(clock.board_time(rig_edge), n * T, 1e-3);
  }
}

TEST(BoardClock, SyncLossDriftsAndRelocks) {
  BoardClockSpec spec;
  spec.drift_ppm = 100;
  spec.offset_ns = 500;
  spec.sync_loss = TimeIntervals({{1'000'000'000, 3'000'000'000}});
  const BoardClock clock(spec);
  EXPECT_DOUBLE_EQ(clock.board_time(0.5e9), 0.5e9 + 500);
  // 1.5 s into the loss the board has gained 150 us.
  EXPECT_NEAR(clock.board_time(2.5e9) - (2.5e9 + 500), 150'000, 1e-3);
  EXPECT_DOUBLE_EQ(clock.board_time(3.5e9), 3.5e9 + 500);
}

TEST(OccludedEmitter, HiddenTimeCountsAsDark) {
  auto inner = std::make_unique<CodeEmitter>(timebase(0, 1000), Modulation{ModulationKind::kConstant, 0},
                                             target_with_codes("1"), BoardClock{});
  std::vector<TimeIntervals> hidden(4);
  hidden[2] = TimeIntervals({{2500, 3250}});
  const OccludedEmitter e(std::move(inner), hidden);
  EXPECT_DOUBLE_EQ(e.mean_emission(2, 2000, 4000), 1 - 750.0 / 2000);
  EXPECT_DOUBLE_EQ(e.mean_emission(1, 2000, 4000), 1.0);
  EXPECT_DOUBLE_EQ(e.mean_emission(2, 2600, 3000), 0.0);
}

TEST(FlickerEmitter, MeansOverWholeCyclesAreTheDutyOrTheMidLevel) {
  const FlickerEmitter square(Flicker{Flicker::Kind::kSquare, 100, 0.3, 1.0, 0.25});
  const FlickerEmitter sine(Flicker{Flicker::Kind::kSine, 100, 0.5, 0.8, 0.1});
  for (int64_t t0 : {int64_t{0}, int64_t{1'234'567}, int64_t{987'654'321'000}}) {
    EXPECT_NEAR(square.mean_emission(0, t0, t0 + 50'000'000), 0.3, 1e-9);  // five cycles
    EXPECT_NEAR(sine.mean_emission(0, t0, t0 + 30'000'000), 1 - 0.8 / 2, 1e-9);
  }
  // A window inside the on part of a cycle (phase 0.25: on for cycle fractions [0.75, 1.05)).
  EXPECT_NEAR(square.mean_emission(0, 8'000'000, 9'000'000), 1.0, 1e-9);
  EXPECT_NEAR(square.mean_emission(0, 1'000'000, 6'000'000), 0.0, 1e-9);
}

// A still LED, exposure straddling a bit edge: the frame's light is the
// time-weighted mix of the two bits' levels.
TEST(FrameRenderer, ExposureStraddlingABitEdgeMixesBothLevels) {
  CameraInfo info;
  info.width = 96;
  info.height = 64;
  info.fx = info.fy = 80;
  info.cx = 47.5;
  info.cy = 31.5;
  Scene scene;
  scene.camera = LensProjector(info);
  scene.bodies.emplace_back();
  const Timebase tb = timebase(0, 10'000'000);
  const double low = 0.3;
  scene.emitters.push_back(std::make_unique<CodeEmitter>(tb, two_level(low), target_with_codes("10"), BoardClock{}));
  LightSphere light;
  light.position_m = Eigen::Vector3d(0.01, -0.02, 0.5);
  light.radius_m = 0.015;
  light.radiance_e_per_ms = 100;
  scene.lights.push_back(light);
  SensorModel sensor(info.width, info.height, SensorConfig{}, 1);
  FrameRenderer renderer(scene, RenderSettings{}, sensor);
  const auto total = [&](int64_t t0, int64_t exposure) {
    cv::Mat light_e(info.height, info.width, CV_32F, cv::Scalar(0));
    renderer.add_light(t0, exposure, &light_e);
    return cv::sum(light_e)[0];
  };
  const int64_t exposure = 2'000'000;
  const double full = total(1'000'000, exposure);  // inside bit 0 ('1')
  const double dim = total(11'000'000, exposure);  // inside bit 1 ('0')
  EXPECT_NEAR(dim / full, low, 1e-6);
  for (int64_t before_edge : {100'000, 500'000, 1'000'000, 1'337'000, 1'900'000}) {
    // Exposure [edge - before_edge, edge - before_edge + exposure) across the 1 -> 0 edge at 10 ms.
    const double f = static_cast<double>(before_edge) / exposure;
    const double mixed = total(10'000'000 - before_edge, exposure);
    EXPECT_NEAR(mixed / full, f + (1 - f) * low, 0.01 * (f + (1 - f) * low)) << before_edge;
    EXPECT_NEAR(mixed / full, f + (1 - f) * low, 1e-5) << before_edge;  // in fact exact
  }
}

}  // namespace
}  // namespace tetrapulse::sim

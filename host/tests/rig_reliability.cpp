#include "rig_reliability.hpp"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "tetrapulse/sim/frame_renderer.hpp"
#include "tetrapulse/sim/scenario_yaml.hpp"
#include "tetrapulse/sim/scene_builder.hpp"
#include "tetrapulse/sim/sensor_model.hpp"

namespace tetrapulse::host::testing {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

}  // namespace

sim::Scenario mixed_sync_scenario(size_t targets) {
  auto loaded = sim::load_scenario("swarm");
  if (!loaded) {
    std::fprintf(stderr, "%s\n", loaded.error().what().c_str());
    std::abort();
  }
  sim::Scenario s = *loaded;
  const sim::BoardSync syncs[] = {sim::BoardSync::kGpio, sim::BoardSync::kCan, sim::BoardSync::kGpio,
                                  sim::BoardSync::kCan};
  s.targets.targets.resize(std::min(targets, s.targets.targets.size()));
  s.simulation.resize(s.targets.targets.size());
  for (size_t i = 0; i < s.simulation.size(); ++i) {
    sim::BoardClockSpec& c = s.simulation[i].clock;
    c.sync = syncs[i % 4];
    c.free_running = c.sync == sim::BoardSync::kNone;
    c.sync_loss = {};
  }
  return s;
}

int64_t board_clock_error_ns(const sim_board::SimBoard& board) {
  const fw::Firmware* f = board.firmware();
  if (f == nullptr) return INT64_MAX;
  return f->board().sync().servo().to_rig(board.tick()) - board.now();
}

struct RigCamera::Parts {
  Parts(const sim::Scenario& s, const std::shared_ptr<HostSyncedRig>& rig)
      : scenario(s),
        scene(sim::build_scene(s, s.seed, host_board_emitters(rig))),
        sensor(s.camera.width, s.camera.height, s.sensor, s.seed),
        renderer(scene, s.render, sensor),
        localizer(s.camera, s.targets) {}
  sim::Scenario scenario;
  sim::Scene scene;
  sim::SensorModel sensor;
  sim::FrameRenderer renderer;
  Localizer localizer;
  cv::Mat image;
};

RigCamera::RigCamera(const sim::Scenario& scenario, const std::shared_ptr<HostSyncedRig>& rig)
    : parts_(std::make_unique<Parts>(scenario, rig)) {}

RigCamera::~RigCamera() = default;

std::optional<std::vector<TargetPose>> RigCamera::localize(int64_t frame) {
  const sim::FrameSchedule& fs = parts_->scenario.frames;
  const int64_t t0 = fs.start_ns + frame * fs.period_ns;
  parts_->renderer.render(t0, fs.exposure_ns, static_cast<uint64_t>(frame), &parts_->image);
  auto poses = parts_->localizer.process(parts_->image, t0, fs.exposure_ns);
  if (!poses) return std::nullopt;
  return *poses;
}

long resident_kib() {
  FILE* statm = std::fopen("/proc/self/statm", "r");
  if (statm == nullptr) return -1;
  long pages = 0, resident = 0;
  const int got = std::fscanf(statm, "%ld %ld", &pages, &resident);
  std::fclose(statm);
  return got == 2 ? resident * (::sysconf(_SC_PAGESIZE) / 1024) : -1;
}

long heap_in_use_kib() {
  const struct mallinfo2 m = ::mallinfo2();
  return static_cast<long>((m.uordblks + m.hblkhd) / 1024);
}

SoakReport soak(const sim::Scenario& scenario, int64_t rig_seconds, int burst_frames,
                void (*progress)(const std::string&)) {
  SoakReport report;
  report.rig_seconds = rig_seconds;
  auto created = HostSyncedRig::create(scenario);
  if (!created) {
    report.failure = created.error().what();
    return report;
  }
  HostSyncedRig& rig = **created;
  RigCamera camera(scenario, *created);
  SoakLocalizer& loc = report.localizer;
  const auto localize_burst = [&](int64_t first_frame) {
    loc.burst_poses.push_back(0);
    for (int k = 0; k < burst_frames; ++k) {
      const int64_t frame = first_frame + k;
      ++loc.frames;
      const auto poses = camera.localize(frame);
      if (!poses) {
        ++loc.frame_errors;
        continue;
      }
      loc.poses += poses->size();
      if (k < SoakLocalizer::kSettleFrames) continue;
      loc.burst_poses.back() += poses->size();
    }
  };
  report.boards.resize(rig.boards());
  std::vector<bool> locked_once(rig.boards(), false);
  for (size_t i = 0; i < rig.boards(); ++i) report.boards[i].sync = scenario.simulation[i].clock.sync;
  const int64_t start = scenario.frames.start_ns;
  const bool any_gpio = std::any_of(report.boards.begin(), report.boards.end(),
                                    [](const SoakBoard& b) { return b.sync == sim::BoardSync::kGpio; });
  for (int64_t second = 1; second <= rig_seconds; ++second) {
    const int64_t t = start + second * kSecond;
    if (burst_frames > 0 && (second - 1) % 60 == 0) {
      localize_burst(((second - 1) * kSecond + scenario.frames.period_ns - 1) / scenario.frames.period_ns);
    }
    rig.run_until(t);
    if (rig.failure()) {
      report.failure = rig.failure()->what();
      return report;
    }
    for (size_t i = 0; i < rig.boards(); ++i) {
      SoakBoard& b = report.boards[i];
      auto status = rig.host_board(i).status();
      if (!status) {
        ++b.status_failures;
        continue;
      }
      if (b.sync == sim::BoardSync::kNone) continue;
      const bool locked = status->sync_state == protocol::SyncState::kLocked;
      // The first seconds after frame 0 settle the lock the lead-in acquired.
      if (locked && second > 2) locked_once[i] = true;
      if (!locked_once[i]) continue;
      if (!locked) ++b.not_locked;
      b.max_abs_error_ns = std::max(b.max_abs_error_ns, std::abs(board_clock_error_ns(rig.board(i))));
    }
    for (size_t i = 0; i < rig.boards(); ++i) report.boards[i].led_changes += rig.board(i).leds().log().size();
    rig.forget_before(t);
    for (size_t i = 0; i < rig.boards(); ++i) {
      // What forget_before kept: each marker's level at t (counted again next second).
      report.boards[i].led_changes -= rig.board(i).leds().log().size();
    }
    if (second == 60) {
      report.rss_kib_after_warmup = resident_kib();
      report.heap_kib_after_warmup = heap_in_use_kib();
    }
    if (progress != nullptr && second % 60 == 0) {
      progress(fmt::format("rig {} s: {} exposures, {} CAN syncs, {} frames localized, {} poses, heap {} KiB, RSS {} KiB",
                           second, rig.exposure_count(), rig.can_syncs(), loc.frames, loc.poses, heap_in_use_kib(),
                           resident_kib()));
    }
  }
  report.exposures = rig.exposure_count();
  // Frames 0 .. whose exposure started by the end (frame 0 at start).
  report.expected_exposures =
      any_gpio ? static_cast<uint64_t>((rig_seconds * kSecond) / scenario.frames.period_ns + 1) : 0;
  report.can_syncs = rig.can_syncs();
  report.rss_kib_end = resident_kib();
  report.heap_kib_end = heap_in_use_kib();
  return report;
}

}  // namespace tetrapulse::host::testing

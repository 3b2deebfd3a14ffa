#include "tetrapulse/host/sim_rig.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "tetrapulse/host/sim_board_link.hpp"
#include "tetrapulse/host/sim_can_bus.hpp"
#include "tetrapulse/host/sim_sync_line.hpp"

namespace tetrapulse::host {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kSecond = 1'000'000'000;

// Whether the board hears its sync at rig time t (not during its sync loss).
std::function<bool(int64_t)> connected(const sim::TimeIntervals& sync_loss) {
  return [sync_loss](int64_t t) { return sync_loss.find(t) == nullptr; };
}

class HostBoardEmitter : public sim::LedEmitter {
 public:
  HostBoardEmitter(std::shared_ptr<HostSyncedRig> rig, size_t index) : rig_(std::move(rig)), index_(index) {}

 private:
  double do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const override {
    if (index < 0 || index >= 4 || t1_ns <= t0_ns) return 0.0;
    rig_->run_until(t1_ns);
    return rig_->board(index_).leds().mean_duty(static_cast<uint8_t>(index), static_cast<long double>(t0_ns),
                                                static_cast<long double>(t1_ns));
  }

  std::shared_ptr<HostSyncedRig> rig_;
  size_t index_;
};

}  // namespace

HostResult<std::shared_ptr<HostSyncedRig>> HostSyncedRig::create(const sim::Scenario& scenario,
                                                                 const sim::FirmwareEmitterOptions& options) {
  std::shared_ptr<HostSyncedRig> rig(new HostSyncedRig());
  if (auto done = rig->set_up(scenario, options); !done) return tl::unexpected(done.error());
  return rig;
}

HostSyncedRig::~HostSyncedRig() = default;

HostResult<void> HostSyncedRig::set_up(const sim::Scenario& scenario, const sim::FirmwareEmitterOptions& options) {
  const TargetsFile& targets = scenario.targets;
  const sim::FrameSchedule& frames = scenario.frames;
  const int64_t power_on = frames.start_ns - options.lead_in_ns;
  auto bus = std::make_unique<SimCanBus>();
  SimSyncLine* line = nullptr;
  std::unique_ptr<SimSyncLine> owned_line;
  bool any_can = false;
  for (size_t i = 0; i < targets.targets.size(); ++i) {
    const sim::BoardClockSpec& clock = scenario.simulation[i].clock;
    auto sim = std::make_shared<sim_board::SimBoard>(sim::firmware_board_options(scenario, i, options));
    sim->advance_to(power_on + 10 * kMs);
    auto board = std::make_unique<Board>(
        std::make_unique<SimLink>(fmt::format("sim:{}", sim->options().node_id), sim_board_port(sim)));

    // What `tetrapulse config --file boards/target-N.yaml` would give this board.
    // (target_board_config of the scenario's targets, with the board's own epoch and, for
    // GPIO, pulse k of the trigger = frame k's exposure start.)
    const protocol::Config config = sim::firmware_board_config(scenario, i, power_on);
    if (auto done = board->configure(config); !done) return tl::unexpected(done.error());

    if (clock.sync == sim::BoardSync::kCan) {
      auto latency = std::make_shared<sim::CanSyncLatency>(options, i);
      bus->attach(sim, [latency] { return latency->next(); }, connected(clock.sync_loss));
      any_can = true;
    } else if (clock.sync == sim::BoardSync::kGpio) {
      if (!owned_line) {
        owned_line = std::make_unique<SimSyncLine>("gpio:sim-trigger", power_on,
                                                   [this](int64_t t) { run_others_until(t); });
        line = owned_line.get();
      }
      line->attach(sim, connected(clock.sync_loss));
      gpio_boards_.push_back(i);
    }
    sims_.push_back(std::move(sim));
    boards_.push_back(std::move(board));
  }

  if (any_can) {
    // The first Sync a tenth of a second after power-up, then at the configured rate.
    bus_ = bus.get();
    can_period_ns_ = options.can_sync_period_ns;
    next_can_ns_ = power_on + 100 * kMs;
    const RigClock clock = bus->rig_clock();
    CanSyncOptions o;
    o.period_ns = can_period_ns_;
    can_ = std::make_unique<CanSync>(std::move(bus), clock, o);
  }
  if (owned_line) {
    GpioTriggerOptions o;
    o.line.line = "sim-trigger";
    o.frame_period_ns = frames.period_ns;
    o.exposure_ns = frames.exposure_ns;
    o.first_edge_ns = sim::firmware_first_sync_edge_ns(scenario, options);
    auto trigger = GpioSync::trigger(o, std::move(owned_line));
    if (!trigger) return tl::unexpected(trigger.error());
    trigger_ = std::move(*trigger);
    pulse_period_ns_ = frames.period_ns;
    next_pulse_ns_ = *o.first_edge_ns;
    frame0_ns_ = frames.start_ns;
    next_coarse_ns_ = *o.first_edge_ns - kSecond / 2;
  }
  return {};
}

void HostSyncedRig::run_others_until(int64_t rig_ns) {
  // A Sync at its transmit time, its FollowUp a turnaround later, in one go.
  for (; can_ && !failure_ && next_can_ns_ <= rig_ns; next_can_ns_ += can_period_ns_) {
    bus_->set_time(next_can_ns_);
    auto sent = can_->send_one();
    if (!sent) {
      failure_ = sent.error();
      break;
    }
    ++can_syncs_;
  }
  // Coarse time for the boards on the trigger line: the rig time the FollowUp names,
  // delivered over the board's own link sim::kCoarseTimeLatencyNs later.
  for (; !gpio_boards_.empty() && next_coarse_ns_ + sim::kCoarseTimeLatencyNs <= rig_ns; next_coarse_ns_ += kSecond) {
    const protocol::Message coarse{0, protocol::FollowUp{coarse_seq_++, next_coarse_ns_}};
    for (size_t i : gpio_boards_) {
      sims_[i]->advance_to(next_coarse_ns_ + sim::kCoarseTimeLatencyNs);
      if (auto sent = boards_[i]->link().send(coarse); !sent && !failure_) failure_ = sent.error();
    }
  }
  for (auto& sim : sims_) sim->advance_to(rig_ns);
}

void HostSyncedRig::run_until(int64_t rig_ns) {
  static const std::atomic<bool> kNeverStop{false};
  for (; trigger_ && !failure_ && next_pulse_ns_ <= rig_ns; next_pulse_ns_ += pulse_period_ns_) {
    auto pulsed = trigger_->run(kNeverStop, 1, [&](const Exposure& e) {
      if (e.timestamp_ns < frame0_ns_) return;  // the lead-in
      Exposure frame = e;
      frame.frame = (e.timestamp_ns - frame0_ns_ + pulse_period_ns_ / 2) / pulse_period_ns_;
      exposures_.push_back(frame);
    });
    if (!pulsed) failure_ = pulsed.error();
  }
  run_others_until(rig_ns);
}

void HostSyncedRig::forget_before(int64_t rig_ns) {
  const auto first_kept = std::partition_point(exposures_.begin(), exposures_.end(),
                                               [rig_ns](const Exposure& e) { return e.timestamp_ns < rig_ns; });
  forgotten_exposures_ += static_cast<uint64_t>(first_kept - exposures_.begin());
  exposures_.erase(exposures_.begin(), first_kept);
  for (auto& sim : sims_) sim->forget_led_changes_before(rig_ns);
}

sim::BoardEmitterFactory host_board_emitters(std::shared_ptr<HostSyncedRig> rig) {
  return [rig](const sim::Scenario& /*scenario*/, size_t index) -> std::unique_ptr<sim::LedEmitter> {
    return std::make_unique<HostBoardEmitter>(rig, index);
  };
}

HostResult<sim::SimulationSummary> simulate_with_host_boards(const sim::Scenario& scenario,
                                                             sim::SimulationOptions options,
                                                             const sim::FirmwareEmitterOptions& boards) {
  auto rig = HostSyncedRig::create(scenario, boards);
  if (!rig) return tl::unexpected(rig.error());
  options.board = host_board_emitters(*rig);
  auto summary = sim::simulate_dataset(scenario, options);
  if (!summary) return host_error(HostErrorKind::kBadFile, summary.error().file, summary.error().what());
  if ((*rig)->failure()) return tl::unexpected(*(*rig)->failure());
  return *summary;
}

}  // namespace tetrapulse::host

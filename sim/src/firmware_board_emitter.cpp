#include "tetrapulse/sim/firmware_board_emitter.hpp"

#include <cmath>

#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/target_config.hpp"
#include "tetrapulse/sim/scene_builder.hpp"

namespace tetrapulse::sim {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kSecond = 1'000'000'000;

uint64_t splitmix(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

sim_board::SimBoardOptions firmware_board_options(const Scenario& scenario, size_t index,
                                                  const FirmwareEmitterOptions& options) {
  sim_board::SimBoardOptions o;
  o.clock_ppm = scenario.simulation[index].clock.drift_ppm;
  o.power_on_ns = scenario.frames.start_ns - options.lead_in_ns;
  o.node_id = protocol::target_node_id(index);
  for (size_t i = 0; i < o.serial.size(); ++i) o.serial[i] = static_cast<uint8_t>((index + 1) * 37 + i);
  return o;
}

protocol::Config firmware_board_config(const Scenario& s, size_t index, int64_t power_on_ns) {
  const Target& target = s.targets.targets[index];
  const BoardClockSpec& clock = s.simulation[index].clock;
  const protocol::SyncSource sync = clock.sync == BoardSync::kGpio  ? protocol::SyncSource::kGpio
                                    : clock.sync == BoardSync::kCan ? protocol::SyncSource::kCan
                                                                    : protocol::SyncSource::kNone;
  protocol::Config c = protocol::target_config(static_cast<uint16_t>(target.id), target.codes(), s.targets.modulation,
                                               s.targets.timebase, index, sync);
  // The board's own epoch: its clock's offset (and, free-running, its power-on time).
  c.epoch_ns = firmware_board_epoch_ns(s, index, power_on_ns);
  if (clock.sync == BoardSync::kGpio) {
    // Edge k is exposure k's start; k is found from the coarse time of FollowUps, so a
    // board that misses edges (sync loss) still numbers the next ones right.
    c.gpio_edge_period_ns = static_cast<uint32_t>(s.frames.period_ns);
    c.gpio_edge_epoch_ns = s.frames.start_ns;
    c.gpio_edge_numbering = protocol::GpioEdgeNumbering::kNearestCoarseTime;
  }
  return c;
}

int64_t firmware_board_epoch_ns(const Scenario& scenario, size_t index, int64_t power_on_ns) {
  const BoardClockSpec& clock = scenario.simulation[index].clock;
  const long double rate = 1.0L + static_cast<long double>(clock.drift_ppm) * 1e-6L;
  int64_t shift = clock.offset_ns;
  if (clock.free_running) shift += static_cast<int64_t>(std::llround(static_cast<long double>(power_on_ns) * rate));
  return scenario.targets.timebase.epoch_ns - shift;
}

int64_t firmware_first_sync_edge_ns(const Scenario& scenario, const FirmwareEmitterOptions& options) {
  const int64_t lead_edges = (options.lead_in_ns - kSecond) / scenario.frames.period_ns;
  return scenario.frames.start_ns - lead_edges * scenario.frames.period_ns;
}

CanSyncLatency::CanSyncLatency(const FirmwareEmitterOptions& options, size_t index)
    : max_ns_(options.can_latency_ns), state_(options.seed * 0x2545F4914F6CDD1Dull + index) {}

int64_t CanSyncLatency::next() {
  return max_ns_ > 0 ? static_cast<int64_t>(splitmix(&state_) % static_cast<uint64_t>(max_ns_ + 1)) : 0;
}

FirmwareBoardEmitter::FirmwareBoardEmitter(const Scenario& scenario, size_t index, const FirmwareEmitterOptions& options)
    : options_(options),
      sync_(scenario.simulation[index].clock.sync),
      sync_loss_(scenario.simulation[index].clock.sync_loss),
      edge_period_ns_(scenario.frames.period_ns),
      latency_(options, index) {
  const sim_board::SimBoardOptions o = firmware_board_options(scenario, index, options);
  const int64_t power_on = o.power_on_ns;
  board_ = std::make_unique<sim_board::SimBoard>(o);
  host_ = std::make_unique<sim_board::HostPort>(*board_);

  // The first strobe comes a second after power-up, the host's coarse time half a second
  // before it.
  const int64_t first_edge = firmware_first_sync_edge_ns(scenario, options);
  board_->advance_to(power_on + 10 * kMs);
  const protocol::Message set{1, protocol::SetConfig{firmware_board_config(scenario, index, power_on)}};
  const protocol::Result<protocol::Message> answer = host_->request(fw::LinkKind::kUsb, set);
  configured_ = answer.ok() && answer->get<protocol::Ack>() != nullptr;
  next_sync_ns_ = sync_ == BoardSync::kGpio ? first_edge : power_on + 100 * kMs;
  next_coarse_ns_ = first_edge - kSecond / 2;
}

FirmwareBoardEmitter::~FirmwareBoardEmitter() = default;

void FirmwareBoardEmitter::feed_sync_until(int64_t rig_ns) const {
  if (sync_ == BoardSync::kGpio) {
    // Coarse time: a FollowUp over USB every second, 300 us late; its own Sync is not
    // needed for numbering edges.
    constexpr int64_t kUsbLatency = kCoarseTimeLatencyNs;
    const auto coarse_until = [&](int64_t t) {
      for (; next_coarse_ns_ + kUsbLatency <= t; next_coarse_ns_ += kSecond) {
        host_->send(fw::LinkKind::kUsb, protocol::Message{0, protocol::FollowUp{coarse_seq_++, next_coarse_ns_}},
                    next_coarse_ns_ + kUsbLatency);
      }
    };
    for (; next_sync_ns_ <= rig_ns; next_sync_ns_ += edge_period_ns_) {
      coarse_until(next_sync_ns_);
      if (sync_loss_.find(next_sync_ns_) == nullptr) board_->sync_edge(next_sync_ns_);
    }
    coarse_until(rig_ns);
  } else if (sync_ == BoardSync::kCan) {
    // A Sync and its FollowUp (1 ms later) go in together, once both are due.
    for (; next_sync_ns_ + kMs <= rig_ns; next_sync_ns_ += options_.can_sync_period_ns) {
      const uint16_t seq = sync_seq_++;
      if (sync_loss_.find(next_sync_ns_) != nullptr) continue;
      const int64_t latency = latency_.next();
      host_->send(fw::LinkKind::kCan, protocol::Message{0, protocol::Sync{seq}}, next_sync_ns_ + latency);
      host_->send(fw::LinkKind::kCan, protocol::Message{0, protocol::FollowUp{seq, next_sync_ns_}}, next_sync_ns_ + kMs);
    }
  }
}

void FirmwareBoardEmitter::run_until(int64_t rig_ns) const {
  if (rig_ns <= board_->now()) return;
  feed_sync_until(rig_ns);
  board_->advance_to(rig_ns);
}

double FirmwareBoardEmitter::do_mean_emission(int index, int64_t t0_ns, int64_t t1_ns) const {
  if (index < 0 || index >= 4 || t1_ns <= t0_ns) return 0.0;
  run_until(t1_ns);
  return board_->leds().mean_duty(static_cast<uint8_t>(index), static_cast<long double>(t0_ns),
                                  static_cast<long double>(t1_ns));
}

std::unique_ptr<LedEmitter> firmware_board_emitter(const Scenario& scenario, size_t index,
                                                   const FirmwareEmitterOptions& options) {
  auto emitter = std::make_unique<FirmwareBoardEmitter>(scenario, index, options);
  if (!emitter->configured()) return contract_board_emitter(scenario, index);
  return emitter;
}

}  // namespace tetrapulse::sim

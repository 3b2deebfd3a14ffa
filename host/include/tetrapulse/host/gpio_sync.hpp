#pragma once
// The GPIO sync master (DESIGN.md: GPIO sync), through libgpiod 1.6 (uAPI v1):
//  - trigger: drives a camera trigger line, one pulse per frame, the pulse width being the
//    exposure; pulse k rises at rig time first_edge_ns + k * frame_period_ns (scheduled
//    with clock_nanosleep on CLOCK_MONOTONIC), and its exposure is stamped with the time
//    the line was actually set (the middle of the set-value ioctl);
//  - strobe: follows the camera's strobe output (active while the sensor integrates),
//    time-stamping both edges from kernel line events (CLOCK_MONOTONIC in libgpiod 1.6 on
//    Linux >= 5.7).
// Both report exposures in rig time (rig_clock.hpp). The same line drives (or is driven in
// parallel to) the boards' sync inputs, which time-stamp the same edges.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tetrapulse/host/exposure.hpp"
#include "tetrapulse/host/host_error.hpp"
#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {

// A GPIO line: CHIP:LINE with CHIP a gpiochip name, path, label or number and LINE an
// offset or a line name; or a line name alone, looked up on every chip.
struct GpioLineAddress {
  std::string chip;  // empty: find the line by name on every chip
  std::string line;
  std::string text() const { return chip.empty() ? line : chip + ":" + line; }
};
HostResult<GpioLineAddress> parse_gpio_line(const std::string& text);

struct GpioTriggerOptions {
  GpioLineAddress line;
  int64_t frame_period_ns = 33'333'333;
  int64_t exposure_ns = 5'000'000;   // pulse width, < frame_period_ns
  bool active_low = false;           // the camera triggers on a low pulse
  // Rig time of pulse 0; unset: the next whole frame period of rig time after start, so
  // that edges fall at k * frame_period_ns (Config.gpio_edge_epoch_ns 0).
  std::optional<int64_t> first_edge_ns;
};

struct GpioStrobeOptions {
  GpioLineAddress line;
  bool active_low = false;       // the strobe is low while the sensor integrates
  int64_t frame_period_ns = 0;   // > 0: number frames by time, so missed pulses skip numbers
};

// What the sync master needs of its line and of time: a libgpiod line on CLOCK_MONOTONIC
// (GpioSync::trigger/strobe with a RigClock), or a simulated line in simulated rig time (the
// virtual rig, host/sim_rig.hpp). Levels are logical: true = active (a trigger pulse, or
// the strobe while the sensor integrates, active_low already applied).
class GpioSyncLine {
 public:
  struct Edge {
    bool active = false;  // the line became active (else inactive)
    int64_t rig_ns = 0;   // when, in rig time
  };
  virtual ~GpioSyncLine() = default;  // owned through the base (unique_ptr<GpioSyncLine>)
  const std::string& name() const { return do_name(); }  // "gpio:gpiochip0:3"
  int64_t now() const { return do_now(); }                // rig time
  // Waits until rig time `rig_ns`; false when `stop` was set first (checked at least every 100 ms).
  bool sleep_until(int64_t rig_ns, const std::atomic<bool>& stop) { return do_sleep_until(rig_ns, stop); }
  // Output line: sets the level; returns the rig time it took effect.
  HostResult<int64_t> set(bool active) { return do_set(active); }
  // Input line: the edges that come within `timeout_ns` (empty: none).
  HostResult<std::vector<Edge>> wait_edges(int64_t timeout_ns) { return do_wait_edges(timeout_ns); }

 private:
  virtual const std::string& do_name() const = 0;
  virtual int64_t do_now() const = 0;
  virtual bool do_sleep_until(int64_t rig_ns, const std::atomic<bool>& stop) = 0;
  virtual HostResult<int64_t> do_set(bool active) = 0;
  virtual HostResult<std::vector<Edge>> do_wait_edges(int64_t timeout_ns) = 0;
};

class GpioSync {
 public:
  // Opens `options.line` through libgpiod, rig time = CLOCK_MONOTONIC through `clock`.
  static HostResult<std::unique_ptr<GpioSync>> trigger(const GpioTriggerOptions& options, RigClock clock);
  static HostResult<std::unique_ptr<GpioSync>> strobe(const GpioStrobeOptions& options, RigClock clock);
  // Over any line (options.line and active_low are then the line's business).
  static HostResult<std::unique_ptr<GpioSync>> trigger(const GpioTriggerOptions& options,
                                                       std::unique_ptr<GpioSyncLine> line);
  static std::unique_ptr<GpioSync> strobe(const GpioStrobeOptions& options, std::unique_ptr<GpioSyncLine> line);
  ~GpioSync();

  // Runs until `stop` is set (checked at least every 100 ms) or `max_frames` exposures were
  // reported (0: no limit); calls `on_exposure` for each. Returns how many were reported.
  // A later call goes on where this one stopped (trigger: with the next pulse).
  HostResult<uint64_t> run(const std::atomic<bool>& stop, uint64_t max_frames,
                           const std::function<void(const Exposure&)>& on_exposure);

  // Trigger mode: rig time of pulse 0 (for the boards' gpio_edge_epoch_ns).
  int64_t first_edge_ns() const;
  const std::string& line_name() const;
  // For the boards' configuration and logs: "trigger LINE: pulse k rises at rig time F +
  // k * P ns (boards: gpio_edge_epoch_ns F, gpio_edge_period_ns P), E ns wide", or
  // "strobe LINE (active high)".
  std::string schedule_text() const;

 private:
  class Impl;
  explicit GpioSync(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tetrapulse::host

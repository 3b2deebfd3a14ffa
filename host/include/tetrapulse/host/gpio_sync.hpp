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

class GpioSync {
 public:
  static HostResult<std::unique_ptr<GpioSync>> trigger(const GpioTriggerOptions& options, RigClock clock);
  static HostResult<std::unique_ptr<GpioSync>> strobe(const GpioStrobeOptions& options, RigClock clock);
  ~GpioSync();

  // Runs until `stop` is set (checked at least every 100 ms) or `max_frames` exposures were
  // reported (0: no limit); calls `on_exposure` for each. Returns how many were reported.
  HostResult<uint64_t> run(const std::atomic<bool>& stop, uint64_t max_frames,
                           const std::function<void(const Exposure&)>& on_exposure);

  // Trigger mode: rig time of pulse 0 (for the boards' gpio_edge_epoch_ns).
  int64_t first_edge_ns() const;
  const std::string& line_name() const;

 private:
  class Impl;
  explicit GpioSync(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tetrapulse::host

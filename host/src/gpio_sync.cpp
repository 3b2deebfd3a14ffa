#include "tetrapulse/host/gpio_sync.hpp"

#include <time.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <gpiod.hpp>
#include <system_error>

#include <fmt/format.h>

#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::host {
namespace {

constexpr const char* kConsumer = "tetrapulse-sync";
constexpr int64_t kStopCheckNs = 100'000'000;

bool is_number(const std::string& s) {
  return !s.empty() && s.size() < 6 && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// Sleeps until CLOCK_MONOTONIC reaches `monotonic_ns` or `stop` is set; false when stopped.
bool sleep_until_monotonic(int64_t monotonic_ns, const std::atomic<bool>& stop) {
  for (;;) {
    if (stop.load()) return false;
    const int64_t now = monotonic_now_ns();
    if (now >= monotonic_ns) return true;
    const int64_t until = std::min(monotonic_ns, now + kStopCheckNs);
    const timespec t{static_cast<time_t>(until / 1'000'000'000), static_cast<long>(until % 1'000'000'000)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
    }
  }
}

HostError gpio_error(const std::string& line, const std::exception& e, const char* what) {
  const auto* system = dynamic_cast<const std::system_error*>(&e);
  const bool missing = system != nullptr && (system->code().value() == ENOENT || system->code().value() == ENODEV);
  const bool busy = system != nullptr && system->code().value() == EBUSY;
  return HostError{missing ? HostErrorKind::kNotFound : HostErrorKind::kOpenFailed, "gpio:" + line,
                   fmt::format("{}: {}{}", what, e.what(), busy ? " (another program holds the line)" : "")};
}

}  // namespace

HostResult<GpioLineAddress> parse_gpio_line(const std::string& text) {
  const size_t colon = text.rfind(':');
  GpioLineAddress a;
  if (colon == std::string::npos) {
    a.line = text;
  } else {
    a.chip = text.substr(0, colon);
    a.line = text.substr(colon + 1);
  }
  if (a.line.empty() || (colon != std::string::npos && a.chip.empty())) {
    return host_error(HostErrorKind::kBadInput, "gpio:" + text, "expected CHIP:LINE (gpiochip0:3) or a line name");
  }
  return a;
}

namespace {

// A libgpiod 1.6 line on CLOCK_MONOTONIC.
class LibgpiodLine final : public GpioSyncLine {
 public:
  LibgpiodLine(GpioLineAddress address, RigClock clock, bool active_low)
      : address_(std::move(address)), clock_(clock), active_low_(active_low) {}

  HostResult<void> open(int request_type) {
    try {
      if (address_.chip.empty()) {
        line_ = gpiod::find_line(address_.line);
      } else {
        gpiod::chip chip(address_.chip, gpiod::chip::OPEN_LOOKUP);
        line_ = is_number(address_.line) ? chip.get_line(static_cast<unsigned>(std::stoul(address_.line)))
                                         : chip.find_line(address_.line);
      }
      if (!line_) {
        return host_error(HostErrorKind::kNotFound, name_, "no such GPIO line");
      }
      gpiod::line_request request;
      request.consumer = kConsumer;
      request.request_type = request_type;
      // An output line inverts in the kernel; input edges are turned around here.
      if (active_low_ && request_type == gpiod::line_request::DIRECTION_OUTPUT) {
        request.flags = gpiod::line_request::FLAG_ACTIVE_LOW;
      }
      line_.request(request, 0);
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "cannot request the line"));
    }
    return {};
  }

 private:
  const std::string& do_name() const override { return name_; }
  int64_t do_now() const override { return clock_.now(); }
  bool do_sleep_until(int64_t rig_ns, const std::atomic<bool>& stop) override {
    return sleep_until_monotonic(clock_.to_monotonic(rig_ns), stop);
  }
  // The time it took effect is taken as the middle of the set-value ioctl.
  HostResult<int64_t> do_set(bool active) override {
    try {
      const int64_t before = monotonic_now_ns();
      line_.set_value(active ? 1 : 0);
      const int64_t after = monotonic_now_ns();
      return clock_.from_monotonic(before + (after - before) / 2);
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "driving the line"));
    }
  }
  HostResult<std::vector<Edge>> do_wait_edges(int64_t timeout_ns) override {
    std::vector<Edge> edges;
    try {
      if (!line_.event_wait(std::chrono::nanoseconds(timeout_ns))) return edges;
      for (const gpiod::line_event& e : line_.event_read_multiple()) {
        const bool rising = e.event_type == gpiod::line_event::RISING_EDGE;
        edges.push_back(Edge{rising != active_low_, clock_.from_monotonic(e.timestamp.count())});
      }
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "reading line events"));
    }
    return edges;
  }

  GpioLineAddress address_;
  std::string name_ = "gpio:" + address_.text();
  RigClock clock_;
  bool active_low_;
  gpiod::line line_;
};

}  // namespace

class GpioSync::Impl {
 public:
  explicit Impl(std::unique_ptr<GpioSyncLine> line) : line_(std::move(line)) {}

  HostResult<uint64_t> trigger(const std::atomic<bool>& stop, uint64_t max_frames,
                               const std::function<void(const Exposure&)>& report) {
    const int64_t period = trigger_.frame_period_ns;
    uint64_t reported = 0;
    for (; max_frames == 0 || reported < max_frames; ++next_pulse_) {
      // Late by more than half a period (the host was busy): skip to the next pulse on time.
      const int64_t now = line_->now();
      const int64_t due = first_edge_ + next_pulse_ * period;
      if (now > due + period / 2) {
        next_pulse_ = protocol::floor_div(now - first_edge_, period);
        continue;
      }
      if (!line_->sleep_until(due, stop)) break;
      const auto rise = line_->set(true);
      if (!rise) return tl::unexpected(rise.error());
      if (!line_->sleep_until(due + trigger_.exposure_ns, stop)) {
        (void)line_->set(false);
        break;
      }
      const auto fall = line_->set(false);
      if (!fall) return tl::unexpected(fall.error());
      report(Exposure{next_pulse_, *rise, *fall - *rise});
      ++reported;
    }
    return reported;
  }

  HostResult<uint64_t> strobe(const std::atomic<bool>& stop, uint64_t max_frames,
                              const std::function<void(const Exposure&)>& report) {
    uint64_t reported = 0;
    while (!stop.load() && (max_frames == 0 || reported < max_frames)) {
      auto edges = line_->wait_edges(kStopCheckNs);
      if (!edges) return tl::unexpected(edges.error());
      for (const GpioSyncLine::Edge& e : *edges) {
        const auto exposure = pairer_.edge(e.active, e.rig_ns);
        if (!exposure) continue;
        report(*exposure);
        if (++reported == max_frames) break;
      }
    }
    return reported;
  }

  std::unique_ptr<GpioSyncLine> line_;
  bool is_trigger_ = false;
  GpioTriggerOptions trigger_;
  int64_t first_edge_ = 0;
  int64_t next_pulse_ = 0;
  StrobeEdgePairer pairer_;
  bool strobe_active_low_ = false;
};

GpioSync::GpioSync(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GpioSync::~GpioSync() = default;

HostResult<std::unique_ptr<GpioSync>> GpioSync::trigger(const GpioTriggerOptions& options, RigClock clock) {
  auto line = std::make_unique<LibgpiodLine>(options.line, clock, options.active_low);
  if (auto opened = line->open(gpiod::line_request::DIRECTION_OUTPUT); !opened) return tl::unexpected(opened.error());
  return trigger(options, std::move(line));
}

HostResult<std::unique_ptr<GpioSync>> GpioSync::trigger(const GpioTriggerOptions& options,
                                                        std::unique_ptr<GpioSyncLine> line) {
  if (options.frame_period_ns <= 0 || options.exposure_ns <= 0 || options.exposure_ns >= options.frame_period_ns) {
    return host_error(HostErrorKind::kBadInput, line->name(),
                      fmt::format("exposure {} ns must be positive and shorter than the frame period {} ns",
                                  options.exposure_ns, options.frame_period_ns));
  }
  auto impl = std::make_unique<Impl>(std::move(line));
  impl->is_trigger_ = true;
  impl->trigger_ = options;
  // Pulse 0 at the next whole frame period, at least a millisecond away.
  impl->first_edge_ = options.first_edge_ns.value_or(
      (protocol::floor_div(impl->line_->now() + 1'000'000, options.frame_period_ns) + 1) * options.frame_period_ns);
  return std::unique_ptr<GpioSync>(new GpioSync(std::move(impl)));
}

HostResult<std::unique_ptr<GpioSync>> GpioSync::strobe(const GpioStrobeOptions& options, RigClock clock) {
  auto line = std::make_unique<LibgpiodLine>(options.line, clock, options.active_low);
  if (auto opened = line->open(gpiod::line_request::EVENT_BOTH_EDGES); !opened) return tl::unexpected(opened.error());
  return strobe(options, std::move(line));
}

std::unique_ptr<GpioSync> GpioSync::strobe(const GpioStrobeOptions& options, std::unique_ptr<GpioSyncLine> line) {
  auto impl = std::make_unique<Impl>(std::move(line));
  impl->pairer_ = StrobeEdgePairer(options.frame_period_ns);
  impl->strobe_active_low_ = options.active_low;
  return std::unique_ptr<GpioSync>(new GpioSync(std::move(impl)));
}

HostResult<uint64_t> GpioSync::run(const std::atomic<bool>& stop, uint64_t max_frames,
                                   const std::function<void(const Exposure&)>& on_exposure) {
  return impl_->is_trigger_ ? impl_->trigger(stop, max_frames, on_exposure) : impl_->strobe(stop, max_frames, on_exposure);
}

int64_t GpioSync::first_edge_ns() const { return impl_->first_edge_; }

std::string GpioSync::schedule_text() const {
  if (!impl_->is_trigger_) {
    return fmt::format("strobe {} (active {})", line_name(), impl_->strobe_active_low_ ? "low" : "high");
  }
  const int64_t first = impl_->first_edge_, period = impl_->trigger_.frame_period_ns;
  return fmt::format("trigger {}: pulse k rises at rig time {} + k * {} ns (boards: gpio_edge_epoch_ns {}, "
                     "gpio_edge_period_ns {}), {} ns wide",
                     line_name(), first, period, first, period, impl_->trigger_.exposure_ns);
}
const std::string& GpioSync::line_name() const { return impl_->line_->name(); }

}  // namespace tetrapulse::host

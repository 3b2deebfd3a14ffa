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
bool sleep_until(int64_t monotonic_ns, const std::atomic<bool>& stop) {
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

class GpioSync::Impl {
 public:
  Impl(GpioLineAddress address, RigClock clock) : address_(std::move(address)), clock_(clock) {}

  HostResult<void> open(int request_type, bool active_low_flag) {
    try {
      if (address_.chip.empty()) {
        line_ = gpiod::find_line(address_.line);
      } else {
        gpiod::chip chip(address_.chip, gpiod::chip::OPEN_LOOKUP);
        line_ = is_number(address_.line) ? chip.get_line(static_cast<unsigned>(std::stoul(address_.line)))
                                         : chip.find_line(address_.line);
      }
      if (!line_) {
        return host_error(HostErrorKind::kNotFound, "gpio:" + address_.text(), "no such GPIO line");
      }
      gpiod::line_request request;
      request.consumer = kConsumer;
      request.request_type = request_type;
      if (active_low_flag) request.flags = gpiod::line_request::FLAG_ACTIVE_LOW;
      line_.request(request, 0);
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "cannot request the line"));
    }
    return {};
  }

  HostResult<uint64_t> trigger(const std::atomic<bool>& stop, uint64_t max_frames,
                               const std::function<void(const Exposure&)>& report) {
    const int64_t period = trigger_.frame_period_ns;
    uint64_t reported = 0;
    try {
      for (int64_t k = 0; max_frames == 0 || reported < max_frames; ++k) {
        // Late by more than half a period (the host was busy): skip to the next pulse on time.
        const int64_t now = clock_.now();
        const int64_t due = first_edge_ + k * period;
        if (now > due + period / 2) {
          k = protocol::floor_div(now - first_edge_, period);
          continue;
        }
        if (!sleep_until(clock_.to_monotonic(due), stop)) break;
        const int64_t rise = set(1);
        if (!sleep_until(clock_.to_monotonic(due + trigger_.exposure_ns), stop)) {
          set(0);
          break;
        }
        const int64_t fall = set(0);
        report(Exposure{k, clock_.from_monotonic(rise), fall - rise});
        ++reported;
      }
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "driving the line"));
    }
    return reported;
  }

  HostResult<uint64_t> strobe(const std::atomic<bool>& stop, uint64_t max_frames,
                              const std::function<void(const Exposure&)>& report) {
    uint64_t reported = 0;
    StrobeEdgePairer pairer(strobe_.frame_period_ns);
    try {
      while (!stop.load() && (max_frames == 0 || reported < max_frames)) {
        if (!line_.event_wait(std::chrono::nanoseconds(kStopCheckNs))) continue;
        for (const gpiod::line_event& e : line_.event_read_multiple()) {
          const bool rising = e.event_type == gpiod::line_event::RISING_EDGE;
          const auto exposure = pairer.edge(rising != strobe_.active_low, clock_.from_monotonic(e.timestamp.count()));
          if (!exposure) continue;
          report(*exposure);
          if (++reported == max_frames) break;
        }
      }
    } catch (const std::exception& e) {
      return tl::unexpected(gpio_error(address_.text(), e, "reading line events"));
    }
    return reported;
  }

  // Sets the line; the time it took effect is taken as the middle of the ioctl.
  int64_t set(int value) {
    const int64_t before = monotonic_now_ns();
    line_.set_value(value);
    const int64_t after = monotonic_now_ns();
    return before + (after - before) / 2;
  }

  GpioLineAddress address_;
  std::string name_ = "gpio:" + address_.text();
  RigClock clock_;
  gpiod::line line_;
  bool is_trigger_ = false;
  GpioTriggerOptions trigger_;
  GpioStrobeOptions strobe_;
  int64_t first_edge_ = 0;
};

GpioSync::GpioSync(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GpioSync::~GpioSync() = default;

HostResult<std::unique_ptr<GpioSync>> GpioSync::trigger(const GpioTriggerOptions& options, RigClock clock) {
  if (options.frame_period_ns <= 0 || options.exposure_ns <= 0 || options.exposure_ns >= options.frame_period_ns) {
    return host_error(HostErrorKind::kBadInput, "gpio:" + options.line.text(),
                      fmt::format("exposure {} ns must be positive and shorter than the frame period {} ns",
                                  options.exposure_ns, options.frame_period_ns));
  }
  auto impl = std::make_unique<Impl>(options.line, clock);
  if (auto opened = impl->open(gpiod::line_request::DIRECTION_OUTPUT, options.active_low); !opened) {
    return tl::unexpected(opened.error());
  }
  impl->is_trigger_ = true;
  impl->trigger_ = options;
  // Pulse 0 at the next whole frame period, at least a millisecond away.
  impl->first_edge_ = options.first_edge_ns.value_or(
      (protocol::floor_div(clock.now() + 1'000'000, options.frame_period_ns) + 1) * options.frame_period_ns);
  return std::unique_ptr<GpioSync>(new GpioSync(std::move(impl)));
}

HostResult<std::unique_ptr<GpioSync>> GpioSync::strobe(const GpioStrobeOptions& options, RigClock clock) {
  auto impl = std::make_unique<Impl>(options.line, clock);
  if (auto opened = impl->open(gpiod::line_request::EVENT_BOTH_EDGES, false); !opened) {
    return tl::unexpected(opened.error());
  }
  impl->strobe_ = options;
  return std::unique_ptr<GpioSync>(new GpioSync(std::move(impl)));
}

HostResult<uint64_t> GpioSync::run(const std::atomic<bool>& stop, uint64_t max_frames,
                                   const std::function<void(const Exposure&)>& on_exposure) {
  return impl_->is_trigger_ ? impl_->trigger(stop, max_frames, on_exposure) : impl_->strobe(stop, max_frames, on_exposure);
}

int64_t GpioSync::first_edge_ns() const { return impl_->first_edge_; }
const std::string& GpioSync::line_name() const { return impl_->name_; }

}  // namespace tetrapulse::host

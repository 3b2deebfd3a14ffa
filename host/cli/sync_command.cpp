// `tetrapulse sync`: the sync master. Drives a camera trigger line or follows the camera's
// strobe line (GPIO), writing every exposure's rig time to an exposures file, and/or
// broadcasts CAN time sync (Sync + FollowUp); runs until Ctrl-C, --frames, --count or
// --duration-s.
#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <fmt/format.h>

#include "board_options.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "json_text.hpp"
#include "stop_signal.hpp"
#include "tetrapulse/host/can_sync.hpp"
#include "tetrapulse/host/gpio_sync.hpp"

namespace tetrapulse::cli {
namespace {

using host::HostError;
using host::HostErrorKind;

struct SyncArgs {
  std::string trigger;
  std::string strobe;
  std::string can;
  double rate_hz = 30.0;
  double can_rate_hz = 10.0;
  double exposure_us = 5000.0;
  bool active_low = false;
  std::string out;
  uint64_t frames = 0;
  uint64_t count = 0;
  double duration_s = 0;
  int64_t rig_offset_ns = 0;
  std::optional<int64_t> first_edge_ns;
  bool json = false;
};

class Printer {
 public:
  explicit Printer(bool json) : json_(json) {}
  void line(bool json_line, const std::string& text) {
    if (json_line != json_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    fmt::print("{}\n", text);
    std::fflush(stdout);
  }

 private:
  bool json_;
  std::mutex mutex_;
};

int64_t period_of(double hz) { return static_cast<int64_t>(1e9 / hz + 0.5); }

int run_sync(const SyncArgs& a) {
  const bool gpio = !a.trigger.empty() || !a.strobe.empty();
  if (!a.trigger.empty() && !a.strobe.empty()) {
    return report_failure("sync", HostError{HostErrorKind::kBadInput, "", "--trigger and --strobe: one GPIO line mode"});
  }
  if (!gpio && a.can.empty()) {
    return report_failure("sync", HostError{HostErrorKind::kBadInput, "", "give --trigger LINE, --strobe LINE and/or --can IFACE"});
  }
  if (gpio && a.out.empty()) {
    return report_failure("sync", HostError{HostErrorKind::kBadInput, "", "--out FILE: where to write the exposures"});
  }
  const host::RigClock clock(a.rig_offset_ns);
  Printer printer(a.json);

  std::unique_ptr<host::GpioSync> gpio_sync;
  std::string gpio_text;
  if (gpio) {
    auto line = host::parse_gpio_line(a.trigger.empty() ? a.strobe : a.trigger);
    if (!line) return report_failure("sync", line.error());
    const int64_t period = period_of(a.rate_hz);
    if (!a.trigger.empty()) {
      host::GpioTriggerOptions o;
      o.line = *line;
      o.frame_period_ns = period;
      o.exposure_ns = static_cast<int64_t>(a.exposure_us * 1000.0 + 0.5);
      o.active_low = a.active_low;
      o.first_edge_ns = a.first_edge_ns;
      auto s = host::GpioSync::trigger(o, clock);
      if (!s) return report_failure("sync", s.error());
      gpio_sync = std::move(*s);
      gpio_text = fmt::format("{} ({} Hz)", gpio_sync->schedule_text(), a.rate_hz);
    } else {
      host::GpioStrobeOptions o;
      o.line = *line;
      o.active_low = a.active_low;
      o.frame_period_ns = period;
      auto s = host::GpioSync::strobe(o, clock);
      if (!s) return report_failure("sync", s.error());
      gpio_sync = std::move(*s);
      gpio_text = fmt::format("{}, frames numbered at {} Hz", gpio_sync->schedule_text(), a.rate_hz);
    }
  }
  std::unique_ptr<host::CanSync> can_sync;
  if (!a.can.empty()) {
    host::CanSyncOptions o;
    o.period_ns = period_of(a.can_rate_hz);
    auto s = host::CanSync::open(a.can, clock, o);
    if (!s) return report_failure("sync", s.error());
    can_sync = std::move(*s);
  }
  std::unique_ptr<host::ExposureLogWriter> writer;
  if (gpio) {
    auto w = host::ExposureLogWriter::create(a.out);
    if (!w) return report_failure("sync", w.error());
    writer = std::move(*w);
  }
  printer.line(false, fmt::format("tetrapulse sync: rig time = CLOCK_MONOTONIC + {} ns{}{}", a.rig_offset_ns,
                                  gpio ? "; " + gpio_text + "; exposures to " + a.out : "",
                                  can_sync ? fmt::format("; CAN Sync/FollowUp on {} at {} Hz", a.can, a.can_rate_hz) : ""));

  // One stop flag for both loops: a signal, --duration-s, or the GPIO side reaching --frames.
  std::atomic<bool> stop{false};
  std::atomic<bool> finished{false};
  const std::atomic<bool>& signalled = stop_on_signals();
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(a.duration_s);
  std::thread watcher([&] {
    while (!finished) {
      if (signalled || (a.duration_s > 0 && std::chrono::steady_clock::now() >= until)) stop = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });

  std::optional<HostError> failure;
  std::mutex failure_mutex;
  uint64_t syncs = 0;
  std::string sources;
  auto run_can = [&] {
    auto sent = can_sync->run(stop, a.count, [&](const host::CanSyncSample& s) {
      if (sources.find(host::tx_stamp_source_name(s.source)) == std::string::npos) {
        sources += (sources.empty() ? "" : ", ") + std::string(host::tx_stamp_source_name(s.source));
      }
      printer.line(true, JsonObject()
                             .str("event", "can_sync")
                             .num("sync_seq", s.sync_seq)
                             .num("tx_time_ns", s.tx_time_ns)
                             .str("tx_time_source", host::tx_stamp_source_name(s.source))
                             .text());
    });
    std::lock_guard<std::mutex> lock(failure_mutex);
    if (!sent && !failure) failure = sent.error();
    if (sent) syncs = *sent;
  };
  uint64_t exposures = 0;
  if (gpio) {
    std::thread can_thread;
    if (can_sync) can_thread = std::thread(run_can);
    auto ran = gpio_sync->run(stop, a.frames, [&](const host::Exposure& e) {
      if (auto w = writer->write(e); !w) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = w.error();
        stop = true;
      }
      printer.line(true, JsonObject()
                             .str("event", "exposure")
                             .num("frame", e.frame)
                             .num("timestamp_ns", e.timestamp_ns)
                             .num("exposure_ns", e.exposure_ns)
                             .text());
    });
    stop = true;
    if (can_thread.joinable()) can_thread.join();
    if (!ran) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = ran.error();
    } else {
      exposures = *ran;
    }
  } else {
    run_can();
  }
  finished = true;
  watcher.join();
  if (failure) return report_failure("sync", *failure);

  JsonObject summary;
  summary.str("event", "summary").num("exposures", exposures).num("can_syncs", syncs);
  if (gpio) summary.str("exposures_file", a.out);
  if (can_sync) summary.str("tx_time_source", sources);
  printer.line(true, summary.text());
  printer.line(false, fmt::format("tetrapulse sync: {}{}{}", gpio ? fmt::format("{} exposures written to {}", exposures, a.out) : "",
                                  gpio && can_sync ? ", " : "",
                                  can_sync ? fmt::format("{} CAN syncs ({})", syncs, sources) : ""));
  return kExitOk;
}

}  // namespace

void add_sync_command(CLI::App& app, int* result) {
  auto a = std::make_shared<SyncArgs>();
  auto* cmd = app.add_subcommand("sync", "Be the sync master: GPIO camera trigger or strobe, and/or CAN time sync");
  const char* g = "GPIO (libgpiod): LINE is CHIP:OFFSET, CHIP:NAME or a line name";
  cmd->add_option("--trigger", a->trigger, "Drive this camera trigger line, one pulse per frame")->group(g);
  cmd->add_option("--strobe", a->strobe, "Follow this camera strobe line (active while exposing)")->group(g);
  cmd->add_option("--rate", a->rate_hz, "Frame rate (trigger), or the nominal rate that numbers strobe frames")
      ->check(CLI::Range(0.01, 100000.0))
      ->capture_default_str()
      ->group(g);
  cmd->add_option("--exposure-us", a->exposure_us, "Trigger pulse width = exposure time")
      ->check(CLI::Range(0.001, 10000000.0))
      ->capture_default_str()
      ->group(g);
  cmd->add_option("--first-edge-ns", a->first_edge_ns, "Rig time of trigger pulse 0 (default: the next whole period)")
      ->group(g);
  cmd->add_flag("--active-low", a->active_low, "The line is active low")->group(g);
  cmd->add_option("--out", a->out, "Exposures file to write: frame,timestamp_ns,exposure_ns in rig time")->group(g);
  cmd->add_option("--frames", a->frames, "Stop after this many exposures (0: until stopped)")->group(g);
  cmd->add_option("--can", a->can, "Broadcast CAN time sync on this SocketCAN interface")->group("CAN");
  cmd->add_option("--can-rate", a->can_rate_hz, "Syncs per second")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str()
      ->group("CAN");
  cmd->add_option("--count", a->count, "With CAN only: stop after this many syncs (0: until stopped)")->group("CAN");
  cmd->add_option("--duration-s", a->duration_s, "Stop after this long (0: until Ctrl-C)")->check(CLI::Range(0.0, 1e9));
  cmd->add_option("--rig-offset-ns", a->rig_offset_ns, "Rig time = CLOCK_MONOTONIC + this (ns)")->capture_default_str();
  cmd->add_flag("--json", a->json, "One JSON object per line: each exposure, each CAN sync, then a summary");
  cmd->footer(
      "Rig time is this host's CLOCK_MONOTONIC plus --rig-offset-ns. GPIO edge timestamps are the kernel's line\n"
      "event times (CLOCK_MONOTONIC); CAN transmit times are the kernel's transmit timestamps (converted from\n"
      "CLOCK_REALTIME), else the frame's own echo, else the send call.");
  cmd->callback([a, result] { *result = run_sync(*a); });
}

}  // namespace tetrapulse::cli

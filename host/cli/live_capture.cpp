// LiveCapture: camera thread, exposure matching, bounded queue (live_capture.hpp).
#include "live_capture.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::cli {

void add_live_options(CLI::App* cmd, LiveArgs* a) {
  cmd->add_option("--exposure-us", a->exposure_us, "Camera ExposureTime (µs)")->capture_default_str();
  cmd->add_option("--gain-db", a->gain_db, "Camera Gain (dB)");
  cmd->add_option("--frame-rate", a->frame_rate_hz, "Camera AcquisitionFrameRate (Hz)");
  cmd->add_option("--pixel-format", a->pixel_format, "Camera PixelFormat: Mono8, Mono16, RGB8, BayerRG8... (V4L2: Mono8, Mono16, YUYV)");
  cmd->add_option("--trigger-source", a->trigger_source, "Hardware trigger: TriggerMode On, TriggerSource this (e.g. Line0)");
  cmd->add_option("--strobe-output", a->strobe_output, "Camera output line to drive with LineSource ExposureActive (e.g. Line1)");
  cmd->add_option("--sync-strobe", a->sync_strobe,
                  "Host GPIO line CHIP:LINE wired to the strobe: be the sync master, stamp exposures from its edges");
  cmd->add_option("--sync-trigger", a->sync_trigger,
                  "Host GPIO line CHIP:LINE wired to the camera's trigger input: be the sync master, one pulse per frame "
                  "at --frame-rate, --exposure-us wide (camera: TriggerMode On, TriggerSource --trigger-source or Line0)");
  cmd->add_option("--sync-can", a->sync_can, "Broadcast the boards' CAN time sync on this SocketCAN interface");
  cmd->add_option("--can-rate", a->can_rate_hz, "CAN time syncs per second")->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  cmd->add_flag("--camera-clock-is-rig-time", a->camera_clock_is_rig,
                "The camera's timestamps are rig time already (PTP-synchronised to the sync master, or a simulated camera)");
  cmd->add_option("--packet-size", a->packet_size, "GigE Vision GevSCPSPacketSize (bytes; needs jumbo frames above 1500)");
  cmd->add_option("--frames", a->frames, "Stop after N frames (0: until SIGINT)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--queue", a->queue, "Frames buffered between capture and output (older ones dropped, counted)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  cmd->add_option("--frame-timeout-ms", a->frame_timeout_ms, "No frame for this long ends the run")
      ->check(CLI::Range(100, 600000))
      ->capture_default_str();
}

static host::ExposureMatcher::Options matcher_options(const LiveArgs& a) {
  host::ExposureMatcher::Options o;
  o.exposure_ns = static_cast<int64_t>(std::llround(a.exposure_us * 1000.0));
  o.camera_clock_is_rig = a.camera_clock_is_rig;
  if (a.frame_rate_hz && *a.frame_rate_hz > 0) o.frame_period_ns = static_cast<int64_t>(std::llround(1e9 / *a.frame_rate_hz));
  return o;
}

tl::expected<std::unique_ptr<LiveCapture>, std::string> LiveCapture::open(
    const LiveArgs& args, int width, int height, const std::function<void(const std::string&)>& note) {
  auto camera = host::open_camera(args.camera);
  if (!camera) return tl::unexpected(camera.error().what());
  host::CameraSettings s;
  s.exposure_us = args.exposure_us;
  s.gain_db = args.gain_db;
  s.frame_rate_hz = args.frame_rate_hz;
  s.pixel_format = args.pixel_format;
  if (!args.trigger_source.empty()) s.trigger_source = args.trigger_source;
  if (!args.strobe_output.empty()) s.strobe_line = args.strobe_output;
  s.packet_size = args.packet_size;
  s.width = width;
  s.height = height;
  const host::ExposureMatcher::Options timing = matcher_options(args);
  if (!args.sync_trigger.empty()) {
    if (!args.sync_strobe.empty()) return tl::unexpected(std::string("--sync-strobe and --sync-trigger: one GPIO line mode"));
    if (timing.frame_period_ns <= 0) return tl::unexpected(std::string("--sync-trigger needs --frame-rate: the pulse rate"));
    s.trigger_source = args.trigger_source.empty() ? "Line0" : args.trigger_source;
    s.trigger_required = true;
  }
  auto notes = (*camera)->configure(s);
  if (!notes) return tl::unexpected(notes.error().what());
  for (const std::string& n : *notes) note(n);
  std::unique_ptr<host::GpioSync> sync;
  if (!args.sync_strobe.empty() || !args.sync_trigger.empty()) {
    auto line = host::parse_gpio_line(args.sync_trigger.empty() ? args.sync_strobe : args.sync_trigger);
    if (!line) return tl::unexpected(line.error().what());
    host::HostResult<std::unique_ptr<host::GpioSync>> g;
    if (!args.sync_trigger.empty()) {
      host::GpioTriggerOptions o;
      o.line = *line;
      o.frame_period_ns = timing.frame_period_ns;
      o.exposure_ns = timing.exposure_ns;
      g = host::GpioSync::trigger(o, host::RigClock(0));
    } else {
      host::GpioStrobeOptions o;
      o.line = *line;
      o.frame_period_ns = timing.frame_period_ns;
      g = host::GpioSync::strobe(o, host::RigClock(0));
    }
    if (!g) return tl::unexpected(g.error().what());
    sync = std::move(*g);
    note("sync master: " + sync->schedule_text());
  }
  std::unique_ptr<host::CanSync> can;
  if (!args.sync_can.empty()) {
    host::CanSyncOptions o;
    o.period_ns = static_cast<int64_t>(std::llround(1e9 / args.can_rate_hz));
    auto c = host::CanSync::open(args.sync_can, host::RigClock(0), o);
    if (!c) return tl::unexpected(c.error().what());
    can = std::move(*c);
    note(fmt::format("CAN time sync on {} at {} Hz", args.sync_can, args.can_rate_hz));
  }
  std::unique_ptr<LiveCapture> live(new LiveCapture(args, std::move(*camera), std::move(sync), std::move(can)));
  if (auto started = live->camera_->start(); !started) return tl::unexpected(started.error().what());
  if (live->sync_) {
    live->sync_thread_ = std::thread([p = live.get()] {
      auto r = p->sync_->run(p->quit_, 0, [p](const host::Exposure& e) { p->matcher_.add_exposure(e); });
      if (!r) p->fail(r.error().what());
    });
  }
  if (live->can_) {
    live->can_thread_ = std::thread([p = live.get()] {
      auto r = p->can_->run(p->quit_, 0, [p](const host::CanSyncSample&) { ++p->can_syncs_; });
      if (!r) p->fail(r.error().what());
    });
  }
  live->capture_thread_ = std::thread([p = live.get()] { p->capture_loop(); });
  return live;
}

LiveCapture::LiveCapture(const LiveArgs& args, std::unique_ptr<host::Camera> camera, std::unique_ptr<host::GpioSync> sync,
                         std::unique_ptr<host::CanSync> can)
    : args_(args),
      camera_(std::move(camera)),
      sync_(std::move(sync)),
      can_(std::move(can)),
      matcher_(sync_ != nullptr, matcher_options(args)) {}

LiveCapture::~LiveCapture() {
  quit_ = true;
  if (capture_thread_.joinable()) capture_thread_.join();
  if (sync_thread_.joinable()) sync_thread_.join();
  if (can_thread_.joinable()) can_thread_.join();
  camera_->stop();
}

// A sync thread failed: the run ends with that error (the first one kept).
void LiveCapture::fail(const std::string& why) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = why;
  }
  quit_ = true;
}

void LiveCapture::capture_loop() {
  int64_t last_frame_ns = host::monotonic_now_ns();
  while (!quit_) {
    auto f = camera_->grab(100);
    if (!f) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = f.error().what();
      break;
    }
    if (!*f) {
      if (host::monotonic_now_ns() - last_frame_ns > int64_t{args_.frame_timeout_ms} * 1'000'000) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = fmt::format("{}: no frame for {} ms", camera_->name(), args_.frame_timeout_ms);
        break;
      }
      continue;
    }
    last_frame_ns = host::monotonic_now_ns();
    LiveFrame live{std::move(**f), {}};
    if (!live.frame.bad) {
      auto stamp = matcher_.match(live.frame.arrived_ns, live.frame.camera_ns);
      if (!stamp) live.frame.bad = camera_->name() + ": frame " + std::to_string(live.frame.sequence) + ": no exposure matches it";
      else {
        live.stamp = *stamp;
        const int64_t end = stamp->exposure.timestamp_ns + stamp->exposure.exposure_ns;
        if (args_.camera_clock_is_rig && !matcher_.synchronised()) {
          const int64_t d = live.frame.arrived_ns - end;
          if (!host_minus_rig_ns_ || d < *host_minus_rig_ns_) host_minus_rig_ns_ = d;
          live.exposure_end_host_ns = end + *host_minus_rig_ns_;
        } else {
          live.exposure_end_host_ns = end;
        }
      }
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (queue_.size() >= static_cast<size_t>(args_.queue)) {
        queue_.pop_front();
        ++drops_;
      }
      queue_.push_back(std::move(live));
      counters_ = camera_->counters();  // read by stats() on the consumer's thread
    }
    ready_.notify_one();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ended_ = true;
  }
  ready_.notify_all();
}

std::optional<LiveFrame> LiveCapture::next(const std::atomic<bool>& stop) {
  if (args_.frames > 0 && handed_out_ >= args_.frames) return std::nullopt;
  std::unique_lock<std::mutex> lock(mutex_);
  while (queue_.empty() && !ended_ && !stop) ready_.wait_for(lock, std::chrono::milliseconds(100));
  if (stop) quit_ = true;  // the capture thread grabs no more; what it queued is drained
  if (queue_.empty()) return std::nullopt;
  LiveFrame f = std::move(queue_.front());
  queue_.pop_front();
  if (!f.frame.bad) ++handed_out_;
  return f;
}

LiveStats LiveCapture::stats() const {
  LiveStats s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.queue_drops = drops_;
    s.grabbed = counters_.frames;
    s.bad_buffers = counters_.bad_buffers;
  }
  s.match = matcher_.counters();
  s.synchronised = matcher_.synchronised();
  s.estimated = !s.synchronised && !args_.camera_clock_is_rig;
  if (sync_) s.sync_master = (args_.sync_trigger.empty() ? "strobe " : "trigger ") + sync_->line_name();
  s.can_syncs = can_syncs_;
  s.can_interface = args_.sync_can;
  return s;
}

int64_t LatencyStats::percentile(double p) const {
  if (samples_.empty()) return 0;
  std::vector<int64_t> sorted = samples_;
  std::sort(sorted.begin(), sorted.end());
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size() - 1, rank == 0 ? 0 : rank - 1)];
}

std::string stamp_source(const LiveStats& s) {
  std::string text = s.synchronised ? "sync master (" + s.sync_master + ")"
                     : s.estimated  ? "camera clock + estimated offset (no sync wiring)"
                                    : "camera clock (rig time)";
  if (!s.can_interface.empty()) text += fmt::format("; {} CAN time syncs on {}", s.can_syncs, s.can_interface);
  return text;
}

std::string LatencyStats::summary() const {
  return fmt::format("latency exposure end -> pose out: p50 {:.2f} ms, p99 {:.2f} ms ({} frames)", percentile(50) / 1e6,
                     percentile(99) / 1e6, samples_.size());
}

}  // namespace tetrapulse::cli

#pragma once
// The live loop's capture side, shared by `record` and `localize --camera`: a
// camera (host/camera.hpp) grabbed on a thread of its own, each frame stamped in rig
// time (ExposureMatcher: the GPIO sync master in this process when --sync-strobe or
// --sync-trigger names its line, else the camera clock and an estimated offset), the
// boards' CAN time sync from the same process when --sync-can names an interface, and
// a bounded queue to the consumer. Capture never waits for the consumer: when the queue is full
// the oldest frame is dropped and counted. Rig time is the host's CLOCK_MONOTONIC
// (RigClock offset 0).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "tetrapulse/host/camera.hpp"
#include "tetrapulse/host/can_sync.hpp"
#include "tetrapulse/host/exposure_matcher.hpp"
#include "tetrapulse/host/gpio_sync.hpp"

namespace tetrapulse::cli {

struct LiveArgs {
  std::string camera;            // aravis:ID or v4l2:/dev/videoN
  double exposure_us = 2000;     // also the exposure written to frames.csv without sync
  std::optional<double> gain_db;
  std::optional<double> frame_rate_hz;
  std::string pixel_format;
  std::string trigger_source;    // camera input line for a hardware trigger
  std::string strobe_output;     // camera output line to drive with ExposureActive
  std::string sync_strobe;       // host GPIO line that sees the strobe (the sync master)
  std::string sync_trigger;      // host GPIO line that triggers the camera (the sync master)
  std::string sync_can;          // SocketCAN interface for the boards' time sync
  double can_rate_hz = 10;       // CAN Sync/FollowUp pairs per second
  int64_t frames = 0;            // stop after this many frames (0: until stopped)
  int queue = 4;                 // frames between capture and consumer
  int frame_timeout_ms = 5000;   // no frame for this long ends the run
  bool camera_clock_is_rig = false;  // the camera's timestamps are rig time (PTP)
  std::optional<int> packet_size;    // GigE Vision packet size (bytes)
  std::string record;            // localize: also write the frames as a rig dataset here
};
// --camera, --exposure-us, --gain-db, --frame-rate, --pixel-format, --trigger-source,
// --strobe-output, --sync-strobe, --sync-trigger, --sync-can, --can-rate, --frames, --queue.
void add_live_options(CLI::App* cmd, LiveArgs* args);

struct LiveFrame {
  host::CameraFrame frame;
  host::MatchedStamp stamp;  // rig time exposure (valid unless frame.bad)
  // The end of the exposure on the host's CLOCK_MONOTONIC, for latency: rig time is
  // CLOCK_MONOTONIC, except when the camera clock is taken as rig time (then mapped by
  // the fastest transfer seen).
  int64_t exposure_end_host_ns = 0;
};

struct LiveStats {
  uint64_t grabbed = 0;       // buffers from the camera
  uint64_t bad_buffers = 0;   // incomplete or wrong-sized
  uint64_t queue_drops = 0;   // dropped because the consumer fell behind
  host::MatchCounters match;
  bool estimated = false;     // stamps from the camera clock and an estimated offset
  bool synchronised = false;  // stamps from the sync master
  std::string sync_master;    // "strobe gpio:gpiochip0:3", "trigger ..." ("" without)
  uint64_t can_syncs = 0;     // CAN Sync/FollowUp pairs sent (--sync-can)
  std::string can_interface;  // "" without --sync-can
};

class LiveCapture {
 public:
  // Opens and configures the camera (each missing feature goes to `note`), starts the
  // sync master and the capture thread. Error: names the camera or line.
  static tl::expected<std::unique_ptr<LiveCapture>, std::string> open(const LiveArgs& args, int width, int height,
                                                                      const std::function<void(const std::string&)>& note);
  ~LiveCapture();

  // The next frame (bad ones included, marked); nullopt once --frames frames were
  // handed out, or the capture ended (then error() says why, if it failed). Once
  // `stop` is set the camera stops and the frames it had already delivered are still
  // handed out, then nullopt: a stop loses no frame that was captured.
  std::optional<LiveFrame> next(const std::atomic<bool>& stop);
  const std::optional<std::string>& error() const { return error_; }
  LiveStats stats() const;
  const std::string& camera_name() const { return camera_->name(); }
  // The camera's transport line (packet resend), "" when it has none (summaries).
  std::string transport_summary() { return camera_->transport_summary(); }

 private:
  LiveCapture(const LiveArgs& args, std::unique_ptr<host::Camera> camera, std::unique_ptr<host::GpioSync> sync,
              std::unique_ptr<host::CanSync> can);
  void capture_loop();
  void fail(const std::string& why);

  LiveArgs args_;
  std::unique_ptr<host::Camera> camera_;
  std::unique_ptr<host::GpioSync> sync_;
  std::unique_ptr<host::CanSync> can_;
  std::atomic<uint64_t> can_syncs_{0};
  host::ExposureMatcher matcher_;
  std::atomic<bool> quit_{false};
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<LiveFrame> queue_;
  bool ended_ = false;
  std::optional<std::string> error_;
  uint64_t drops_ = 0;
  std::optional<int64_t> host_minus_rig_ns_;
  host::CameraCounters counters_;
  int64_t handed_out_ = 0;
  std::thread sync_thread_;
  std::thread can_thread_;
  std::thread capture_thread_;
};

// How the frames were stamped (and the boards' CAN time sync, if any), for summaries.
std::string stamp_source(const LiveStats& s);

// Latency from exposure end to pose out (ns), p50/p99 in a summary line.
class LatencyStats {
 public:
  void add(int64_t ns) { samples_.push_back(ns); }
  size_t count() const { return samples_.size(); }
  // Nearest-rank percentile (0..100); 0 when empty.
  int64_t percentile(double p) const;
  std::string summary() const;  // "latency exposure end -> pose out: p50 3.1 ms, p99 7.9 ms (N frames)"

 private:
  std::vector<int64_t> samples_;
};

}  // namespace tetrapulse::cli

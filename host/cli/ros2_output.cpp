#include "ros2_output.hpp"

#include <atomic>
#include <cstdio>

#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/ros2/background_publisher.hpp"
#include "tetrapulse/ros2/dds_pose_publisher.hpp"
#include "tetrapulse/ros2/ros_names.hpp"

namespace tetrapulse::cli {

namespace {

constexpr int64_t kStatusPeriodNs = 1'000'000'000;  // rig time between two statuses
constexpr int64_t kDiscoverySettleNs = 100'000'000;  // no new reader for this long: discovery is done
constexpr int64_t kNsPerMs = 1'000'000;
constexpr size_t kQueueFrames = 256;  // 2.5 s at 100 fps

}  // namespace

struct Ros2Output::State {
  std::unique_ptr<ros2::PosePublisher> publisher;  // null: not publishing (DDS failed)
  bool failed = false;
  const TargetsFile* targets = nullptr;
  int64_t wait_ns = 0;
  ros2::LocalizerStatus status;
  ros2::DurationStats processing;
  std::optional<ros2::DurationStats> latency;  // live: mid-exposure to publish
  std::optional<int64_t> last_frame;
  std::optional<int64_t> next_status_ns;
  std::function<LiveFeed()> live_feed;
  // CLOCK_MONOTONIC minus rig time of the newest frame, for stamps on the publisher's
  // thread (live only; 0: rig time is CLOCK_MONOTONIC).
  std::shared_ptr<std::atomic<int64_t>> monotonic_minus_rig = std::make_shared<std::atomic<int64_t>>(0);
};

Ros2Output::Ros2Output(Ros2Output&&) noexcept = default;
Ros2Output& Ros2Output::operator=(Ros2Output&&) noexcept = default;
Ros2Output::~Ros2Output() = default;

void add_ros2_options(CLI::App* command, Ros2Args* args) {
  command->add_flag("--ros2", args->enabled,
                    "Publish into ROS 2 over DDS: /tf, /tetrapulse/target_<id>/pose, /tetrapulse/status "
                    "(domain ROS_DOMAIN_ID, configuration CYCLONEDDS_URI; docs/ros2.md)");
  command->add_option("--frame-id", args->frame_id, "--ros2: the camera's frame, parent of every transform "
                                                    "(default: camera_name of camera.yaml)");
  command->add_option("--node-name", args->node_name, "--ros2: the ROS 2 node's name (default: tetrapulse_<frame id>)");
  command->add_option("--ros2-namespace", args->ros_namespace,
                      "--ros2: the node's namespace; its topics and child frames go beneath it")
      ->capture_default_str();
  command->add_option("--ros2-wait-ms", args->wait_ms,
                      "--ros2: longest wait for readers to appear before a replay's first frame, and for "
                      "reliable readers to acknowledge at the end")
      ->check(CLI::Range(0, 60'000))
      ->capture_default_str();
}

tl::expected<Ros2Output, std::string> Ros2Output::open(const Ros2Args& args, const CameraInfo& camera,
                                                       const TargetsFile& targets, bool live) {
  Ros2Output out;
  out.state_ = std::make_unique<State>();
  ros2::DdsPublisherOptions options;
  options.frame_id = args.frame_id.empty() ? camera.name : args.frame_id;
  if (options.frame_id.empty()) options.frame_id = "camera";
  options.node_name = args.node_name.empty() ? ros2::default_node_name(options.frame_id) : args.node_name;
  options.ros_namespace = args.ros_namespace;
  for (const Target& t : targets.targets) options.target_ids.push_back(t.id);
  if (live) {
    // Rig time -> CLOCK_MONOTONIC (the live loop's mapping of the newest frame) ->
    // CLOCK_REALTIME (the difference now: the stamp is written within ms of the frame).
    options.stamp_ns = [mmr = out.state_->monotonic_minus_rig](int64_t rig_ns) {
      return host::RigClock(0).to_realtime(rig_ns + mmr->load(std::memory_order_relaxed));
    };
  }
  for (auto check : {ros2::check_node_name(options.node_name), ros2::check_namespace(options.ros_namespace),
                     ros2::check_frame_id(options.frame_id)}) {
    if (!check) return tl::unexpected("--ros2: " + check.error().message);
  }

  out.state_->targets = &targets;
  out.state_->wait_ns = int64_t(args.wait_ms) * kNsPerMs;
  if (live) out.state_->latency.emplace();
  auto publisher = ros2::open_dds_publisher(options);
  if (!publisher) {
    out.fail(publisher.error().message);
    return out;
  }
  // A replay waits for room in the queue (loses nothing); a live camera never waits.
  out.state_->publisher = ros2::publish_in_background(std::move(*publisher), kQueueFrames,
                                                      live ? ros2::WhenQueueFull::kDropOldest : ros2::WhenQueueFull::kWait);
  if (!live) out.state_->publisher->wait_for_readers(out.state_->wait_ns, kDiscoverySettleNs);
  return out;
}

void Ros2Output::fail(const std::string& message) {
  if (state_->failed) return;
  state_->failed = true;
  state_->publisher.reset();
  std::fprintf(stderr, "tetrapulse localize: --ros2: %s; localizing on without publishing\n", message.c_str());
}

void Ros2Output::follow_live(std::function<LiveFeed()> feed) {
  state_->live_feed = std::move(feed);
  state_->status.live.emplace();
}

void Ros2Output::frame(const Frame& frame, const std::vector<TargetPose>& poses, int64_t processing_ns,
                       const Localizer& localizer) {
  State& s = *state_;
  int64_t monotonic_minus_rig = 0;
  if (s.live_feed) {
    // The loop's own counters: a frame lost to the queue, a bad buffer or a missing
    // exposure is counted once (with the sync master a bad buffer's exposure is the
    // one without a frame).
    const LiveFeed f = s.live_feed();
    const uint64_t localized = s.status.live->frames_localized + 1;
    s.status.live = f.counters;
    s.status.live->frames_localized = localized;
    s.status.frames_matched = f.frames_matched;
    s.status.frames_dropped = f.counters.queue_drops + f.counters.frames_without_exposure +
                              (f.synchronised ? f.counters.exposures_without_frame : f.counters.bad_buffers);
    monotonic_minus_rig = f.monotonic_minus_rig_ns;
    s.monotonic_minus_rig->store(monotonic_minus_rig, std::memory_order_relaxed);
  } else {
    s.status.frames_matched += 1;
    if (s.last_frame && frame.frame > *s.last_frame + 1) s.status.frames_dropped += uint64_t(frame.frame - *s.last_frame - 1);
  }
  s.last_frame = frame.frame;
  s.status.rig_time_ns = frame.timestamp_ns + frame.exposure_ns / 2;
  s.status.targets_with_pose.clear();
  for (const TargetPose& p : poses) s.status.targets_with_pose.push_back(p.target_id);
  s.processing.add(processing_ns);
  if (!s.publisher) return;
  if (auto r = s.publisher->publish(poses); !r) return fail(r.error().message);
  if (s.latency) s.latency->add(host::monotonic_now_ns() - (s.status.rig_time_ns + monotonic_minus_rig));
  if (!s.next_status_ns) s.next_status_ns = s.status.rig_time_ns + kStatusPeriodNs;
  if (s.status.rig_time_ns >= *s.next_status_ns) {
    publish_status(localizer);
    s.next_status_ns = s.status.rig_time_ns + kStatusPeriodNs;
  }
}

void Ros2Output::publish_status(const Localizer& localizer) {
  State& s = *state_;
  s.status.boards.clear();
  // A dataset names no boards: one per target, in the state its time base implies.
  for (const Target& t : s.targets->targets) {
    ros2::BoardSync b;
    b.target_id = t.id;
    b.board = "target " + std::to_string(t.id);
    if (s.targets->timebase.synchronized) {
      b.state = ros2::BoardSyncState::kSynchronized;
    } else {
      b.state = ros2::BoardSyncState::kFreeRunning;
      if (const auto clock = localizer.clock_of(t.id)) {
        b.offset_ns = clock->origin_ns - s.targets->timebase.epoch_ns;
        b.rate_ppm = (clock->rate - 1.0) * 1e6;
      }
    }
    s.status.boards.push_back(std::move(b));
  }
  s.status.processing = s.processing;
  s.processing = {};
  s.status.latency = s.latency;
  if (s.latency) s.latency = ros2::DurationStats{};
  if (auto r = s.publisher->publish_status(s.status); !r) fail(r.error().message);
}

bool Ros2Output::finish(const Localizer& localizer, bool quiet) {
  State& s = *state_;
  if (s.publisher && s.status.frames_matched > 0) publish_status(localizer);
  if (s.publisher && !s.publisher->wait_for_acknowledgments(s.wait_ns) && !quiet) {
    std::fprintf(stderr, "tetrapulse localize: --ros2: not every reliable reader acknowledged within %lld ms\n",
                 static_cast<long long>(s.wait_ns / kNsPerMs));
  }
  if (s.publisher && !quiet) {
    const ros2::PublishCounters c = s.publisher->counters();
    std::fprintf(stderr,
                 "tetrapulse localize: --ros2: %llu transforms on /tf, %llu poses, %llu statuses published%s\n",
                 static_cast<unsigned long long>(c.transforms), static_cast<unsigned long long>(c.poses),
                 static_cast<unsigned long long>(c.statuses),
                 c.dropped == 0 ? "" : (", " + std::to_string(c.dropped) + " dropped (queue full)").c_str());
  }
  s.publisher.reset();
  return !s.failed;
}

}  // namespace tetrapulse::cli

#pragma once
// `localize --ros2`: the localizer's poses and status into ROS 2
// (tetrapulse::ros2, docs/ros2.md). A thin layer: options, the publisher's
// start, one call per frame, the end.
//
// When DDS cannot start (ROS_DOMAIN_ID malformed, CYCLONEDDS_URI naming an
// interface that does not exist, ...), localization carries on unaffected: one
// line says why and that nothing is published, poses are written as without
// --ros2, and the command exits with kExitPublishFailed (7) at the end.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/ros2/pose_publisher.hpp"

namespace tetrapulse::cli {

struct Ros2Args {
  bool enabled = false;
  std::string frame_id;           // default: the camera's camera_name
  std::string node_name;          // default: ros2::default_node_name(frame id)
  std::string ros_namespace = "/";
  int wait_ms = 2000;             // replay: discovery before the first frame; always: acknowledgments at the end
};

void add_ros2_options(CLI::App* command, Ros2Args* args);

// What a live camera loop (live_localize.hpp) knows after the frame it handed out last.
struct LiveFeed {
  uint64_t frames_matched = 0;   // frames the exposure matcher stamped
  bool synchronised = false;     // stamped by the sync master (then a bad buffer is an exposure without a frame)
  ros2::LiveFrameCounters counters;  // frames_localized is counted here, not read
  int64_t monotonic_minus_rig_ns = 0;
};

class Ros2Output {
 public:
  // `live`: stamps on CLOCK_REALTIME (rig time mapped to the host's CLOCK_MONOTONIC,
  // follow_live) and no wait for readers; else rig time as is.
  // Returns kExitUsage's message for a bad name (nothing else is wrong then).
  static tl::expected<Ros2Output, std::string> open(const Ros2Args& args, const CameraInfo& camera,
                                                    const TargetsFile& targets, bool live);
  Ros2Output(Ros2Output&&) noexcept;
  Ros2Output& operator=(Ros2Output&&) noexcept;
  ~Ros2Output();

  // A live camera loop: read once per frame, for the status's frames matched and
  // dropped, for stamps (rig time -> CLOCK_MONOTONIC -> CLOCK_REALTIME) and latency.
  // Without it a live source's rig time is taken as CLOCK_MONOTONIC.
  void follow_live(std::function<LiveFeed()> feed);

  // After the localizer returned `poses` for `frame`; `processing_ns` what reading
  // and localizing the frame took.
  void frame(const Frame& frame, const std::vector<TargetPose>& poses, int64_t processing_ns,
             const Localizer& localizer);
  // The last status, then the bounded wait for acknowledgments. False when
  // publishing failed at any point (its line was printed).
  bool finish(const Localizer& localizer, bool quiet);

 private:
  Ros2Output() = default;
  void fail(const std::string& message);
  void publish_status(const Localizer& localizer);

  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tetrapulse::cli

#pragma once
// `localize --camera aravis:ID|v4l2:DEV`: the live camera as the localizer's
// FrameSource, over LiveCapture (live_capture.hpp: capture thread, matched rig-time
// stamps, bounded queue). Latency exposure end -> pose out is taken for each frame
// when the localizer asks for the next one (its poses are out by then); the summary
// (p50/p99, buffers, drops, mismatches, how frames were stamped) goes to stderr when
// the source is destroyed. With args.record the frames are written as a rig
// dataset too (each before it is localized).
#include <memory>
#include <string>

#include "live_capture.hpp"
#include "tetrapulse/datasets/frame_source.hpp"

namespace tetrapulse::cli {

// "aravis:..." or "v4l2:...": a camera for host/camera.hpp (anything else: OpenCV's).
bool is_live_camera_spec(const std::string& spec);

tl::expected<std::unique_ptr<FrameSource>, std::string> live_frame_source(const LiveArgs& args, const CameraInfo& camera,
                                                                          const TargetsFile& targets,
                                                                          const std::atomic<bool>& stop);

// What the live loop knows after the frame it handed out last, for --ros2's status and
// stamps (ros2_output.hpp); nullopt when `source` is not live_frame_source's.
struct LiveLoopState {
  LiveStats stats;
  // CLOCK_MONOTONIC minus rig time at that frame: 0 when rig time is CLOCK_MONOTONIC;
  // with --camera-clock-is-rig-time the mapping by the fastest transfer seen.
  int64_t monotonic_minus_rig_ns = 0;
};
std::optional<LiveLoopState> live_loop_state(const FrameSource& source);

}  // namespace tetrapulse::cli

#pragma once
// A PosePublisher that hands every frame to a thread of its own, so that the
// localizer's loop never waits on DDS (a write to a matched reader costs a few
// microseconds of serialisation and a send each; BENCHMARKS.md "ROS 2 publishing").
// publish() and publish_status() copy their input into a queue of at most
// `queue_frames` items, in order; the thread calls the wrapped publisher with
// them. When the queue is full: a replay waits for room (nothing is lost), a live
// loop drops the oldest item and counts it (PublishCounters::dropped), never
// stalling. An error of the wrapped publisher comes back from the next call.
// wait_for_acknowledgments() first lets the queue drain, within its bound. The
// owner calls it from one thread (the localizer's); the publisher's own thread is
// internal.
#include <cstddef>
#include <memory>

#include "tetrapulse/ros2/pose_publisher.hpp"

namespace tetrapulse::ros2 {

enum class WhenQueueFull { kWait, kDropOldest };

std::unique_ptr<PosePublisher> publish_in_background(std::unique_ptr<PosePublisher> publisher, size_t queue_frames,
                                                     WhenQueueFull when_full);

}  // namespace tetrapulse::ros2

#pragma once
// Where a localizer's poses go on ROS 2. A dataset replay, a video, a live camera
// loop call the same three things: publish(poses) once per frame,
// publish_status(status) now and then, and the two bounded waits around a replay.
// What goes on which topic: ros_names.hpp; how a pose reads there:
// ros_conventions.hpp. Header stamps are the poses' mid-exposure times mapped by
// the publisher's stamp clock (dds_pose_publisher.hpp).
#include <cstdint>
#include <vector>

#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/ros2/localizer_status.hpp"
#include "tetrapulse/ros2/ros2_error.hpp"

namespace tetrapulse::ros2 {

struct PublishCounters {
  uint64_t frames = 0;     // publish() calls
  uint64_t transforms = 0; // TransformStamped written on /tf
  uint64_t poses = 0;      // PoseWithCovarianceStamped written
  uint64_t statuses = 0;   // DiagnosticArray written
  uint64_t dropped = 0;    // frames and statuses never written (a full background queue, live)
};

class PosePublisher {
 public:
  virtual ~PosePublisher() = default;

  // One frame's poses: one TFMessage holding a TransformStamped per pose on /tf,
  // and one PoseWithCovarianceStamped per pose on its target's topic (the
  // covariance all zeros when the pose has none). Never blocks on readers.
  Ros2Result<void> publish(const std::vector<TargetPose>& poses) { return do_publish(poses); }
  Ros2Result<void> publish_status(const LocalizerStatus& status) { return do_publish_status(status); }

  // For a replay, before the first publish: waits until one of this node's topics
  // has a reader and no further reader has matched for `settle_ns`, at most
  // `timeout_ns` in all. Returns how many readers its topics have (summed).
  int wait_for_readers(int64_t timeout_ns, int64_t settle_ns) { return do_wait_for_readers(timeout_ns, settle_ns); }
  // At the end: waits until every reliable reader has acknowledged everything
  // written, at most `timeout_ns`. False when the time ran out.
  bool wait_for_acknowledgments(int64_t timeout_ns) { return do_wait_for_acknowledgments(timeout_ns); }

  PublishCounters counters() const { return do_counters(); }

 private:
  virtual Ros2Result<void> do_publish(const std::vector<TargetPose>& poses) = 0;
  virtual Ros2Result<void> do_publish_status(const LocalizerStatus& status) = 0;
  virtual int do_wait_for_readers(int64_t timeout_ns, int64_t settle_ns) = 0;
  virtual bool do_wait_for_acknowledgments(int64_t timeout_ns) = 0;
  virtual PublishCounters do_counters() const = 0;
};

}  // namespace tetrapulse::ros2

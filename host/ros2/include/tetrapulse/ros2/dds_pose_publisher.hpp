#pragma once
// The PosePublisher that speaks DDS the way ROS 2's rmw_cyclonedds_cpp does, with
// Eclipse Cyclone DDS and no ROS installation: topics "rt/<ros topic>", type names
// "<pkg>::msg::dds_::<Name>_", one DDS participant per node with USER_DATA
// "enclave=/;", and the node announced on "ros_discovery_info" (so that
// `ros2 node list` shows it). Domain: ROS_DOMAIN_ID (default 0); configuration:
// CYCLONEDDS_URI, which Cyclone DDS reads itself. QoS: ros_qos.hpp.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tetrapulse/ros2/pose_publisher.hpp"

namespace tetrapulse::ros2 {

struct DdsPublisherOptions {
  std::string node_name;            // check_node_name
  std::string ros_namespace = "/";  // check_namespace
  std::string frame_id;             // parent frame of every transform: the camera
  std::vector<int> target_ids;      // a pose topic for each, created up front
  // Header stamp (ns since the ROS epoch) of a rig time. Empty: rig time as is (a
  // dataset replay, as a bag replay would be). A live loop maps rig time to
  // CLOCK_REALTIME, the clock ROS 2 nodes stamp with (RigClock::to_realtime).
  std::function<int64_t(int64_t)> stamp_ns;
  std::optional<uint32_t> domain_id;  // empty: ros_domain_id()
};

// ROS_DOMAIN_ID from the environment: unset or empty is 0; otherwise an integer
// in [0, 232] (ROS 2's range on Linux), else kBadEnvironment.
Ros2Result<uint32_t> ros_domain_id();

// Creates the participant, its writers and the discovery announcement. Errors:
// kBadName, kBadEnvironment, or kDdsUnavailable with what Cyclone DDS said (an
// interface in CYCLONEDDS_URI that does not exist, a file it cannot read).
Ros2Result<std::unique_ptr<PosePublisher>> open_dds_publisher(const DdsPublisherOptions& options);

}  // namespace tetrapulse::ros2

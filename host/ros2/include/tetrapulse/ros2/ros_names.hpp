#pragma once
// ROS 2 names tetrapulse publishes under, and the DDS topic names rmw_cyclonedds
// gives them (a ROS topic /a/b is the DDS topic "rt/a/b").
//
// One localizer process is one ROS 2 node. Its namespace NS (default "/") holds
// its own topics; /tf is global, as tf2 listens there:
//   /tf                              tf2_msgs/msg/TFMessage
//   NS/tetrapulse/target_<id>/pose   geometry_msgs/msg/PoseWithCovarianceStamped
//   NS/tetrapulse/status             diagnostic_msgs/msg/DiagnosticArray
// Child frames: "tetrapulse/target_<id>", prefixed with NS without its leading
// slash when NS is not "/" (NS=/cam_b: "cam_b/tetrapulse/target_<id>"), so that two
// cameras that see one target do not give its frame two parents.
#include <string>

#include "tetrapulse/ros2/ros2_error.hpp"

namespace tetrapulse::ros2 {

// A node name: [A-Za-z_][A-Za-z0-9_]*, at most 255 characters.
Ros2Result<void> check_node_name(const std::string& name);
// A namespace: "/" or "/tok[/tok...]", each token a node name.
Ros2Result<void> check_namespace(const std::string& ns);
// A tf2 frame id: not empty, no leading '/', no whitespace.
Ros2Result<void> check_frame_id(const std::string& frame_id);

// "tetrapulse_" + the camera name with every character outside [A-Za-z0-9_]
// replaced by '_' ("cam-0" -> "tetrapulse_cam_0"; "" -> "tetrapulse_camera").
std::string default_node_name(const std::string& camera_name);

std::string child_frame_id(const std::string& ns, int target_id);
// ROS topic names (absolute) of a node in namespace `ns`.
std::string pose_topic(const std::string& ns, int target_id);  // "/tetrapulse/target_3/pose"
std::string status_topic(const std::string& ns);              // "/tetrapulse/status"
inline constexpr const char* kTfTopic = "/tf";
// The DDS topic of a ROS topic: "rt" + ros_topic.
std::string dds_topic(const std::string& ros_topic);

}  // namespace tetrapulse::ros2

#pragma once
// How a TargetPose reads in ROS 2 terms.
//
// Transform: parent = the camera frame (OpenCV: x right, y down, z forward), child
// = the target frame; translation t and rotation R of p_C = R p_T + t (metres), so
// that tf2 maps target coordinates into the camera frame exactly as the pose does.
//
// Covariance. The refinement's is over (w, v) with R <- exp([w]x) R, t <- t + v,
// w and v in the camera frame (pose_refinement.hpp). geometry_msgs'
// PoseWithCovariance orders its 6x6 row-major matrix (x, y, z, rotation about X,
// about Y, about Z), the rotations about the fixed axes of the parent frame,
// i.e. a small rotation d applied as R <- exp([d]x) R in the camera frame: the
// same perturbation as w. So
//   C_ros = P C_wv P^T,   P = [0 I; I 0]   (positions first, then rotations),
// in m^2, m rad and rad^2. (Tools that read the rotation block as roll/pitch/yaw
// Euler-angle covariance agree with this to first order near the identity only.)
#include <array>
#include <cstdint>

#include <Eigen/Core>

namespace tetrapulse::ros2 {

// builtin_interfaces/msg/Time.
struct RosTime {
  int32_t sec = 0;
  uint32_t nanosec = 0;  // [0, 1e9)
};

// ns = sec * 1e9 + nanosec with nanosec in [0, 1e9) (floor division, also for
// negative times). Seconds outside int32 saturate (with nanosec 0 or 999999999).
RosTime ros_time(int64_t ns);
int64_t nanoseconds(const RosTime& t);

// C_ros (row-major, 36 values) from the refinement's covariance of (w, v).
std::array<double, 36> ros_pose_covariance(const Eigen::Matrix<double, 6, 6>& covariance_wv);
// The inverse: (w, v) covariance from a ROS covariance.
Eigen::Matrix<double, 6, 6> wv_covariance(const std::array<double, 36>& ros_covariance);

}  // namespace tetrapulse::ros2

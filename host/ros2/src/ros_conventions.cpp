#include "tetrapulse/ros2/ros_conventions.hpp"

#include <limits>

namespace tetrapulse::ros2 {

namespace {

constexpr int64_t kNsPerSec = 1'000'000'000;

// Block swap between (w, v) and (v, w): index i of one is index (i + 3) % 6 of the other.
int swapped(int i) { return (i + 3) % 6; }

}  // namespace

RosTime ros_time(int64_t ns) {
  int64_t sec = ns / kNsPerSec;
  int64_t rest = ns % kNsPerSec;
  if (rest < 0) {
    rest += kNsPerSec;
    sec -= 1;
  }
  if (sec > std::numeric_limits<int32_t>::max()) return RosTime{std::numeric_limits<int32_t>::max(), uint32_t(kNsPerSec - 1)};
  if (sec < std::numeric_limits<int32_t>::min()) return RosTime{std::numeric_limits<int32_t>::min(), 0};
  return RosTime{int32_t(sec), uint32_t(rest)};
}

int64_t nanoseconds(const RosTime& t) { return int64_t(t.sec) * kNsPerSec + int64_t(t.nanosec); }

std::array<double, 36> ros_pose_covariance(const Eigen::Matrix<double, 6, 6>& covariance_wv) {
  std::array<double, 36> out{};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out[size_t(r * 6 + c)] = covariance_wv(swapped(r), swapped(c));
  }
  return out;
}

Eigen::Matrix<double, 6, 6> wv_covariance(const std::array<double, 36>& ros_covariance) {
  Eigen::Matrix<double, 6, 6> out;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out(swapped(r), swapped(c)) = ros_covariance[size_t(r * 6 + c)];
  }
  return out;
}

}  // namespace tetrapulse::ros2

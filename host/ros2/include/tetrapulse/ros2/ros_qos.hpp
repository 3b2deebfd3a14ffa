#pragma once
// The ROS 2 QoS profiles tetrapulse's topics use, as Cyclone DDS QoS (what
// rmw_cyclonedds sets for them). Readers built for tests use the same.
//   tf              reliable, volatile, keep last 100 (tf2's listener and broadcaster)
//   sensor data     best effort, volatile, keep last 5 (rmw_qos_profile_sensor_data)
//   default         reliable, volatile, keep last 10 (diagnostics)
//   discovery info  reliable, transient local, keep last 1 (ros_discovery_info)
#include <memory>

#include <dds/dds.h>

namespace tetrapulse::ros2 {

struct QosProfile {
  bool reliable = true;
  bool transient_local = false;
  int depth = 10;
};
inline constexpr QosProfile kTfQos{true, false, 100};
inline constexpr QosProfile kSensorDataQos{false, false, 5};
inline constexpr QosProfile kDefaultQos{true, false, 10};
inline constexpr QosProfile kDiscoveryInfoQos{true, true, 1};

struct DdsQosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};
using DdsQos = std::unique_ptr<dds_qos_t, DdsQosDeleter>;

// As rmw_cyclonedds: keep-last history, writers that do not dispose on unregister,
// a durability service history equal to the history for transient local.
DdsQos ros_qos(const QosProfile& profile);

}  // namespace tetrapulse::ros2

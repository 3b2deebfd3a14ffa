#include "tetrapulse/ros2/ros_qos.hpp"

namespace tetrapulse::ros2 {

DdsQos ros_qos(const QosProfile& profile) {
  DdsQos q(dds_create_qos());
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, profile.depth);
  if (profile.reliable) {
    dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_INFINITY);
  } else {
    dds_qset_reliability(q.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
  }
  if (profile.transient_local) {
    dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
    dds_qset_durability_service(q.get(), 0, DDS_HISTORY_KEEP_LAST, profile.depth, DDS_LENGTH_UNLIMITED,
                                DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  } else {
    dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  }
  dds_qset_writer_data_lifecycle(q.get(), false);
  return q;
}

}  // namespace tetrapulse::ros2

#pragma once
// A ROS 2 node made visible the way rmw_dds_common does it: the participant
// writes one rmw_dds_common/msg/ParticipantEntitiesInfo on the DDS topic
// "ros_discovery_info" (no "rt/" prefix; reliable, transient local, keep last 1,
// so that tools started later still read it): its own Gid and, per node, the
// namespace, the name and the Gids of the node's readers and writers. Written
// again whenever the node's endpoints change.
#include <string>
#include <vector>

#include "dds_entity.hpp"
#include "tetrapulse/ros2/ros2_error.hpp"

namespace tetrapulse::ros2 {

class NodeAnnouncement {
 public:
  static Ros2Result<NodeAnnouncement> create(dds_entity_t participant, std::string ros_namespace,
                                             std::string node_name);
  Ros2Result<void> announce(const std::vector<dds_entity_t>& readers, const std::vector<dds_entity_t>& writers);

 private:
  NodeAnnouncement() = default;
  dds_entity_t participant_ = 0;
  DdsEntity topic_;
  DdsEntity writer_;
  std::string namespace_;
  std::string name_;
};

}  // namespace tetrapulse::ros2

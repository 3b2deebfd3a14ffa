#pragma once
// The DDS participant of a ROS 2 node, as rmw_cyclonedds creates it.
#include <cstdint>
#include <string>

#include "dds_entity.hpp"
#include "tetrapulse/ros2/ros2_error.hpp"

namespace tetrapulse::ros2 {

// A participant in `domain` with USER_DATA "enclave=/;" and the node's name as its
// entity name. On failure, kDdsUnavailable whose message is what Cyclone DDS
// logged while trying (which would otherwise go to stderr), e.g.
// "tp_x0: does not match an available interface".
Ros2Result<DdsEntity> create_ros_participant(uint32_t domain, const std::string& node_name);

// The 16 bytes of an entity's DDS GUID: ROS 2's Gid of it.
void entity_gid(dds_entity_t entity, char out[16]);

}  // namespace tetrapulse::ros2

#include "node_announcement.hpp"

#include <cstring>

#include "dds_participant.hpp"
#include "rmw_dds_common.h"
#include "tetrapulse/ros2/ros_qos.hpp"

namespace tetrapulse::ros2 {

namespace {

using Gid = rmw_dds_common_msg_dds__Gid_;

std::vector<Gid> gids_of(const std::vector<dds_entity_t>& entities) {
  std::vector<Gid> out(entities.size());
  for (size_t i = 0; i < entities.size(); ++i) entity_gid(entities[i], out[i].data);
  return out;
}

// A bounded IDL string<256> field: at most 256 characters (names are checked before).
template <size_t N>
void copy_bounded(const std::string& s, char (&to)[N]) {
  const size_t n = std::min(s.size(), N - 1);
  std::memcpy(to, s.data(), n);
  to[n] = '\0';
}

}  // namespace

Ros2Result<NodeAnnouncement> NodeAnnouncement::create(dds_entity_t participant, std::string ros_namespace,
                                                      std::string node_name) {
  NodeAnnouncement a;
  a.participant_ = participant;
  a.namespace_ = std::move(ros_namespace);
  a.name_ = std::move(node_name);
  const DdsQos qos = ros_qos(kDiscoveryInfoQos);
  a.topic_ = DdsEntity(dds_create_topic(participant, &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc,
                                        "ros_discovery_info", qos.get(), nullptr));
  if (a.topic_.get() < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed,
                      std::string("topic ros_discovery_info: ") + dds_strretcode(a.topic_.get()));
  }
  a.writer_ = DdsEntity(dds_create_writer(participant, a.topic_.get(), qos.get(), nullptr));
  if (a.writer_.get() < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed,
                      std::string("writer of ros_discovery_info: ") + dds_strretcode(a.writer_.get()));
  }
  return a;
}

Ros2Result<void> NodeAnnouncement::announce(const std::vector<dds_entity_t>& readers,
                                            const std::vector<dds_entity_t>& writers) {
  std::vector<Gid> reader_gids = gids_of(readers), writer_gids = gids_of(writers);
  rmw_dds_common_msg_dds__NodeEntitiesInfo_ node{};
  copy_bounded(namespace_, node.node_namespace);
  copy_bounded(name_, node.node_name);
  node.reader_gid_seq._length = node.reader_gid_seq._maximum = uint32_t(reader_gids.size());
  node.reader_gid_seq._buffer = reader_gids.data();
  node.writer_gid_seq._length = node.writer_gid_seq._maximum = uint32_t(writer_gids.size());
  node.writer_gid_seq._buffer = writer_gids.data();

  rmw_dds_common_msg_dds__ParticipantEntitiesInfo_ info{};
  entity_gid(participant_, info.gid.data);
  info.node_entities_info_seq._length = info.node_entities_info_seq._maximum = 1;
  info.node_entities_info_seq._buffer = &node;
  const dds_return_t r = dds_write(writer_.get(), &info);
  if (r < 0) return ros2_error(Ros2Error::Kind::kDdsFailed, std::string("ros_discovery_info: ") + dds_strretcode(r));
  return {};
}

}  // namespace tetrapulse::ros2

#include "dds_participant.hpp"

#include <cstring>

#include "tetrapulse/ros2/ros_qos.hpp"

namespace tetrapulse::ros2 {

namespace {

void collect_log(void* arg, const dds_log_data_t* data) {
  auto* text = static_cast<std::string*>(arg);
  std::string line(data->message, data->size);
  while (!line.empty() && (line.back() == '\n' || line.back() == ' ')) line.pop_back();
  if (line.empty()) return;
  if (!text->empty()) *text += "; ";
  *text += line;
}

}  // namespace

Ros2Result<DdsEntity> create_ros_participant(uint32_t domain, const std::string& node_name) {
  DdsQos qos(dds_create_qos());
  // rmw_cyclonedds' USER_DATA: the security enclave, "/" without ROS security.
  static constexpr char kUserData[] = "enclave=/;";
  dds_qset_userdata(qos.get(), kUserData, sizeof(kUserData) - 1);
  dds_qset_entity_name(qos.get(), node_name.c_str());
  // Cyclone logs why it cannot start (to stderr by default); keep it for the error instead.
  std::string log;
  dds_set_log_sink(collect_log, &log);
  const dds_entity_t p = dds_create_participant(dds_domainid_t(domain), qos.get(), nullptr);
  dds_set_log_sink(nullptr, nullptr);
  if (p < 0) {
    std::string why = log.empty() ? std::string(dds_strretcode(p)) : log;
    return ros2_error(Ros2Error::Kind::kDdsUnavailable, why);
  }
  return DdsEntity(p);
}

void entity_gid(dds_entity_t entity, char out[16]) {
  dds_guid_t guid{};
  dds_get_guid(entity, &guid);
  static_assert(sizeof(guid.v) == 16, "a DDS GUID is 16 bytes");
  std::memcpy(out, guid.v, 16);
}

}  // namespace tetrapulse::ros2

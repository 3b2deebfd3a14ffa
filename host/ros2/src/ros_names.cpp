#include "tetrapulse/ros2/ros_names.hpp"

#include <cctype>

namespace tetrapulse::ros2 {

namespace {

bool name_char(char c, bool first) {
  const unsigned char u = static_cast<unsigned char>(c);
  return std::isalpha(u) || c == '_' || (!first && std::isdigit(u));
}

bool valid_token(const std::string& s) {
  if (s.empty() || s.size() > 255) return false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (!name_char(s[i], i == 0)) return false;
  }
  return true;
}

// NS with a trailing slash ("/" stays "/"), for appending relative names.
std::string with_slash(const std::string& ns) { return ns == "/" ? ns : ns + "/"; }

}  // namespace

Ros2Result<void> check_node_name(const std::string& name) {
  if (!valid_token(name)) {
    return ros2_error(Ros2Error::Kind::kBadName,
                      "node name '" + name + "': must be a letter or '_' then letters, digits or '_' (at most 255)");
  }
  return {};
}

Ros2Result<void> check_namespace(const std::string& ns) {
  bool ok = !ns.empty() && ns[0] == '/';
  if (ok && ns != "/") {
    size_t from = 1;
    while (ok) {
      const size_t slash = ns.find('/', from);
      ok = valid_token(ns.substr(from, slash == std::string::npos ? std::string::npos : slash - from));
      if (slash == std::string::npos) break;
      from = slash + 1;
    }
  }
  if (!ok) {
    return ros2_error(Ros2Error::Kind::kBadName,
                      "namespace '" + ns + "': must be '/' or '/name[/name...]', names as for nodes");
  }
  return {};
}

Ros2Result<void> check_frame_id(const std::string& frame_id) {
  bool ok = !frame_id.empty() && frame_id[0] != '/';
  for (char c : frame_id) ok = ok && !std::isspace(static_cast<unsigned char>(c)) && std::isprint(static_cast<unsigned char>(c));
  if (!ok) {
    return ros2_error(Ros2Error::Kind::kBadName,
                      "frame id '" + frame_id + "': must be printable, without spaces or a leading '/'");
  }
  return {};
}

std::string default_node_name(const std::string& camera_name) {
  std::string name = "tetrapulse_" + (camera_name.empty() ? std::string("camera") : camera_name);
  for (char& c : name) {
    if (!name_char(c, false)) c = '_';
  }
  return name.substr(0, 255);
}

std::string child_frame_id(const std::string& ns, int target_id) {
  const std::string prefix = ns == "/" ? "" : ns.substr(1) + "/";
  return prefix + "tetrapulse/target_" + std::to_string(target_id);
}

std::string pose_topic(const std::string& ns, int target_id) {
  return with_slash(ns) + "tetrapulse/target_" + std::to_string(target_id) + "/pose";
}

std::string status_topic(const std::string& ns) { return with_slash(ns) + "tetrapulse/status"; }

std::string dds_topic(const std::string& ros_topic) { return "rt" + ros_topic; }

}  // namespace tetrapulse::ros2

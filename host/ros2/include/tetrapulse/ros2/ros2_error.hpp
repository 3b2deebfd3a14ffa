#pragma once
// Errors of the ROS 2 publisher, as values (tl::expected).
#include <string>

#include <tl/expected.hpp>

namespace tetrapulse::ros2 {

struct Ros2Error {
  enum class Kind {
    kBadName,         // a node name, namespace or frame id ROS 2 would refuse
    kBadEnvironment,  // ROS_DOMAIN_ID is not a domain number
    kDdsUnavailable,  // the DDS participant cannot be created (configuration, interfaces)
    kDdsFailed,       // a topic, writer or write failed after the start
  };
  Kind kind;
  std::string message;  // one line: what, and where ("ROS_DOMAIN_ID=abc: not a number")
};

template <typename T>
using Ros2Result = tl::expected<T, Ros2Error>;

inline tl::unexpected<Ros2Error> ros2_error(Ros2Error::Kind kind, std::string message) {
  return tl::unexpected<Ros2Error>(Ros2Error{kind, std::move(message)});
}

}  // namespace tetrapulse::ros2

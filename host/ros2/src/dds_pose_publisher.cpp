#include "tetrapulse/ros2/dds_pose_publisher.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <map>

#include "dds_entity.hpp"
#include "dds_participant.hpp"
#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "node_announcement.hpp"
#include "tetrapulse/ros2/ros_conventions.hpp"
#include "tetrapulse/ros2/ros_names.hpp"
#include "tetrapulse/ros2/ros_qos.hpp"
#include "tetrapulse/ros2/status_diagnostics.hpp"
#include "tf2_msgs.h"

namespace tetrapulse::ros2 {

namespace {

using Clock = std::chrono::steady_clock;
using TransformStamped = geometry_msgs_msg_dds__TransformStamped_;

// IDL strings are char*; Cyclone only reads them when writing.
char* c_str(const std::string& s) { return const_cast<char*>(s.c_str()); }

void set_stamp(int64_t ns, builtin_interfaces_msg_dds__Time_* out) {
  const RosTime t = ros_time(ns);
  out->sec = t.sec;
  out->nanosec = t.nanosec;
}

struct Writer {
  DdsEntity topic;
  DdsEntity writer;
};

Ros2Result<Writer> make_writer(dds_entity_t participant, const dds_topic_descriptor_t* type,
                               const std::string& ros_topic, const QosProfile& profile) {
  const DdsQos qos = ros_qos(profile);
  const std::string name = dds_topic(ros_topic);
  Writer w;
  w.topic = DdsEntity(dds_create_topic(participant, type, name.c_str(), qos.get(), nullptr));
  if (w.topic.get() < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed, "topic " + ros_topic + ": " + dds_strretcode(w.topic.get()));
  }
  w.writer = DdsEntity(dds_create_writer(participant, w.topic.get(), qos.get(), nullptr));
  if (w.writer.get() < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed, "writer of " + ros_topic + ": " + dds_strretcode(w.writer.get()));
  }
  dds_set_status_mask(w.writer.get(), DDS_PUBLICATION_MATCHED_STATUS);
  return w;
}

class DdsPosePublisher final : public PosePublisher {
 public:
  static Ros2Result<std::unique_ptr<PosePublisher>> open(const DdsPublisherOptions& options, uint32_t domain);

 private:
  DdsPosePublisher() = default;

  Ros2Result<void> do_publish(const std::vector<TargetPose>& poses) override;
  Ros2Result<void> do_publish_status(const LocalizerStatus& status) override;
  int do_wait_for_readers(int64_t timeout_ns, int64_t settle_ns) override;
  bool do_wait_for_acknowledgments(int64_t timeout_ns) override;
  PublishCounters do_counters() const override { return counters_; }

  int64_t stamp(int64_t rig_ns) const { return options_.stamp_ns ? options_.stamp_ns(rig_ns) : rig_ns; }
  Ros2Result<const Writer*> pose_writer(int target_id);
  Ros2Result<void> announce();
  std::vector<dds_entity_t> writers() const;

  DdsPublisherOptions options_;
  DdsEntity participant_;  // first: deleted last
  std::optional<NodeAnnouncement> announcement_;
  Writer tf_;
  Writer status_;
  std::map<int, Writer> pose_writers_;
  std::map<int, std::string> child_frames_;
  std::vector<TransformStamped> transforms_;  // reused per frame
  uint64_t last_dropped_ = 0;
  PublishCounters counters_;
};

Ros2Result<std::unique_ptr<PosePublisher>> DdsPosePublisher::open(const DdsPublisherOptions& options,
                                                                  uint32_t domain) {
  std::unique_ptr<DdsPosePublisher> p(new DdsPosePublisher());
  p->options_ = options;
  auto participant = create_ros_participant(domain, options.node_name);
  if (!participant) return tl::unexpected(participant.error());
  p->participant_ = std::move(*participant);
  const dds_entity_t pp = p->participant_.get();
  auto announcement = NodeAnnouncement::create(pp, options.ros_namespace, options.node_name);
  if (!announcement) return tl::unexpected(announcement.error());
  p->announcement_ = std::move(*announcement);
  auto tf = make_writer(pp, &tf2_msgs_msg_dds__TFMessage__desc, kTfTopic, kTfQos);
  if (!tf) return tl::unexpected(tf.error());
  p->tf_ = std::move(*tf);
  auto status = make_writer(pp, &diagnostic_msgs_msg_dds__DiagnosticArray__desc, status_topic(options.ros_namespace),
                            kDefaultQos);
  if (!status) return tl::unexpected(status.error());
  p->status_ = std::move(*status);
  for (int id : options.target_ids) {
    auto w = make_writer(pp, &geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc,
                         pose_topic(options.ros_namespace, id), kSensorDataQos);
    if (!w) return tl::unexpected(w.error());
    p->pose_writers_.emplace(id, std::move(*w));
  }
  if (auto r = p->announce(); !r) return tl::unexpected(r.error());
  return std::unique_ptr<PosePublisher>(std::move(p));
}

std::vector<dds_entity_t> DdsPosePublisher::writers() const {
  std::vector<dds_entity_t> w{tf_.writer.get(), status_.writer.get()};
  for (const auto& [id, pw] : pose_writers_) w.push_back(pw.writer.get());
  return w;
}

Ros2Result<void> DdsPosePublisher::announce() { return announcement_->announce({}, writers()); }

Ros2Result<const Writer*> DdsPosePublisher::pose_writer(int target_id) {
  auto it = pose_writers_.find(target_id);
  if (it != pose_writers_.end()) return &it->second;
  // A target the options did not list: its topic appears now (readers may miss its first poses).
  auto w = make_writer(participant_.get(), &geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc,
                       pose_topic(options_.ros_namespace, target_id), kSensorDataQos);
  if (!w) return tl::unexpected(w.error());
  it = pose_writers_.emplace(target_id, std::move(*w)).first;
  if (auto r = announce(); !r) return tl::unexpected(r.error());
  return &it->second;
}

Ros2Result<void> DdsPosePublisher::do_publish(const std::vector<TargetPose>& poses) {
  ++counters_.frames;
  if (poses.empty()) return {};
  transforms_.assign(poses.size(), TransformStamped{});
  for (size_t i = 0; i < poses.size(); ++i) {
    const TargetPose& p = poses[i];
    auto child = child_frames_.find(p.target_id);
    if (child == child_frames_.end()) {
      child = child_frames_.emplace(p.target_id, child_frame_id(options_.ros_namespace, p.target_id)).first;
    }
    const Eigen::Quaterniond q = p.pose.quaternion();
    TransformStamped& t = transforms_[i];
    set_stamp(stamp(p.mid_exposure_ns), &t.header.stamp);
    t.header.frame_id = c_str(options_.frame_id);
    t.child_frame_id = c_str(child->second);
    t.transform.translation = {p.pose.t.x(), p.pose.t.y(), p.pose.t.z()};
    t.transform.rotation = {q.x(), q.y(), q.z(), q.w()};
  }
  tf2_msgs_msg_dds__TFMessage_ message{};
  message.transforms._length = message.transforms._maximum = uint32_t(transforms_.size());
  message.transforms._buffer = transforms_.data();
  if (const dds_return_t r = dds_write(tf_.writer.get(), &message); r < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed, std::string("writing /tf: ") + dds_strretcode(r));
  }
  counters_.transforms += poses.size();

  for (size_t i = 0; i < poses.size(); ++i) {
    const TargetPose& p = poses[i];
    auto w = pose_writer(p.target_id);
    if (!w) return tl::unexpected(w.error());
    geometry_msgs_msg_dds__PoseWithCovarianceStamped_ m{};
    m.header = transforms_[i].header;
    m.pose.pose.position = {p.pose.t.x(), p.pose.t.y(), p.pose.t.z()};
    m.pose.pose.orientation = transforms_[i].transform.rotation;
    if (p.has_covariance) {
      const std::array<double, 36> c = ros_pose_covariance(p.covariance);
      std::copy(c.begin(), c.end(), m.pose.covariance);
    }
    if (const dds_return_t r = dds_write((*w)->writer.get(), &m); r < 0) {
      return ros2_error(Ros2Error::Kind::kDdsFailed,
                        "writing " + pose_topic(options_.ros_namespace, p.target_id) + ": " + dds_strretcode(r));
    }
    ++counters_.poses;
  }
  return {};
}

Ros2Result<void> DdsPosePublisher::do_publish_status(const LocalizerStatus& status) {
  const uint64_t dropped = status.frames_dropped >= last_dropped_ ? status.frames_dropped - last_dropped_ : 0;
  last_dropped_ = status.frames_dropped;
  const std::vector<DiagnosticEntry> entries = status_diagnostics(status, options_.node_name, options_.frame_id, dropped);
  std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> out(entries.size());
  std::vector<std::vector<diagnostic_msgs_msg_dds__KeyValue_>> values(entries.size());
  for (size_t i = 0; i < entries.size(); ++i) {
    const DiagnosticEntry& e = entries[i];
    for (const auto& [key, value] : e.values) values[i].push_back({c_str(key), c_str(value)});
    out[i].level = e.level;
    out[i].name = c_str(e.name);
    out[i].message = c_str(e.message);
    out[i].hardware_id = c_str(e.hardware_id);
    out[i].values._length = out[i].values._maximum = uint32_t(values[i].size());
    out[i].values._buffer = values[i].data();
  }
  diagnostic_msgs_msg_dds__DiagnosticArray_ m{};
  set_stamp(stamp(status.rig_time_ns), &m.header.stamp);
  m.header.frame_id = c_str(options_.frame_id);
  m.status._length = m.status._maximum = uint32_t(out.size());
  m.status._buffer = out.data();
  if (const dds_return_t r = dds_write(status_.writer.get(), &m); r < 0) {
    return ros2_error(Ros2Error::Kind::kDdsFailed,
                      "writing " + status_topic(options_.ros_namespace) + ": " + dds_strretcode(r));
  }
  ++counters_.statuses;
  return {};
}

int DdsPosePublisher::do_wait_for_readers(int64_t timeout_ns, int64_t settle_ns) {
  DdsEntity waitset(dds_create_waitset(participant_.get()));
  const std::vector<dds_entity_t> ws = writers();
  for (dds_entity_t w : ws) dds_waitset_attach(waitset.get(), w, w);
  const auto deadline = Clock::now() + std::chrono::nanoseconds(timeout_ns);
  std::optional<Clock::time_point> last_match;
  uint32_t readers = 0;
  for (;;) {
    uint32_t matched_changes = 0;
    readers = 0;
    for (dds_entity_t w : ws) {
      dds_publication_matched_status_t s{};
      dds_get_publication_matched_status(w, &s);  // also resets the status' trigger
      matched_changes += s.total_count_change;
      readers += s.current_count;
    }
    const auto now = Clock::now();
    if (matched_changes > 0) last_match = now;
    Clock::time_point until = deadline;
    if (readers > 0 && last_match) {
      const auto settled = *last_match + std::chrono::nanoseconds(settle_ns);
      if (now >= settled) break;
      until = std::min(until, settled);
    }
    if (now >= deadline) break;
    const auto wait = std::chrono::duration_cast<std::chrono::nanoseconds>(until - now).count();
    dds_waitset_wait(waitset.get(), nullptr, 0, dds_duration_t(wait));
  }
  return int(readers);
}

bool DdsPosePublisher::do_wait_for_acknowledgments(int64_t timeout_ns) {
  // Reliable writers only: best-effort ones have nothing to wait for.
  const auto deadline = Clock::now() + std::chrono::nanoseconds(timeout_ns);
  for (dds_entity_t w : {tf_.writer.get(), status_.writer.get()}) {
    const int64_t left = std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - Clock::now()).count();
    if (dds_wait_for_acks(w, dds_duration_t(std::max<int64_t>(left, 0))) != DDS_RETCODE_OK) return false;
  }
  return true;
}

}  // namespace

Ros2Result<uint32_t> ros_domain_id() {
  const char* env = std::getenv("ROS_DOMAIN_ID");
  if (env == nullptr || *env == '\0') return 0u;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  if (*end != '\0' || v < 0 || v > 232) {
    return ros2_error(Ros2Error::Kind::kBadEnvironment,
                      std::string("ROS_DOMAIN_ID=") + env + ": not a domain number (0 to 232)");
  }
  return uint32_t(v);
}

Ros2Result<std::unique_ptr<PosePublisher>> open_dds_publisher(const DdsPublisherOptions& options) {
  if (auto r = check_node_name(options.node_name); !r) return tl::unexpected(r.error());
  if (auto r = check_namespace(options.ros_namespace); !r) return tl::unexpected(r.error());
  if (auto r = check_frame_id(options.frame_id); !r) return tl::unexpected(r.error());
  uint32_t domain = 0;
  if (options.domain_id) {
    domain = *options.domain_id;
  } else {
    auto d = ros_domain_id();
    if (!d) return tl::unexpected(d.error());
    domain = *d;
  }
  auto p = DdsPosePublisher::open(options, domain);
  if (!p && p.error().kind == Ros2Error::Kind::kDdsUnavailable) {
    const char* uri = std::getenv("CYCLONEDDS_URI");
    p.error().message = "DDS cannot start in domain " + std::to_string(domain) +
                        (uri != nullptr && *uri != '\0' ? std::string(" (CYCLONEDDS_URI=") + uri + ")" : "") + ": " +
                        p.error().message;
  }
  return p;
}

}  // namespace tetrapulse::ros2

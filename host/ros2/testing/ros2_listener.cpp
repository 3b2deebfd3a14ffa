// tetrapulse_ros2_listener: a ROS 2 reader built from the same IDL as the
// publisher, with nothing of the publisher's code path, for tests and the
// benchmark. It subscribes one topic the way a ROS 2 node would and writes what
// it takes to a CSV file:
//   tf            rt/tf: sec,nanosec,parent,child,x,y,z,qx,qy,qz,qw (one line per transform)
//   pose          rt/...: sec,nanosec,frame,x,y,z,qx,qy,qz,qw,c0..c35
//   status        rt/...: sec,nanosec,frame,level,name,message,hardware_id,key=value;...
//   discovery     ros_discovery_info (transient local): participant_gid,namespace,node,reader_gids,writer_gids
//   publications  the DCPSPublication built-in topic: gid,topic,type,reliability,durability,depth
// It prints "ready" on stdout once its reader exists, and at the end one line
// "samples N matched M incompatible_qos K lost L". It ends when --count samples
// came, when --writers writers have matched and all have gone again, or after
// --timeout-ms (exit 4); with --until-incompatible, as soon as a writer whose QoS
// does not match its reader's was seen. --count-only takes samples without
// formatting them (for the benchmark). Runs only inside tests/netns/isolated.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <dds/dds.h>
#include <fmt/format.h>

#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "rmw_dds_common.h"
#include "tetrapulse/ros2/dds_pose_publisher.hpp"
#include "tetrapulse/ros2/ros_qos.hpp"
#include "tf2_msgs.h"

namespace {

using namespace tetrapulse::ros2;
using Clock = std::chrono::steady_clock;

struct Args {
  std::string kind;
  std::string topic;
  std::string out;
  bool reliable = true;
  bool transient_local = false;
  int depth = 100;
  long count = 0;        // 0: no limit
  long writers = 1;      // end once this many writers matched and all went
  long timeout_ms = 60000;
  bool until_incompatible = false;  // end once a writer with incompatible QoS was seen
  bool count_only = false;          // take and count, format nothing (a reader as light as can be)
};

int usage() {
  std::fprintf(stderr,
               "usage: tetrapulse_ros2_listener tf|pose|status|discovery|publications --out FILE [--topic DDS_TOPIC]\n"
               "       [--best-effort] [--transient-local] [--depth N] [--count N] [--writers N] [--timeout-ms N]\n"
               "       [--until-incompatible] [--count-only]\n");
  return 2;
}

std::string hex(const void* bytes, size_t n) {
  std::string s;
  for (size_t i = 0; i < n; ++i) s += fmt::format("{:02x}", static_cast<const unsigned char*>(bytes)[i]);
  return s;
}

std::string number(double v) { return fmt::format("{:.17g}", v); }

std::string stamp(const builtin_interfaces_msg_dds__Time_& t) { return fmt::format("{},{}", t.sec, t.nanosec); }

void write_tf(const tf2_msgs_msg_dds__TFMessage_& m, std::string* out, long* n) {
  for (uint32_t i = 0; i < m.transforms._length; ++i) {
    const auto& t = m.transforms._buffer[i];
    const auto& tr = t.transform.translation;
    const auto& q = t.transform.rotation;
    *out += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", stamp(t.header.stamp), t.header.frame_id,
                        t.child_frame_id, number(tr.x), number(tr.y), number(tr.z), number(q.x), number(q.y),
                        number(q.z), number(q.w));
    ++*n;
  }
}

void write_pose(const geometry_msgs_msg_dds__PoseWithCovarianceStamped_& m, std::string* out, long* n) {
  const auto& p = m.pose.pose;
  *out += fmt::format("{},{},{},{},{},{},{},{},{}", stamp(m.header.stamp), m.header.frame_id, number(p.position.x),
                      number(p.position.y), number(p.position.z), number(p.orientation.x), number(p.orientation.y),
                      number(p.orientation.z), number(p.orientation.w));
  for (double c : m.pose.covariance) *out += "," + number(c);
  *out += "\n";
  ++*n;
}

void write_status(const diagnostic_msgs_msg_dds__DiagnosticArray_& m, std::string* out, long* n) {
  for (uint32_t i = 0; i < m.status._length; ++i) {
    const auto& s = m.status._buffer[i];
    std::string values;
    for (uint32_t k = 0; k < s.values._length; ++k) {
      values += fmt::format("{}{}={}", k == 0 ? "" : ";", s.values._buffer[k].key, s.values._buffer[k].value);
    }
    *out += fmt::format("{},{},{},{},{},{},{}\n", stamp(m.header.stamp), m.header.frame_id, int(s.level), s.name,
                        s.message, s.hardware_id, values);
  }
  ++*n;
}

std::string gids(const dds_sequence_rmw_dds_common_msg_dds__Gid_& seq) {
  std::string s;
  for (uint32_t i = 0; i < seq._length; ++i) s += (i == 0 ? "" : ";") + hex(seq._buffer[i].data, 16);
  return s;
}

void write_discovery(const rmw_dds_common_msg_dds__ParticipantEntitiesInfo_& m, std::string* out, long* n) {
  for (uint32_t i = 0; i < m.node_entities_info_seq._length; ++i) {
    const auto& node = m.node_entities_info_seq._buffer[i];
    *out += fmt::format("{},{},{},{},{}\n", hex(m.gid.data, 16), node.node_namespace, node.node_name,
                        gids(node.reader_gid_seq), gids(node.writer_gid_seq));
  }
  ++*n;
}

void write_publication(const dds_builtintopic_endpoint_t& e, std::string* out, long* n) {
  dds_reliability_kind_t rel = DDS_RELIABILITY_BEST_EFFORT;
  dds_duration_t blocking = 0;
  dds_durability_kind_t dur = DDS_DURABILITY_VOLATILE;
  dds_history_kind_t hist = DDS_HISTORY_KEEP_LAST;
  int32_t depth = 0;
  dds_qget_reliability(e.qos, &rel, &blocking);
  dds_qget_durability(e.qos, &dur);
  dds_qget_history(e.qos, &hist, &depth);
  *out += fmt::format("{},{},{},{},{},{}\n", hex(e.key.v, 16), e.topic_name, e.type_name,
                      rel == DDS_RELIABILITY_RELIABLE ? "reliable" : "best-effort",
                      dur == DDS_DURABILITY_TRANSIENT_LOCAL ? "transient-local" : "volatile", depth);
  ++*n;
}

// Takes every sample waiting on `reader` and formats it. Returns samples taken.
long drain(const Args& a, dds_entity_t reader, std::string* out, long* n) {
  constexpr int kBatch = 64;
  void* samples[kBatch] = {};
  dds_sample_info_t infos[kBatch];
  long taken = 0;
  for (;;) {
    const dds_return_t k = dds_take(reader, samples, infos, kBatch, kBatch);
    if (k <= 0) break;
    for (int i = 0; i < k; ++i) {
      if (!infos[i].valid_data) continue;
      ++taken;
      if (a.count_only) continue;
      if (a.kind == "tf") write_tf(*static_cast<tf2_msgs_msg_dds__TFMessage_*>(samples[i]), out, n);
      if (a.kind == "pose") write_pose(*static_cast<geometry_msgs_msg_dds__PoseWithCovarianceStamped_*>(samples[i]), out, n);
      if (a.kind == "status") write_status(*static_cast<diagnostic_msgs_msg_dds__DiagnosticArray_*>(samples[i]), out, n);
      if (a.kind == "discovery") {
        write_discovery(*static_cast<rmw_dds_common_msg_dds__ParticipantEntitiesInfo_*>(samples[i]), out, n);
      }
      if (a.kind == "publications") write_publication(*static_cast<dds_builtintopic_endpoint_t*>(samples[i]), out, n);
    }
    dds_return_loan(reader, samples, k);
  }
  return taken;
}

const dds_topic_descriptor_t* type_of(const std::string& kind) {
  if (kind == "tf") return &tf2_msgs_msg_dds__TFMessage__desc;
  if (kind == "pose") return &geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc;
  if (kind == "status") return &diagnostic_msgs_msg_dds__DiagnosticArray__desc;
  if (kind == "discovery") return &rmw_dds_common_msg_dds__ParticipantEntitiesInfo__desc;
  return nullptr;
}

int run(const Args& a) {
  const char* netns = std::getenv("TETRAPULSE_IN_NETNS");
  if (netns == nullptr || std::strcmp(netns, "1") != 0) {
    std::fprintf(stderr, "tetrapulse_ros2_listener: runs only inside tests/netns/isolated\n");
    return 1;
  }
  auto domain = ros_domain_id();
  if (!domain) {
    std::fprintf(stderr, "tetrapulse_ros2_listener: %s\n", domain.error().message.c_str());
    return 1;
  }
  const dds_entity_t participant = dds_create_participant(dds_domainid_t(*domain), nullptr, nullptr);
  if (participant < 0) {
    std::fprintf(stderr, "tetrapulse_ros2_listener: no participant: %s\n", dds_strretcode(participant));
    return 1;
  }
  dds_entity_t reader = 0;
  if (a.kind == "publications") {
    reader = dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  } else {
    const DdsQos qos = ros_qos(QosProfile{a.reliable, a.transient_local, a.depth});
    const std::string topic = a.topic.empty() ? (a.kind == "tf" ? "rt/tf" : "ros_discovery_info") : a.topic;
    const dds_entity_t t = dds_create_topic(participant, type_of(a.kind), topic.c_str(), qos.get(), nullptr);
    reader = t < 0 ? t : dds_create_reader(participant, t, qos.get(), nullptr);
  }
  if (reader < 0) {
    std::fprintf(stderr, "tetrapulse_ros2_listener: no reader: %s\n", dds_strretcode(reader));
    dds_delete(participant);
    return 1;
  }
  dds_set_status_mask(reader, DDS_DATA_AVAILABLE_STATUS | DDS_SUBSCRIPTION_MATCHED_STATUS |
                                  DDS_REQUESTED_INCOMPATIBLE_QOS_STATUS | DDS_SAMPLE_LOST_STATUS);
  const dds_entity_t waitset = dds_create_waitset(participant);
  dds_waitset_attach(waitset, reader, reader);
  std::printf("ready\n");
  std::fflush(stdout);

  std::string text;
  long lines = 0, samples = 0;
  uint32_t matched_total = 0, matched_now = 0, incompatible = 0, lost = 0;
  const auto deadline = Clock::now() + std::chrono::milliseconds(a.timeout_ms);
  bool timed_out = false;
  for (;;) {
    samples += drain(a, reader, &text, &lines);
    if (a.kind != "publications") {
      dds_subscription_matched_status_t m{};
      dds_get_subscription_matched_status(reader, &m);
      matched_total = m.total_count;
      matched_now = m.current_count;
      dds_requested_incompatible_qos_status_t q{};
      dds_get_requested_incompatible_qos_status(reader, &q);
      incompatible = q.total_count;
      dds_sample_lost_status_t l{};
      dds_get_sample_lost_status(reader, &l);
      lost = l.total_count;
    }
    if (a.count > 0 && samples >= a.count) break;
    if (a.until_incompatible && incompatible > 0) break;
    if (a.writers > 0 && matched_total >= uint32_t(a.writers) && matched_now == 0) {
      samples += drain(a, reader, &text, &lines);  // what came with the last unmatch
      break;
    }
    const auto now = Clock::now();
    if (now >= deadline) {
      timed_out = true;
      break;
    }
    dds_waitset_wait(waitset, nullptr, 0,
                     dds_duration_t(std::chrono::duration_cast<std::chrono::nanoseconds>(deadline - now).count()));
  }
  dds_delete(participant);

  std::FILE* f = std::fopen(a.out.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "tetrapulse_ros2_listener: %s: cannot write\n", a.out.c_str());
    return 1;
  }
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  std::printf("samples %ld lines %ld matched %u incompatible_qos %u lost %u%s\n", samples, lines, matched_total,
              incompatible, lost, timed_out ? " timeout" : "");
  return timed_out ? 4 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (argc < 2) return usage();
  a.kind = argv[1];
  if (a.kind != "tf" && a.kind != "pose" && a.kind != "status" && a.kind != "discovery" && a.kind != "publications") {
    return usage();
  }
  // Like rmw's own reader of it: transient local, and a history that holds every participant's latest.
  if (a.kind == "discovery") a.transient_local = true;
  for (int i = 2; i < argc; ++i) {
    const std::string k = argv[i];
    const bool has_value = i + 1 < argc;
    if (k == "--best-effort") {
      a.reliable = false;
    } else if (k == "--count-only") {
      a.count_only = true;
    } else if (k == "--until-incompatible") {
      a.until_incompatible = true;
    } else if (k == "--transient-local") {
      a.transient_local = true;
    } else if (k == "--out" && has_value) {
      a.out = argv[++i];
    } else if (k == "--topic" && has_value) {
      a.topic = argv[++i];
    } else if (k == "--depth" && has_value) {
      a.depth = std::atoi(argv[++i]);
    } else if (k == "--count" && has_value) {
      a.count = std::atol(argv[++i]);
    } else if (k == "--writers" && has_value) {
      a.writers = std::atol(argv[++i]);
    } else if (k == "--timeout-ms" && has_value) {
      a.timeout_ms = std::atol(argv[++i]);
    } else {
      return usage();
    }
  }
  if (a.out.empty() || a.depth < 1) return usage();
  if ((a.kind == "pose" || a.kind == "status") && a.topic.empty()) return usage();
  return run(a);
}

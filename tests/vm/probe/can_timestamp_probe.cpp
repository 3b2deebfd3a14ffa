// can_timestamp_probe: measures which kernel timestamps a SocketCAN interface
// gives a raw socket, the facts CAN time sync is built on:
//  - what the driver advertises (ETHTOOL_GET_TS_INFO),
//  - transmit timestamps through SO_TIMESTAMPING on the error queue
//    (SCHED: when the frame entered the device queue; SOFTWARE: when the driver
//    handed it to the hardware),
//  - the receive timestamp of the socket's own frame looped back to it
//    (CAN_RAW_RECV_OWN_MSGS), which stands in for a transmit time otherwise.
// All software timestamps are CLOCK_REALTIME; delays are printed relative to
// the clock read just before send().
//
// usage: can_timestamp_probe IFACE     exits 0 when the measurement ran

#include <time.h>  // before linux/errqueue.h, which uses struct timespec

#include <linux/can.h>
#include <linux/can/raw.h>
#include <linux/errqueue.h>
#include <linux/ethtool.h>
#include <linux/net_tstamp.h>
#include <linux/sockios.h>

#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

constexpr canid_t kProbeId = 0x1ABCDE0 | CAN_EFF_FLAG;

int64_t Nanoseconds(const timespec& t) { return static_cast<int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec; }

const char* YesNo(bool b) { return b ? "yes" : "no"; }

struct Findings {
  bool tx_sched = false;
  bool tx_software = false;
  bool own_echo = false;
  bool own_echo_stamped = false;
  int64_t tx_sched_delay_ns = 0;
  int64_t tx_software_delay_ns = 0;
  int64_t own_echo_delay_ns = 0;
};

void ReportDriverCapabilities(int fd, const std::string& iface) {
  ethtool_ts_info info{};
  info.cmd = ETHTOOL_GET_TS_INFO;
  ifreq ifr{};
  std::snprintf(ifr.ifr_name, sizeof(ifr.ifr_name), "%s", iface.c_str());
  ifr.ifr_data = reinterpret_cast<char*>(&info);
  if (ioctl(fd, SIOCETHTOOL, &ifr) != 0) {
    std::printf("can_timestamp_probe: ETHTOOL_GET_TS_INFO on %s: %s\n", iface.c_str(), std::strerror(errno));
    return;
  }
  const uint32_t caps = info.so_timestamping;
  std::printf(
      "can_timestamp_probe: %s advertises so_timestamping 0x%x (tx-software %s, rx-software %s, software %s, "
      "tx-hardware %s, rx-hardware %s), phc %d\n",
      iface.c_str(), caps, YesNo(caps & SOF_TIMESTAMPING_TX_SOFTWARE), YesNo(caps & SOF_TIMESTAMPING_RX_SOFTWARE),
      YesNo(caps & SOF_TIMESTAMPING_SOFTWARE), YesNo(caps & SOF_TIMESTAMPING_TX_HARDWARE),
      YesNo(caps & SOF_TIMESTAMPING_RX_HARDWARE), info.phc_index);
}

// One message from the error queue: a transmit timestamp and what stage it marks.
void ReadErrorQueue(int fd, int64_t sent_ns, Findings* found) {
  char control[512];
  msghdr msg{};
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  if (recvmsg(fd, &msg, MSG_ERRQUEUE | MSG_DONTWAIT) < 0) return;
  const scm_timestamping* stamps = nullptr;
  const sock_extended_err* err = nullptr;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPING) {
      stamps = reinterpret_cast<const scm_timestamping*>(CMSG_DATA(c));
    } else if (c->cmsg_level == SOL_CAN_RAW && c->cmsg_type == SCM_CAN_RAW_ERRQUEUE) {
      err = reinterpret_cast<const sock_extended_err*>(CMSG_DATA(c));
    }
  }
  if (stamps == nullptr || err == nullptr || err->ee_origin != SO_EE_ORIGIN_TIMESTAMPING) return;
  const int64_t delay = Nanoseconds(stamps->ts[0]) - sent_ns;
  if (err->ee_info == SCM_TSTAMP_SCHED) {
    found->tx_sched = true;
    found->tx_sched_delay_ns = delay;
  } else if (err->ee_info == SCM_TSTAMP_SND) {
    found->tx_software = true;
    found->tx_software_delay_ns = delay;
  }
}

// One frame from the receive queue: our own frame coming back, with its receive timestamp.
void ReadOwnEcho(int fd, int64_t sent_ns, Findings* found) {
  can_frame frame{};
  iovec iov{&frame, sizeof(frame)};
  char control[512];
  msghdr msg{};
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  if (recvmsg(fd, &msg, MSG_DONTWAIT) < static_cast<ssize_t>(sizeof(frame))) return;
  if (frame.can_id != kProbeId || (msg.msg_flags & MSG_CONFIRM) == 0) return;
  found->own_echo = true;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPING) {
      const auto* stamps = reinterpret_cast<const scm_timestamping*>(CMSG_DATA(c));
      if (Nanoseconds(stamps->ts[0]) != 0) {
        found->own_echo_stamped = true;
        found->own_echo_delay_ns = Nanoseconds(stamps->ts[0]) - sent_ns;
      }
    }
  }
}

int Probe(const std::string& iface) {
  const int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    std::fprintf(stderr, "can_timestamp_probe: no raw CAN socket: %s\n", std::strerror(errno));
    return 1;
  }
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(if_nametoindex(iface.c_str()));
  if (address.can_ifindex == 0 || bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    std::fprintf(stderr, "can_timestamp_probe: cannot bind to %s: %s\n", iface.c_str(), std::strerror(errno));
    return 1;
  }
  ReportDriverCapabilities(fd, iface);

  const int own = 1;
  const int flags = SOF_TIMESTAMPING_TX_SCHED | SOF_TIMESTAMPING_TX_SOFTWARE | SOF_TIMESTAMPING_RX_SOFTWARE |
                    SOF_TIMESTAMPING_SOFTWARE | SOF_TIMESTAMPING_OPT_ID | SOF_TIMESTAMPING_OPT_TSONLY;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own)) != 0 ||
      setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPING, &flags, sizeof(flags)) != 0) {
    std::fprintf(stderr, "can_timestamp_probe: setsockopt on %s: %s\n", iface.c_str(), std::strerror(errno));
    return 1;
  }

  can_frame frame{};
  frame.can_id = kProbeId;
  frame.can_dlc = 2;
  frame.data[0] = 0x5A;
  frame.data[1] = 0xA5;
  // Receive stamps switch on through a deferred static key (net_enable_timestamp() schedules
  // a work item), so on a machine where no socket wanted them a moment ago the first frames
  // can come back unstamped: send again until one is, a few times.
  Findings found;
  int frames_sent = 0;
  for (; frames_sent < 5 && !found.own_echo_stamped; ++frames_sent) {
    timespec before{};
    clock_gettime(CLOCK_REALTIME, &before);
    const int64_t sent_ns = Nanoseconds(before);
    if (write(fd, &frame, sizeof(frame)) != static_cast<ssize_t>(sizeof(frame))) {
      std::fprintf(stderr, "can_timestamp_probe: sending on %s: %s\n", iface.c_str(), std::strerror(errno));
      return 1;
    }
    // Give every kind of timestamp a second to arrive (TCG is slow).
    for (int tick = 0; tick < 10; ++tick) {
      pollfd p{fd, POLLIN | POLLERR, 0};
      if (poll(&p, 1, 100) <= 0) continue;
      if ((p.revents & POLLERR) != 0) ReadErrorQueue(fd, sent_ns, &found);
      if ((p.revents & POLLIN) != 0) ReadOwnEcho(fd, sent_ns, &found);
    }
  }
  close(fd);

  std::printf("can_timestamp_probe: tx SCHED timestamp on the error queue: %s", YesNo(found.tx_sched));
  if (found.tx_sched) std::printf(" (%lld ns after send())", static_cast<long long>(found.tx_sched_delay_ns));
  std::printf("\ncan_timestamp_probe: tx SOFTWARE timestamp on the error queue: %s", YesNo(found.tx_software));
  if (found.tx_software) std::printf(" (%lld ns after send())", static_cast<long long>(found.tx_software_delay_ns));
  std::printf("\ncan_timestamp_probe: own frame looped back: %s, rx software timestamp: %s", YesNo(found.own_echo),
              YesNo(found.own_echo_stamped));
  if (found.own_echo_stamped) std::printf(" (%lld ns after send())", static_cast<long long>(found.own_echo_delay_ns));
  std::printf("\ncan_timestamp_probe: frames sent: %d", frames_sent);
  std::printf("\ncan_timestamp_probe: RESULT tx_sched=%s tx_software=%s own_echo_rx_timestamp=%s\n",
              YesNo(found.tx_sched), YesNo(found.tx_software), YesNo(found.own_echo_stamped));
  return found.own_echo ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: can_timestamp_probe IFACE\n");
    return 2;
  }
  return Probe(argv[1]);
}

// A raw SocketCAN socket (Documentation/networking/can.rst) with kernel timestamps
// (Documentation/networking/timestamping.rst).
#include <time.h>  // before linux/errqueue.h, which uses struct timespec

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <linux/errqueue.h>
#include <linux/net_tstamp.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "tetrapulse/host/can_port.hpp"
#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {
namespace {

int64_t nanoseconds(const timespec& t) { return static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec; }

// A software kernel timestamp (CLOCK_REALTIME) on CLOCK_MONOTONIC; 0 stays 0.
int64_t monotonic_stamp(const timespec& t) {
  const int64_t real = nanoseconds(t);
  return real == 0 ? 0 : monotonic_from_realtime_ns(real);
}

class SocketCanPort final : public CanPort {
 public:
  SocketCanPort(std::string name, int fd) : name_(std::move(name)), fd_(fd) {}
  ~SocketCanPort() override { ::close(fd_); }

 private:
  const std::string& do_interface_name() const override { return name_; }

  HostResult<uint32_t> do_send(const protocol::CanFrame& frame) override {
    can_frame f{};
    f.can_id = (frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    f.can_dlc = frame.size;
    std::memcpy(f.data, frame.data, frame.size);
    // A full transmit queue (ENOBUFS) drains within milliseconds on a live bus: wait for room.
    for (int attempt = 0;; ++attempt) {
      const ssize_t n = ::write(fd_, &f, sizeof(f));
      if (n == static_cast<ssize_t>(sizeof(f))) return tx_key_++;
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == ENOBUFS || errno == EAGAIN) && attempt < 100) {
        pollfd p{fd_, POLLOUT, 0};
        ::poll(&p, 1, 10);
        continue;
      }
      const int e = errno;
      if (e == ENETDOWN) return host_error(HostErrorKind::kIo, "can:" + name_, "send: the interface is down");
      return host_error(HostErrorKind::kIo, "can:" + name_, fmt::format("send: {}", std::strerror(e)));
    }
  }

  HostResult<std::optional<CanPortEvent>> do_next(int64_t timeout_ns) override {
    const int64_t deadline = monotonic_now_ns() + timeout_ns;
    for (;;) {
      pollfd p{fd_, POLLIN | POLLERR, 0};
      const int64_t left = deadline - monotonic_now_ns();
      const int ready = ::poll(&p, 1, left <= 0 ? 0 : static_cast<int>((left + 999'999) / 1'000'000));
      if (ready < 0 && errno == EINTR) continue;
      if (ready < 0) return host_error(HostErrorKind::kIo, "can:" + name_, fmt::format("poll: {}", std::strerror(errno)));
      if (ready == 0) return std::nullopt;
      if ((p.revents & POLLERR) != 0) {
        if (auto stamp = read_error_queue()) return stamp;
      }
      if ((p.revents & POLLIN) != 0) {
        auto event = read_frame();
        if (!event) return tl::unexpected(event.error());
        if (event->has_value()) return event;
      }
      if (monotonic_now_ns() >= deadline) return std::nullopt;
    }
  }

  // A transmit timestamp from the error queue, if that is what is there.
  std::optional<CanPortEvent> read_error_queue() {
    char control[512];
    msghdr msg{};
    msg.msg_control = control;
    msg.msg_controllen = sizeof(control);
    if (::recvmsg(fd_, &msg, MSG_ERRQUEUE | MSG_DONTWAIT) < 0) return std::nullopt;
    const scm_timestamping* stamps = nullptr;
    const sock_extended_err* err = nullptr;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPING) {
        stamps = reinterpret_cast<const scm_timestamping*>(CMSG_DATA(c));
      } else if (c->cmsg_level == SOL_CAN_RAW && c->cmsg_type == SCM_CAN_RAW_ERRQUEUE) {
        err = reinterpret_cast<const sock_extended_err*>(CMSG_DATA(c));
      }
    }
    if (stamps == nullptr || err == nullptr || err->ee_origin != SO_EE_ORIGIN_TIMESTAMPING ||
        err->ee_info != SCM_TSTAMP_SND) {
      return std::nullopt;
    }
    CanPortEvent e;
    e.kind = CanPortEvent::Kind::kTxTimestamp;
    e.timestamp_ns = monotonic_stamp(stamps->ts[0]);
    e.tx_key = err->ee_data;
    return e;
  }

  HostResult<std::optional<CanPortEvent>> read_frame() {
    can_frame f{};
    iovec iov{&f, sizeof(f)};
    char control[512];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof(control);
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return std::nullopt;
    if (n < 0) {
      const int e = errno;
      if (e == ENETDOWN) return host_error(HostErrorKind::kIo, "can:" + name_, "the interface went down");
      return host_error(HostErrorKind::kIo, "can:" + name_, fmt::format("receive: {}", std::strerror(e)));
    }
    if (n != static_cast<ssize_t>(sizeof(f))) return std::nullopt;  // CAN FD frames are not ours
    CanPortEvent e;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SO_TIMESTAMPING) {
        e.timestamp_ns = monotonic_stamp(reinterpret_cast<const scm_timestamping*>(CMSG_DATA(c))->ts[0]);
      } else if (c->cmsg_type == SO_TIMESTAMPNS) {
        e.timestamp_ns = monotonic_stamp(*reinterpret_cast<const timespec*>(CMSG_DATA(c)));
      }
    }
    if (e.timestamp_ns == 0) e.timestamp_ns = monotonic_now_ns();
    if ((f.can_id & CAN_ERR_FLAG) != 0) {
      e.kind = CanPortEvent::Kind::kError;
      e.error_class = f.can_id & CAN_ERR_MASK;
      std::memcpy(e.error_data.data(), f.data, sizeof(f.data));
      return e;
    }
    // Standard and remote frames are not part of the protocol (SPEC.md §4).
    if ((f.can_id & CAN_EFF_FLAG) == 0 || (f.can_id & CAN_RTR_FLAG) != 0 || f.can_dlc > 8) return std::nullopt;
    e.kind = CanPortEvent::Kind::kFrame;
    e.own = (msg.msg_flags & MSG_CONFIRM) != 0;
    e.frame.id = f.can_id & CAN_EFF_MASK;
    e.frame.size = f.can_dlc;
    std::memcpy(e.frame.data, f.data, f.can_dlc);
    return e;
  }

  std::string name_;
  int fd_;
  uint32_t tx_key_ = 0;  // SOF_TIMESTAMPING_OPT_ID numbers this socket's sends from 0
};

}  // namespace

HostResult<std::unique_ptr<CanPort>> open_socketcan(const std::string& interface_name, const SocketCanOptions& options) {
  const std::string name = "can:" + interface_name;
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ) {
    return host_error(HostErrorKind::kBadInput, name, "not a network interface name");
  }
  const unsigned index = if_nametoindex(interface_name.c_str());
  if (index == 0) return host_error(HostErrorKind::kNotFound, name, "no such network interface");
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    return host_error(HostErrorKind::kOpenFailed, name, fmt::format("no raw CAN socket: {}", std::strerror(errno)));
  }
  auto port = std::make_unique<SocketCanPort>(interface_name, fd);
  auto fail = [&](const char* what) {
    return host_error(HostErrorKind::kOpenFailed, name, fmt::format("{}: {}", what, std::strerror(errno)));
  };

  std::vector<can_filter> filters;
  for (const protocol::CanFilter& f : options.filters) {
    filters.push_back(can_filter{(f.id & CAN_EFF_MASK) | CAN_EFF_FLAG, (f.mask & CAN_EFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
  }
  if (filters.empty()) filters.push_back(can_filter{CAN_EFF_FLAG, CAN_EFF_FLAG | CAN_RTR_FLAG});
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                 static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0) {
    return fail("CAN_RAW_FILTER");
  }
  const can_err_mask_t errors = options.error_frames ? CAN_ERR_MASK : 0;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors)) != 0) return fail("CAN_RAW_ERR_FILTER");
  const int own = options.receive_own ? 1 : 0;
  if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &own, sizeof(own)) != 0) return fail("CAN_RAW_RECV_OWN_MSGS");

  int stamping = SOF_TIMESTAMPING_RX_SOFTWARE | SOF_TIMESTAMPING_SOFTWARE;
  if (options.tx_timestamps) {
    stamping |= SOF_TIMESTAMPING_TX_SOFTWARE | SOF_TIMESTAMPING_OPT_ID | SOF_TIMESTAMPING_OPT_TSONLY;
  }
  if (setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPING, &stamping, sizeof(stamping)) != 0) {
    if (options.tx_timestamps) return fail("SO_TIMESTAMPING (transmit timestamps)");
    const int on = 1;
    if (setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on)) != 0) return fail("SO_TIMESTAMPNS");
  }

  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) return fail("bind");
  return std::unique_ptr<CanPort>(std::move(port));
}

std::string can_error_class_names(uint32_t error_class) {
  struct Name {
    uint32_t bit;
    const char* name;
  };
  static const Name kNames[] = {{CAN_ERR_TX_TIMEOUT, "tx timeout"}, {CAN_ERR_LOSTARB, "lost arbitration"},
                                {CAN_ERR_CRTL, "controller"},       {CAN_ERR_PROT, "protocol violation"},
                                {CAN_ERR_TRX, "transceiver"},       {CAN_ERR_ACK, "no acknowledgement"},
                                {CAN_ERR_BUSOFF, "bus-off"},        {CAN_ERR_BUSERROR, "bus error"},
                                {CAN_ERR_RESTARTED, "restarted"}};
  std::string out;
  for (const Name& n : kNames) {
    if ((error_class & n.bit) != 0) out += (out.empty() ? "" : ", ") + std::string(n.name);
  }
  return out.empty() ? "unspecified" : out;
}

}  // namespace tetrapulse::host

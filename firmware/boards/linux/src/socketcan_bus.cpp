// Raw SocketCAN (Documentation/networking/can.rst) with SO_TIMESTAMPNS receive stamps.
#include "tetrapulse/linux_board/socketcan_bus.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "tetrapulse/fw/app/board_state.hpp"
#include "tetrapulse/protocol/clock_bracket.hpp"

namespace tetrapulse::linux_board {

BoardResult<std::unique_ptr<SocketCanBus>> SocketCanBus::open(const std::string& interface_name,
                                                              const MonotonicClock& clock) {
  const std::string where = "CAN interface '" + interface_name + "'";
  const unsigned index = if_nametoindex(interface_name.c_str());
  if (index == 0) return board_error(BoardErrorKind::kCan, where, "no such interface");
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) {
    return board_error(BoardErrorKind::kCan, where, std::string("cannot open a raw CAN socket: ") + std::strerror(errno));
  }
  const int on = 1;
  const can_err_mask_t errors = CAN_ERR_MASK;
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on)) != 0 ||
      ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errors, sizeof(errors)) != 0 ||
      ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0) {
    const int e = errno;
    ::close(fd);
    return board_error(BoardErrorKind::kCan, where, std::strerror(e));
  }
  return std::unique_ptr<SocketCanBus>(new SocketCanBus(fd, interface_name, clock));
}

SocketCanBus::~SocketCanBus() { ::close(fd_); }

protocol::Status SocketCanBus::do_send(const protocol::CanFrame& frame) {
  can_frame f{};
  f.can_id = (frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG;
  f.can_dlc = frame.size;
  std::memcpy(f.data, frame.data, frame.size);
  // The core queues a whole transfer at once; a full socket queue drains within
  // milliseconds on a live bus, so wait for room briefly before answering busy.
  for (int attempt = 0; attempt < 20; ++attempt) {
    const ssize_t n = ::write(fd_, &f, sizeof(f));
    if (n == static_cast<ssize_t>(sizeof(f))) return {};
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == ENOBUFS || errno == EAGAIN)) {
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 5);
      continue;
    }
    break;
  }
  fw::bump(errors_);
  return protocol::Error::kBusy;
}

void SocketCanBus::do_set_filters(const protocol::CanNodeFilters& filters) {
  can_filter f[2] = {};
  const protocol::CanFilter* ours[2] = {&filters.addressed, &filters.broadcast};
  for (int i = 0; i < 2; ++i) {
    // CAN_EFF_FLAG in id and mask: standard and remote frames never match.
    f[i].can_id = (ours[i]->id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    f[i].can_mask = (ours[i]->mask & CAN_EFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
  }
  if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, f, sizeof(f)) != 0) fw::bump(errors_);
}

std::optional<ReceivedCanFrame> SocketCanBus::receive() {
  for (;;) {
    can_frame f{};
    iovec io{&f, sizeof(f)};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec))] = {};
    msghdr m{};
    m.msg_iov = &io;
    m.msg_iovlen = 1;
    m.msg_control = control;
    m.msg_controllen = sizeof(control);
    const ssize_t n = ::recvmsg(fd_, &m, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n != static_cast<ssize_t>(sizeof(f))) return std::nullopt;
    if ((f.can_id & CAN_ERR_FLAG) != 0) {
      fw::bump(errors_);
      if ((f.can_id & CAN_ERR_BUSOFF) != 0) bus_off_ = true;
      if ((f.can_id & CAN_ERR_RESTARTED) != 0) bus_off_ = false;
      continue;
    }
    if ((f.can_id & CAN_EFF_FLAG) == 0 || (f.can_id & CAN_RTR_FLAG) != 0 || f.can_dlc > CAN_MAX_DLEN) continue;
    int64_t monotonic = linux_board::monotonic_ns();
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c != nullptr; c = CMSG_NXTHDR(&m, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec t{};
        std::memcpy(&t, CMSG_DATA(c), sizeof(t));
        // On CLOCK_MONOTONIC through the current difference of the two clocks: a stamp is
        // converted microseconds after it was taken, so an NTP step in between is not worth a guard.
        const int64_t realtime = static_cast<int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
        monotonic = realtime - protocol::bracketed_clock_offset_ns(monotonic_ns, realtime_ns);
      }
    }
    ReceivedCanFrame r;
    r.frame.id = f.can_id & CAN_EFF_MASK;
    r.frame.size = f.can_dlc;
    std::memcpy(r.frame.data, f.data, f.can_dlc);
    r.rx = clock_.at(monotonic);
    return r;
  }
}

}  // namespace tetrapulse::linux_board

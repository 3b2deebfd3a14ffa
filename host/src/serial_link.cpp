#include "tetrapulse/host/serial_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {
namespace {

constexpr int kWriteTimeoutMs = 1000;

bool baud_constant(uint32_t baud, speed_t* out) {
  struct Rate {
    uint32_t baud;
    speed_t constant;
  };
  static const Rate kRates[] = {{1200, B1200},       {2400, B2400},       {4800, B4800},       {9600, B9600},
                                {19200, B19200},     {38400, B38400},     {57600, B57600},     {115200, B115200},
                                {230400, B230400},   {460800, B460800},   {500000, B500000},   {576000, B576000},
                                {921600, B921600},   {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000},
                                {2000000, B2000000}, {2500000, B2500000}, {3000000, B3000000}, {3500000, B3500000},
                                {4000000, B4000000}};
  for (const Rate& r : kRates) {
    if (r.baud == baud) {
      *out = r.constant;
      return true;
    }
  }
  return false;
}

}  // namespace

HostResult<std::unique_ptr<SerialLink>> SerialLink::open(const std::string& path, uint32_t baud) {
  const std::string name = "serial:" + path;
  speed_t speed = B0;
  if (!baud_constant(baud, &speed)) {
    return host_error(HostErrorKind::kBadInput, name, fmt::format("{} baud is not a standard rate", baud));
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int e = errno;
    return host_error(e == ENOENT ? HostErrorKind::kNotFound : HostErrorKind::kOpenFailed, name,
                      fmt::format("cannot open: {}", std::strerror(e)));
  }
  std::unique_ptr<SerialLink> link(new SerialLink(name, fd));
  termios tio{};
  if (tcgetattr(fd, &tio) != 0) {
    return host_error(HostErrorKind::kOpenFailed, name, fmt::format("not a serial port: {}", std::strerror(errno)));
  }
  // Raw bytes: no echo, no line editing, no CR/LF or XON/XOFF translation, 8N1, no flow control.
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS);
  tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0 || tcsetattr(fd, TCSANOW, &tio) != 0) {
    return host_error(HostErrorKind::kOpenFailed, name, fmt::format("cannot set {} baud raw mode: {}", baud,
                                                                     std::strerror(errno)));
  }
  ioctl(fd, TIOCEXCL);  // one program per port; a pseudo-terminal may not support it
  tcflush(fd, TCIOFLUSH);
  // A delimiter first ends whatever noise the line carried (SPEC.md §6.2).
  const uint8_t delimiter = protocol::kUartDelimiter;
  if (auto sent = link->write_all(&delimiter, 1); !sent) return tl::unexpected(sent.error());
  return link;
}

SerialLink::~SerialLink() { ::close(fd_); }

HostResult<void> SerialLink::write_all(const uint8_t* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n > 0) {
      data += n;
      size -= static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, kWriteTimeoutMs) == 0) {
        return host_error(HostErrorKind::kTimeout, name(), "write: the line takes no data (flow stopped?)");
      }
      continue;
    }
    return host_error(HostErrorKind::kIo, name(), fmt::format("write: {}", std::strerror(errno)));
  }
  return {};
}

HostResult<void> SerialLink::send_bytes(protocol::ByteView message) {
  uint8_t frame[protocol::kUartMaxFrameSize];
  const protocol::Result<size_t> size = protocol::encode_uart_frame(message, frame, sizeof(frame));
  if (!size) {
    return host_error(HostErrorKind::kBadInput, name(),
                      fmt::format("cannot frame a {}-byte message: {}", message.size, protocol::error_name(size.error())),
                      size.error());
  }
  return write_all(frame, *size);
}

HostResult<std::optional<RawMessage>> SerialLink::receive_bytes(int64_t timeout_ns) {
  const int64_t deadline = monotonic_now_ns() + timeout_ns;
  for (;;) {
    // What was read before goes through the decoder first.
    while (unread_at_ < unread_.size()) {
      size_t used = 0;
      const protocol::ByteView rest{unread_.data() + unread_at_, unread_.size() - unread_at_};
      const protocol::ReceiveEvent event = decoder_.feed(rest, &used);
      unread_at_ += used;
      if (event.kind == protocol::ReceiveKind::kMessage) {
        return RawMessage{std::vector<uint8_t>(event.message.begin(), event.message.end()), monotonic_now_ns(), 0};
      }
      if (event.kind == protocol::ReceiveKind::kError) ++counters_.transport_errors;
    }
    const int64_t left = deadline - monotonic_now_ns();
    if (left <= 0) return std::nullopt;
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>((left + 999'999) / 1'000'000));
    if (ready < 0 && errno != EINTR) {
      return host_error(HostErrorKind::kIo, name(), fmt::format("poll: {}", std::strerror(errno)));
    }
    if (ready <= 0) continue;
    if ((p.revents & (POLLERR | POLLNVAL)) != 0 || ((p.revents & POLLHUP) != 0 && (p.revents & POLLIN) == 0)) {
      return host_error(HostErrorKind::kDisconnected, name(), "the serial line hung up");
    }
    uint8_t buffer[512];
    const ssize_t n = ::read(fd_, buffer, sizeof(buffer));
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
    if (n < 0) return host_error(HostErrorKind::kIo, name(), fmt::format("read: {}", std::strerror(errno)));
    if (n == 0) continue;
    unread_.assign(buffer, buffer + n);
    unread_at_ = 0;
  }
}

}  // namespace tetrapulse::host

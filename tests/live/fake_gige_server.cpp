// GVCP/GVSP transport over ArvFakeCamera's register map (fake_gige_server.hpp).
// Layouts as the GigE Vision standard gives them: every field big-endian; GVCP
// command header {0x42, flags, command, length, req_id}, acknowledge header {status,
// answer, length, ack_id}; GVSP header {status, block_id, content type << 24 |
// packet_id} (16-bit block ids, 24-bit packet ids: extended ids are not offered).
#include "fake_gige_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <deque>
#include <random>
#include <vector>

namespace tetrapulse::live_test {
namespace {

// Bootstrap registers (GigE Vision 2.x, table "bootstrap registers").
constexpr uint32_t kGvcpCapability = 0x0934, kHeartbeatTimeout = 0x0938, kControlPrivilege = 0x0a00;
constexpr uint32_t kStreamPort = 0x0d00, kStreamAddress = 0x0d18;  // packet size (0x0d04): ArvFakeCamera reads it
constexpr uint32_t kCapabilityWriteMemory = 1u << 1, kCapabilityPacketResend = 1u << 2;
constexpr uint16_t kDiscoveryCmd = 0x0002, kResendCmd = 0x0040, kReadRegCmd = 0x0080, kWriteRegCmd = 0x0082,
                   kReadMemCmd = 0x0084, kWriteMemCmd = 0x0086;
constexpr uint16_t kStatusInvalidParameter = 0x8002, kStatusInvalidAddress = 0x8003, kStatusNotImplemented = 0x8001;
constexpr uint16_t kGvspPacketUnavailable = 0x800c;
constexpr uint8_t kLeader = 1, kTrailer = 2, kPayload = 3;
constexpr size_t kIpUdpGvspOverhead = 20 + 8 + 8;
constexpr uint16_t kPayloadTypeImage = 0x0001;

uint16_t be16(const uint8_t* p) { return static_cast<uint16_t>(p[0] << 8 | p[1]); }
uint32_t be32(const uint8_t* p) { return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3]; }
void put16(std::vector<uint8_t>* v, uint16_t x) {
  v->push_back(static_cast<uint8_t>(x >> 8));
  v->push_back(static_cast<uint8_t>(x));
}
void put32(std::vector<uint8_t>* v, uint32_t x) {
  put16(v, static_cast<uint16_t>(x >> 16));
  put16(v, static_cast<uint16_t>(x));
}

int64_t now_us() { return g_get_real_time(); }

struct SentFrame {
  uint16_t block_id = 0;
  uint64_t timestamp = 0;  // ticks (the fake camera's tick is 1 ns)
  uint32_t pixel_format = 0, width = 0, height = 0, x = 0, y = 0;
  size_t block_size = 0;   // image bytes per payload packet
  std::vector<uint8_t> data;
  uint32_t payload_packets() const { return static_cast<uint32_t>((data.size() + block_size - 1) / block_size); }
};

class Server {
 public:
  Server(ArvFakeCamera* camera, const FakeGigeOptions& o, FakeGigeCounters* c)
      : camera_(camera), o_(o), c_(c), random_(o.seed) {}
  ~Server() {
    if (gvcp_ >= 0) close(gvcp_);
    if (gvsp_ >= 0) close(gvsp_);
    if (buffer_) g_object_unref(buffer_);
  }

  std::optional<std::string> listen() {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(3956);
    if (inet_pton(AF_INET, o_.address.c_str(), &a.sin_addr) != 1) return o_.address + ": not an IPv4 address";
    gvcp_ = socket(AF_INET, SOCK_DGRAM, 0);
    gvsp_ = socket(AF_INET, SOCK_DGRAM, 0);
    if (gvcp_ < 0 || gvsp_ < 0 || bind(gvcp_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      return o_.address + ":3956: cannot listen: " + std::strerror(errno);
    }
    // Big enough for a whole frame burst, so that the host's own socket, not this
    // one, is where a slow reader loses packets.
    const int size = 8 << 20;
    setsockopt(gvsp_, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);
    uint32_t capability = 0;
    arv_fake_camera_read_register(camera_, kGvcpCapability, &capability);
    capability |= kCapabilityWriteMemory;
    if (o_.resend) capability |= kCapabilityPacketResend;
    else capability &= ~kCapabilityPacketResend;
    arv_fake_camera_write_register(camera_, kGvcpCapability, capability);
    return std::nullopt;
  }

  void run(int seconds, const std::atomic<bool>& stop) {
    const int64_t end = now_us() + int64_t{seconds} * 1'000'000;
    guint64 next_frame = 0;
    int64_t last_command = now_us();
    while (!stop && now_us() < end) {
      const bool streaming = reg(kControlPrivilege) != 0 && arv_fake_camera_get_acquisition_status(camera_) != 0;
      if (!streaming) next_frame = 0;
      else if (next_frame == 0) arv_fake_camera_get_sleep_time_for_next_frame(camera_, &next_frame);
      int timeout_ms = 100;
      if (streaming) timeout_ms = static_cast<int>(std::clamp<int64_t>((static_cast<int64_t>(next_frame) - now_us()) / 1000, 0, 100));
      pollfd p{gvcp_, POLLIN, 0};
      if (poll(&p, 1, timeout_ms) > 0) {
        uint8_t in[1500];
        sockaddr_in from{};
        socklen_t len = sizeof from;
        ssize_t n;
        while ((n = recvfrom(gvcp_, in, sizeof in, MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len)) > 0) {
          last_command = now_us();
          handle(in, static_cast<size_t>(n), from);
          len = sizeof from;
        }
      }
      // A host gone without releasing control: the heartbeat lapses, control ends.
      if (reg(kControlPrivilege) != 0 && now_us() - last_command > int64_t{reg(kHeartbeatTimeout)} * 1000) {
        arv_fake_camera_write_register(camera_, kControlPrivilege, 0);
      }
      if (streaming && next_frame != 0 && now_us() >= static_cast<int64_t>(next_frame)) {
        send_frame();
        next_frame = 0;
      }
    }
  }

 private:
  uint32_t reg(uint32_t address) {
    uint32_t v = 0;
    arv_fake_camera_read_register(camera_, address, &v);
    return v;
  }

  void reply(const sockaddr_in& to, uint16_t status, uint16_t answer, uint16_t id, const std::vector<uint8_t>& body) {
    std::vector<uint8_t> out;
    put16(&out, status);
    put16(&out, answer);
    put16(&out, static_cast<uint16_t>(body.size()));
    put16(&out, id);
    out.insert(out.end(), body.begin(), body.end());
    sendto(gvcp_, out.data(), out.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }

  void handle(const uint8_t* p, size_t n, const sockaddr_in& from) {
    if (n < 8 || p[0] != 0x42) return;
    const uint16_t command = be16(p + 2), length = be16(p + 4), id = be16(p + 6);
    if (8u + length > n) return;
    const uint8_t* d = p + 8;
    const auto answer = static_cast<uint16_t>(command + 1);
    std::vector<uint8_t> body;
    switch (command) {
      case kReadRegCmd:
        for (size_t i = 0; i + 4 <= length; i += 4) {
          uint32_t v = 0;
          if (!arv_fake_camera_read_register(camera_, be32(d + i), &v)) return reply(from, kStatusInvalidAddress, answer, id, {});
          put32(&body, v);
        }
        return reply(from, 0, answer, id, body);
      case kWriteRegCmd: {
        uint16_t written = 0;
        for (size_t i = 0; i + 8 <= length; i += 8, ++written) {
          if (!arv_fake_camera_write_register(camera_, be32(d + i), be32(d + i + 4))) break;
        }
        put16(&body, 0);
        put16(&body, written);
        return reply(from, written * 8u == length ? 0 : kStatusInvalidAddress, answer, id, body);
      }
      case kReadMemCmd: {
        if (length < 8) return reply(from, kStatusInvalidParameter, answer, id, {});
        const uint32_t address = be32(d), count = be16(d + 6);
        if (count > 536) return reply(from, kStatusInvalidParameter, answer, id, {});
        put32(&body, address);
        body.resize(4 + count);
        if (!arv_fake_camera_read_memory(camera_, address, count, body.data() + 4)) {
          return reply(from, kStatusInvalidAddress, answer, id, {});
        }
        return reply(from, 0, answer, id, body);
      }
      case kWriteMemCmd: {
        if (length < 4) return reply(from, kStatusInvalidParameter, answer, id, {});
        const uint32_t address = be32(d);
        if (!arv_fake_camera_write_memory(camera_, address, length - 4u, d + 4)) {
          return reply(from, kStatusInvalidAddress, answer, id, {});
        }
        put16(&body, 0);
        put16(&body, static_cast<uint16_t>(length - 4u));
        return reply(from, 0, answer, id, body);
      }
      case kResendCmd:
        // No acknowledge: the answer is the packets, on the stream channel.
        if (o_.resend && length >= 12) resend(static_cast<uint16_t>(be32(d)), be32(d + 4) & 0xffffff, be32(d + 8) & 0xffffff);
        return;
      case kDiscoveryCmd:
        return;  // opened by address only; nothing here answers a broadcast
      default:
        return reply(from, kStatusNotImplemented, answer, id, {});
    }
  }

  sockaddr_in stream_destination() {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    arv_fake_camera_read_memory(camera_, kStreamAddress, 4, &to.sin_addr.s_addr);  // stored in network order
    to.sin_port = htons(static_cast<uint16_t>(reg(kStreamPort) & 0xffff));
    return to;
  }

  // One packet of `f`: 0 the leader, 1..N payload, N+1 the trailer.
  std::vector<uint8_t> packet(const SentFrame& f, uint32_t packet_id) {
    std::vector<uint8_t> out;
    const uint32_t n = f.payload_packets();
    const uint8_t content = packet_id == 0 ? kLeader : packet_id <= n ? kPayload : kTrailer;
    put16(&out, 0);
    put16(&out, f.block_id);
    put32(&out, uint32_t{content} << 24 | (packet_id & 0xffffff));
    if (content == kLeader) {
      put16(&out, 0);
      put16(&out, kPayloadTypeImage);
      put32(&out, static_cast<uint32_t>(f.timestamp >> 32));
      put32(&out, static_cast<uint32_t>(f.timestamp));
      for (uint32_t v : {f.pixel_format, f.width, f.height, f.x, f.y}) put32(&out, v);
      put16(&out, 0);
      put16(&out, 0);
    } else if (content == kPayload) {
      const size_t begin = (packet_id - 1) * f.block_size;
      const size_t end = std::min(f.data.size(), begin + f.block_size);
      out.insert(out.end(), f.data.begin() + static_cast<std::ptrdiff_t>(begin), f.data.begin() + static_cast<std::ptrdiff_t>(end));
    } else {
      put32(&out, kPayloadTypeImage);
      put32(&out, f.height);
    }
    return out;
  }

  // Sent unless the loss draw takes it.
  bool lossy_send(const std::vector<uint8_t>& bytes, const sockaddr_in& to) {
    if (o_.lost_ratio > 0 && uniform_(random_) < o_.lost_ratio) return false;
    sendto(gvsp_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    return true;
  }

  void send_frame() {
    const size_t payload = arv_fake_camera_get_payload(camera_);
    if (!buffer_ || buffer_size_ != payload) {
      if (buffer_) g_object_unref(buffer_);
      buffer_ = arv_buffer_new(payload, nullptr);
      buffer_size_ = payload;
    }
    guint32 packet_size = 0;
    arv_fake_camera_fill_buffer(camera_, buffer_, &packet_size);
    if (packet_size <= kIpUdpGvspOverhead) return;
    size_t unused = 0;
    const auto* pixels = static_cast<const uint8_t*>(arv_buffer_get_data(buffer_, &unused));
    SentFrame f;
    f.block_id = static_cast<uint16_t>(arv_buffer_get_frame_id(buffer_));
    f.timestamp = arv_buffer_get_timestamp(buffer_);
    f.pixel_format = arv_buffer_get_image_pixel_format(buffer_);
    gint x = 0, y = 0, w = 0, h = 0;
    arv_buffer_get_image_region(buffer_, &x, &y, &w, &h);
    f.x = static_cast<uint32_t>(x), f.y = static_cast<uint32_t>(y), f.width = static_cast<uint32_t>(w), f.height = static_cast<uint32_t>(h);
    f.block_size = packet_size - kIpUdpGvspOverhead;
    f.data.assign(pixels, pixels + payload);
    const sockaddr_in to = stream_destination();
    const uint32_t last = f.payload_packets() + 1;
    for (uint32_t id = 0; id <= last; ++id) {
      if (lossy_send(packet(f, id), to)) ++c_->packets_sent;
      else ++c_->packets_lost;
    }
    ++c_->frames_sent;
    sent_.push_back(std::move(f));
    while (sent_.size() > static_cast<size_t>(std::max(o_.retained_frames, 1))) sent_.pop_front();
  }

  void resend(uint16_t block_id, uint32_t first, uint32_t last) {
    ++c_->resend_requests;
    const sockaddr_in to = stream_destination();
    auto f = std::find_if(sent_.begin(), sent_.end(), [&](const SentFrame& s) { return s.block_id == block_id; });
    const uint32_t count = last >= first ? last - first + 1 : 0;
    c_->packets_requested += count;
    if (f == sent_.end() || last > f->payload_packets() + 1) {
      // Gone (or never there): say so, so that the host stops asking for this frame.
      ++c_->packets_unavailable;
      std::vector<uint8_t> out;
      put16(&out, kGvspPacketUnavailable);
      put16(&out, block_id);
      put32(&out, uint32_t{kPayload} << 24 | (first & 0xffffff));
      sendto(gvsp_, out.data(), out.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
      return;
    }
    for (uint32_t id = first; id <= last; ++id) {
      if (lossy_send(packet(*f, id), to)) ++c_->packets_resent;
      else ++c_->resent_lost;
    }
  }

  ArvFakeCamera* camera_;
  FakeGigeOptions o_;
  FakeGigeCounters* c_;
  std::mt19937 random_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  int gvcp_ = -1, gvsp_ = -1;
  ArvBuffer* buffer_ = nullptr;
  size_t buffer_size_ = 0;
  std::deque<SentFrame> sent_;
};

}  // namespace

std::optional<std::string> serve_fake_gige(ArvFakeCamera* camera, const FakeGigeOptions& options, int seconds,
                                           const std::atomic<bool>& stop, FakeGigeCounters* counters) {
  Server server(camera, options, counters);
  if (auto e = server.listen()) return e;
  server.run(seconds, stop);
  return std::nullopt;
}

}  // namespace tetrapulse::live_test

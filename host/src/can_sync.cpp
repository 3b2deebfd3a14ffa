#include "tetrapulse/host/can_sync.hpp"

#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "tetrapulse/host/can_link.hpp"
#include "tetrapulse/protocol/message.hpp"
#include "tetrapulse/protocol/timebase.hpp"

namespace tetrapulse::host {

const char* tx_stamp_source_name(TxStampSource source) {
  switch (source) {
    case TxStampSource::kKernelTransmit: return "kernel-tx";
    case TxStampSource::kOwnEcho: return "own-echo";
    case TxStampSource::kSendCall: return "send-call";
  }
  return "unknown";
}

HostResult<std::unique_ptr<CanSync>> CanSync::open(const std::string& interface_name, RigClock clock,
                                                   CanSyncOptions options) {
  SocketCanOptions o;
  // Only our own Syncs come back (as echoes); nothing else is read.
  o.filters = {protocol::CanFilter{0x00400000u | (protocol::kCanBroadcastNode << 8), 0x1FFFFFFFu}};
  o.error_frames = false;
  o.tx_timestamps = true;
  o.receive_own = true;
  auto port = open_socketcan(interface_name, o);
  if (!port) return tl::unexpected(port.error());
  return std::make_unique<CanSync>(std::move(*port), clock, options);
}

CanSync::CanSync(std::unique_ptr<CanPort> port, RigClock clock, CanSyncOptions options)
    : port_(std::move(port)), name_("can:" + port_->interface_name()), clock_(clock), options_(options) {}

HostResult<void> CanSync::send_message(const protocol::Message& m, uint32_t* first_key, protocol::CanFrame* first_frame) {
  uint8_t bytes[protocol::kMaxMessageSize];
  protocol::ByteWriter w(bytes, sizeof(bytes));
  if (!protocol::encode(m, w)) return host_error(HostErrorKind::kBadInput, name_, "cannot encode a time-sync message");
  HostError failure;
  bool first = true;
  const protocol::Status sent = sender_.send(protocol::kCanPrioritySync, protocol::kCanBroadcastNode, w.view(),
                                             [&](const protocol::CanFrame& frame) {
                                               auto key = port_->send(frame);
                                               if (!key) {
                                                 failure = key.error();
                                                 return protocol::Status{protocol::Error::kBusy};
                                               }
                                               if (first && first_key != nullptr) {
                                                 *first_key = *key;
                                                 *first_frame = frame;
                                               }
                                               first = false;
                                               return protocol::Status{};
                                             });
  if (!sent) return tl::unexpected(failure.message.empty() ? HostError{HostErrorKind::kIo, name_, "send failed"} : failure);
  return {};
}

HostResult<CanSyncSample> CanSync::send_one() {
  CanSyncSample sample;
  sample.sync_seq = seq_++;
  uint32_t key = 0;
  protocol::CanFrame frame;
  const int64_t before = monotonic_now_ns();
  if (auto sent = send_message(protocol::Message{0, protocol::Sync{sample.sync_seq}}, &key, &frame); !sent) {
    return tl::unexpected(sent.error());
  }
  const int64_t after_send = monotonic_now_ns();
  // Wait for the kernel's word on when it left.
  int64_t echo_ns = 0;
  int64_t tx_ns = 0;
  const int64_t deadline = after_send + std::chrono::nanoseconds(options_.stamp_wait).count();
  while (tx_ns == 0) {
    const int64_t left = deadline - monotonic_now_ns();
    if (left <= 0 || (!kernel_tx_stamps_ && echo_ns != 0)) break;
    auto event = port_->next(left);
    if (!event) return tl::unexpected(event.error());
    if (!event->has_value()) break;
    const CanPortEvent& e = **event;
    if (e.kind == CanPortEvent::Kind::kTxTimestamp && e.tx_key == key && e.timestamp_ns != 0) {
      tx_ns = e.timestamp_ns;
    } else if (e.kind == CanPortEvent::Kind::kFrame && e.own && e.frame.id == frame.id && e.frame.size == frame.size &&
               std::equal(frame.data, frame.data + frame.size, e.frame.data)) {
      echo_ns = e.timestamp_ns;
    }
  }
  if (tx_ns != 0) {
    sample.source = TxStampSource::kKernelTransmit;
  } else {
    kernel_tx_stamps_ = false;
    if (echo_ns != 0) {
      tx_ns = echo_ns;
      sample.source = TxStampSource::kOwnEcho;
    } else {
      tx_ns = before + (after_send - before) / 2;
      sample.source = TxStampSource::kSendCall;
    }
  }
  sample.tx_time_ns = clock_.from_monotonic(tx_ns);
  if (auto sent = send_message(protocol::Message{0, protocol::FollowUp{sample.sync_seq, sample.tx_time_ns}}, nullptr,
                               nullptr);
      !sent) {
    return tl::unexpected(sent.error());
  }
  return sample;
}

HostResult<uint64_t> CanSync::run(const std::atomic<bool>& stop, uint64_t max_count,
                                  const std::function<void(const CanSyncSample&)>& on_sample) {
  const int64_t period = options_.period_ns;
  if (period <= 0) return host_error(HostErrorKind::kBadInput, name_, "the sync period must be positive");
  const int64_t start = (protocol::floor_div(clock_.now(), period) + 1) * period;
  uint64_t sent = 0;
  for (int64_t k = 0; !stop.load() && (max_count == 0 || sent < max_count); ++k) {
    const int64_t due = clock_.to_monotonic(start + k * period);
    while (!stop.load() && monotonic_now_ns() < due) {
      const int64_t until = std::min(due, monotonic_now_ns() + 100'000'000);
      const timespec t{static_cast<time_t>(until / 1'000'000'000), static_cast<long>(until % 1'000'000'000)};
      while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, nullptr) == EINTR) {
      }
    }
    if (stop.load()) break;
    auto sample = send_one();
    if (!sample) return tl::unexpected(sample.error());
    on_sample(*sample);
    ++sent;
  }
  return sent;
}

}  // namespace tetrapulse::host

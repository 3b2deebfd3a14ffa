#include "fake_can_bus.hpp"

#include <algorithm>
#include <thread>

#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host::testing {

class FakeCanBus::Port final : public CanPort {
 public:
  Port(FakeCanBus* bus, SocketCanOptions options) : bus_(bus), options_(std::move(options)) {
    bus_->ports_.push_back(this);
  }
  ~Port() override { bus_->ports_.erase(std::find(bus_->ports_.begin(), bus_->ports_.end(), this)); }

  bool accepts(const protocol::CanFrame& frame) const {
    if (options_.filters.empty()) return true;
    return std::any_of(options_.filters.begin(), options_.filters.end(),
                       [&](const protocol::CanFilter& f) { return protocol::can_filter_matches(f, frame.id); });
  }
  void push(CanPortEvent e) { events_.push_back(e); }
  const SocketCanOptions& options() const { return options_; }

 private:
  const std::string& do_interface_name() const override { return bus_->name_; }

  HostResult<uint32_t> do_send(const protocol::CanFrame& frame) override {
    const uint32_t key = key_++;
    bus_->transmit(this, frame);
    if (options_.tx_timestamps) {
      CanPortEvent e;
      e.kind = CanPortEvent::Kind::kTxTimestamp;
      e.timestamp_ns = monotonic_now_ns();
      e.tx_key = key;
      events_.push_back(e);
    }
    return key;
  }

  HostResult<std::optional<CanPortEvent>> do_next(int64_t timeout_ns) override {
    if (events_.empty()) {
      // Nothing can arrive while a single-threaded test waits: wait out the timeout.
      std::this_thread::sleep_for(std::chrono::nanoseconds(timeout_ns));
      return std::nullopt;
    }
    CanPortEvent e = events_.front();
    events_.pop_front();
    return e;
  }

  FakeCanBus* bus_;
  SocketCanOptions options_;
  std::deque<CanPortEvent> events_;
  uint32_t key_ = 0;
};

std::unique_ptr<CanPort> FakeCanBus::open(const SocketCanOptions& options) {
  return std::make_unique<Port>(this, options);
}

void FakeCanBus::deliver(Port* from, const protocol::CanFrame& frame, int64_t now_ns) {
  log_.push_back(frame);
  for (Port* p : ports_) {
    const bool own = p == from;
    if ((own && !p->options().receive_own) || !p->accepts(frame)) continue;
    CanPortEvent e;
    e.frame = frame;
    e.timestamp_ns = now_ns;
    e.own = own;
    p->push(e);
  }
}

void FakeCanBus::transmit(Port* from, const protocol::CanFrame& frame) {
  const int64_t now = monotonic_now_ns();
  deliver(from, frame, now);
  if (lose_ && lose_(frame)) return;
  for (Node& node : nodes_) {
    for (const protocol::CanFrame& answer : node(frame, now)) deliver(nullptr, answer, monotonic_now_ns());
  }
}

void FakeCanBus::raise_error(uint32_t error_class, const std::array<uint8_t, 8>& data) {
  for (Port* p : ports_) {
    if (!p->options().error_frames) continue;
    CanPortEvent e;
    e.kind = CanPortEvent::Kind::kError;
    e.error_class = error_class;
    e.error_data = data;
    e.timestamp_ns = monotonic_now_ns();
    p->push(e);
  }
}

}  // namespace tetrapulse::host::testing

// Generators of message_generators.hpp. Written with gen::exec (values drawn
// inside one function) rather than gen::build / gen::set, whose lens machinery
// took minutes to compile; drawing shrinks as well.
#include "message_generators.hpp"

namespace tetrapulse::protocol::testing {
namespace {

template <size_t... I>
rc::Gen<Body> body_gen(std::index_sequence<I...>) {
  return rc::gen::oneOf(rc::gen::cast<Body>(rc::gen::arbitrary<std::variant_alternative_t<I, Body>>())...);
}

template <size_t I = 0>
rc::Gen<Body> body_of_type_from(MessageType t) {
  using T = std::variant_alternative_t<I, Body>;
  if constexpr (I + 1 < std::variant_size_v<Body>) {
    if (T::kType != t) return body_of_type_from<I + 1>(t);
  }
  return rc::gen::cast<Body>(rc::gen::arbitrary<T>());
}

}  // namespace

rc::Gen<Body> body_of_type(MessageType t) { return body_of_type_from(t); }
rc::Gen<Body> any_body() { return body_gen(std::make_index_sequence<std::variant_size_v<Body>>()); }

}  // namespace tetrapulse::protocol::testing

namespace rc {

namespace detail_tp {
namespace {
template <class T>
T any() {
  return *gen::arbitrary<T>();
}
template <class E>
E up_to(E last) {
  return *tp::testing::enum_up_to(last);
}
}  // namespace
}  // namespace detail_tp

Gen<tp::Code> Arbitrary<tp::Code>::arbitrary() {
  return gen::exec([] {
    tp::Code c;
    const int length = *gen::inRange<int>(0, tp::kMaxCodeLength + 1);
    const uint64_t bits = detail_tp::any<uint64_t>();
    c.length = static_cast<uint8_t>(length);
    c.bits = length == 64 ? bits : bits & ((uint64_t{1} << length) - 1);
    return c;
  });
}

Gen<tp::Config> Arbitrary<tp::Config>::arbitrary() {
  return gen::exec([] {
    using detail_tp::any;
    using detail_tp::up_to;
    tp::Config c;
    c.node_id = *tp::testing::node_id_gen();
    c.target_id = any<uint16_t>();
    for (tp::Code& code : c.codes) code = any<tp::Code>();
    c.modulation = up_to(tp::Modulation::kConstant);
    c.low_level = any<uint16_t>();
    c.bit_period_ns = *gen::inRange<uint32_t>(tp::kMinBitPeriodNs, UINT32_MAX);
    c.epoch_ns = any<int64_t>();
    c.brightness = any<uint16_t>();
    c.current_limit_ma = any<uint16_t>();
    c.sync_source = up_to(tp::SyncSource::kCan);
    c.gpio_edge = up_to(tp::GpioEdge::kFalling);
    c.gpio_edge_period_ns = *gen::inRange<uint32_t>(tp::kMinGpioEdgePeriodNs, UINT32_MAX);
    c.gpio_edge_epoch_ns = any<int64_t>();
    c.gpio_edge_numbering = up_to(tp::GpioEdgeNumbering::kCountAfterGap);
    return c;
  });
}

Gen<tp::SetConfig> Arbitrary<tp::SetConfig>::arbitrary() {
  return gen::exec([] { return tp::SetConfig{detail_tp::any<tp::Config>()}; });
}

Gen<tp::Identify> Arbitrary<tp::Identify>::arbitrary() {
  return gen::exec([] {
    tp::Identify m;
    m.pattern = detail_tp::up_to(tp::IdentifyPattern::kCountIndex);
    m.duration_ms = detail_tp::any<decltype(m.duration_ms)>();
    return m;
  });
}

Gen<tp::Reboot> Arbitrary<tp::Reboot>::arbitrary() {
  return gen::exec([] {
    tp::Reboot m;
    m.mode = detail_tp::up_to(tp::RebootMode::kBootloader);
    return m;
  });
}

Gen<tp::UpdateBegin> Arbitrary<tp::UpdateBegin>::arbitrary() {
  return gen::exec([] {
    tp::UpdateBegin m;
    m.image_size = *gen::inRange<uint32_t>(64, UINT32_MAX);
    m.version = detail_tp::any<decltype(m.version)>();
    m.crc32c = detail_tp::any<decltype(m.crc32c)>();
    return m;
  });
}

Gen<tp::UpdateChunk> Arbitrary<tp::UpdateChunk>::arbitrary() {
  return gen::exec([] {
    tp::UpdateChunk m;
    m.offset = detail_tp::any<uint32_t>();
    const int length = *gen::inRange<int>(1, tp::kMaxUpdateChunk + 1);
    m.length = static_cast<uint16_t>(length);
    const auto data = *gen::container<std::vector<uint8_t>>(static_cast<size_t>(length), gen::arbitrary<uint8_t>());
    for (int i = 0; i < length; ++i) m.data[i] = data[static_cast<size_t>(i)];
    return m;
  });
}

Gen<tp::GetLedLog> Arbitrary<tp::GetLedLog>::arbitrary() {
  return gen::exec([] {
    tp::GetLedLog m;
    m.first = detail_tp::any<decltype(m.first)>();
    return m;
  });
}

Gen<tp::Sync> Arbitrary<tp::Sync>::arbitrary() {
  return gen::exec([] {
    tp::Sync m;
    m.sync_seq = detail_tp::any<decltype(m.sync_seq)>();
    return m;
  });
}

Gen<tp::FollowUp> Arbitrary<tp::FollowUp>::arbitrary() {
  return gen::exec([] {
    tp::FollowUp m;
    m.sync_seq = detail_tp::any<decltype(m.sync_seq)>();
    m.tx_time_ns = detail_tp::any<decltype(m.tx_time_ns)>();
    return m;
  });
}

Gen<tp::Ack> Arbitrary<tp::Ack>::arbitrary() {
  return gen::exec([] {
    using T = tp::MessageType;
    tp::Ack m;
    m.request_type = *gen::element(T::kGetInfo, T::kGetConfig, T::kSetConfig, T::kGetStatus, T::kIdentify,
                                   T::kPersistConfig, T::kFactoryReset, T::kReboot, T::kUpdateBegin,
                                   T::kUpdateChunk, T::kUpdateVerify, T::kUpdateAbort, T::kGetLedLog);
    m.value = detail_tp::any<decltype(m.value)>();
    return m;
  });
}

Gen<tp::Info> Arbitrary<tp::Info>::arbitrary() {
  return gen::exec([] {
    using detail_tp::any;
    tp::Info m;
    m.protocol_version = any<decltype(m.protocol_version)>();
    m.hw_model = *gen::element(tp::HwModel::kStm32f405Reference, tp::HwModel::kLinuxBoard,
                               tp::HwModel::kSimulatedBoard);
    m.hw_revision = any<decltype(m.hw_revision)>();
    m.fw_version = any<decltype(m.fw_version)>();
    m.bootloader_version = any<decltype(m.bootloader_version)>();
    m.serial = any<decltype(m.serial)>();
    m.uptime_ms = any<decltype(m.uptime_ms)>();
    m.capabilities = any<decltype(m.capabilities)>();
    m.node_id = *tp::testing::node_id_gen();
    m.active_slot = any<decltype(m.active_slot)>();
    m.max_code_length = *gen::inRange<uint8_t>(1, tp::kMaxCodeLength + 1);
    return m;
  });
}

Gen<tp::ConfigReport> Arbitrary<tp::ConfigReport>::arbitrary() {
  return gen::exec([] { return tp::ConfigReport{detail_tp::any<tp::Config>()}; });
}

Gen<tp::StatusReport> Arbitrary<tp::StatusReport>::arbitrary() {
  return gen::exec([] {
    using detail_tp::any;
    using detail_tp::up_to;
    tp::StatusReport m;
    m.sync_state = up_to(tp::SyncState::kHoldover);
    m.sync_source = up_to(tp::SyncSource::kCan);
    m.offset_ns = any<decltype(m.offset_ns)>();
    m.rate_ppb = any<decltype(m.rate_ppb)>();
    m.holdover_ms = any<decltype(m.holdover_ms)>();
    m.sync_accepted = any<decltype(m.sync_accepted)>();
    m.sync_rejected = any<decltype(m.sync_rejected)>();
    m.rx_malformed = any<decltype(m.rx_malformed)>();
    m.can_errors = any<decltype(m.can_errors)>();
    m.can_bus_off = *gen::inRange<uint8_t>(0, 2);
    m.flash_errors = any<decltype(m.flash_errors)>();
    m.watchdog_resets = any<decltype(m.watchdog_resets)>();
    // Any byte: a receiver must carry error codes it does not know.
    m.last_error = static_cast<tp::Error>(any<uint8_t>());
    m.update_state = up_to(tp::UpdateState::kFailed);
    m.uptime_ms = any<decltype(m.uptime_ms)>();
    return m;
  });
}

Gen<tp::LedLogEntry> Arbitrary<tp::LedLogEntry>::arbitrary() {
  return gen::exec([] {
    using detail_tp::any;
    tp::LedLogEntry m;
    m.seq = any<decltype(m.seq)>();
    m.rig_time_ns = any<decltype(m.rig_time_ns)>();
    m.marker = *gen::inRange<uint8_t>(0, tp::kMarkersPerTarget);
    m.duty = any<decltype(m.duty)>();
    return m;
  });
}

Gen<tp::LedLog> Arbitrary<tp::LedLog>::arbitrary() {
  return gen::exec([] {
    tp::LedLog m;
    m.next = detail_tp::any<uint32_t>();
    const int count = *gen::inRange<int>(0, tp::kMaxLedLogEntries + 1);
    m.count = static_cast<uint8_t>(count);
    for (int i = 0; i < count; ++i) m.entries[i] = detail_tp::any<tp::LedLogEntry>();
    return m;
  });
}

Gen<tp::ErrorResponse> Arbitrary<tp::ErrorResponse>::arbitrary() {
  return gen::exec([] {
    tp::ErrorResponse m;
    m.request_type = static_cast<tp::MessageType>(detail_tp::any<uint8_t>());
    m.error = static_cast<tp::Error>(*gen::inRange<int>(1, 256));
    m.detail = detail_tp::any<decltype(m.detail)>();
    return m;
  });
}

Gen<tp::Message> Arbitrary<tp::Message>::arbitrary() {
  return gen::exec([] {
    tp::Message m;
    m.seq = detail_tp::any<decltype(m.seq)>();
    m.body = *tp::testing::any_body();
    return m;
  });
}

}  // namespace rc

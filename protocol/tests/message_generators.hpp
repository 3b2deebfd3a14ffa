#pragma once
// rapidcheck generators of valid protocol messages: every field anywhere in its range;
// and the message types as GoogleTest typed-test parameters.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "tetrapulse/protocol/limits.hpp"
#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol::testing {

// An enum value among 0..last.
template <class E>
rc::Gen<E> enum_up_to(E last) {
  using U = std::underlying_type_t<E>;
  return rc::gen::map(rc::gen::inRange<int>(0, static_cast<int>(last) + 1),
                      [](int v) { return static_cast<E>(static_cast<U>(v)); });
}

inline rc::Gen<uint8_t> node_id_gen() { return rc::gen::inRange<uint8_t>(1, 255); }

// Every Body alternative, for TYPED_TEST_SUITE(Suite, BodyTypes, BodyTypeName).
template <class V>
struct TypesOf;
template <class... Ts>
struct TypesOf<std::variant<Ts...>> {
  using type = ::testing::Types<Ts...>;
};
using BodyTypes = TypesOf<Body>::type;

// Typed tests named after the message ("identify"), not a number.
struct BodyTypeName {
  template <class T>
  static std::string GetName(int) {
    return message_name(T::kType);
  }
};

// Body alternative I as a Body.
template <size_t... I>
rc::Gen<Body> body_gen(std::index_sequence<I...>) {
  return rc::gen::oneOf(rc::gen::cast<Body>(rc::gen::arbitrary<std::variant_alternative_t<I, Body>>())...);
}

// Random bodies of type `t` (a Body alternative's kType); of the first alternative otherwise.
template <size_t I = 0>
rc::Gen<Body> body_of_type(MessageType t) {
  using T = std::variant_alternative_t<I, Body>;
  if constexpr (I + 1 < std::variant_size_v<Body>) {
    if (T::kType != t) return body_of_type<I + 1>(t);
  }
  return rc::gen::cast<Body>(rc::gen::arbitrary<T>());
}

// The type of every Body alternative, in Body's order.
template <size_t... I>
std::vector<MessageType> body_types(std::index_sequence<I...>) {
  return {std::variant_alternative_t<I, Body>::kType...};
}
inline std::vector<MessageType> body_types() { return body_types(std::make_index_sequence<std::variant_size_v<Body>>()); }

}  // namespace tetrapulse::protocol::testing

namespace rc {

namespace tp = tetrapulse::protocol;

template <>
struct Arbitrary<tp::Code> {
  static Gen<tp::Code> arbitrary() {
    return gen::apply(
        [](int length, uint64_t bits) {
          tp::Code c;
          c.length = static_cast<uint8_t>(length);
          c.bits = length == 64 ? bits : bits & ((uint64_t{1} << length) - 1);
          return c;
        },
        gen::inRange<int>(0, tp::kMaxCodeLength + 1), gen::arbitrary<uint64_t>());
  }
};

template <>
struct Arbitrary<tp::Config> {
  static Gen<tp::Config> arbitrary() {
    using tp::Config;
    using tp::testing::enum_up_to;
    return gen::build<Config>(
        gen::set(&Config::node_id, tp::testing::node_id_gen()), gen::set(&Config::target_id),
        gen::set(&Config::codes), gen::set(&Config::modulation, enum_up_to(tp::Modulation::kConstant)),
        gen::set(&Config::low_level),
        gen::set(&Config::bit_period_ns, gen::inRange<uint32_t>(tp::kMinBitPeriodNs, UINT32_MAX)),
        gen::set(&Config::epoch_ns), gen::set(&Config::brightness), gen::set(&Config::current_limit_ma),
        gen::set(&Config::sync_source, enum_up_to(tp::SyncSource::kCan)),
        gen::set(&Config::gpio_edge, enum_up_to(tp::GpioEdge::kFalling)),
        gen::set(&Config::gpio_edge_period_ns, gen::inRange<uint32_t>(tp::kMinGpioEdgePeriodNs, UINT32_MAX)),
        gen::set(&Config::gpio_edge_epoch_ns),
        gen::set(&Config::gpio_edge_numbering, enum_up_to(tp::GpioEdgeNumbering::kCountAfterGap)));
  }
};

template <tp::MessageType kT>
struct Arbitrary<tp::EmptyMessage<kT>> {
  static Gen<tp::EmptyMessage<kT>> arbitrary() { return gen::just(tp::EmptyMessage<kT>{}); }
};

template <>
struct Arbitrary<tp::SetConfig> {
  static Gen<tp::SetConfig> arbitrary() { return gen::build<tp::SetConfig>(gen::set(&tp::SetConfig::config)); }
};

template <>
struct Arbitrary<tp::Identify> {
  static Gen<tp::Identify> arbitrary() {
    return gen::build<tp::Identify>(
        gen::set(&tp::Identify::pattern, tp::testing::enum_up_to(tp::IdentifyPattern::kCountIndex)),
        gen::set(&tp::Identify::duration_ms));
  }
};

template <>
struct Arbitrary<tp::Reboot> {
  static Gen<tp::Reboot> arbitrary() {
    return gen::build<tp::Reboot>(gen::set(&tp::Reboot::mode, tp::testing::enum_up_to(tp::RebootMode::kBootloader)));
  }
};

template <>
struct Arbitrary<tp::UpdateBegin> {
  static Gen<tp::UpdateBegin> arbitrary() {
    return gen::build<tp::UpdateBegin>(
        gen::set(&tp::UpdateBegin::image_size, gen::inRange<uint32_t>(64, UINT32_MAX)),
        gen::set(&tp::UpdateBegin::version), gen::set(&tp::UpdateBegin::crc32c));
  }
};

template <>
struct Arbitrary<tp::UpdateChunk> {
  static Gen<tp::UpdateChunk> arbitrary() {
    return gen::apply(
        [](uint32_t offset, int length, std::array<uint8_t, tp::kMaxUpdateChunk> data) {
          tp::UpdateChunk m;
          m.offset = offset;
          m.length = static_cast<uint16_t>(length);
          for (int i = 0; i < length; ++i) m.data[i] = data[i];
          return m;
        },
        gen::arbitrary<uint32_t>(), gen::inRange<int>(1, tp::kMaxUpdateChunk + 1),
        gen::arbitrary<std::array<uint8_t, tp::kMaxUpdateChunk>>());
  }
};

template <>
struct Arbitrary<tp::GetLedLog> {
  static Gen<tp::GetLedLog> arbitrary() { return gen::build<tp::GetLedLog>(gen::set(&tp::GetLedLog::first)); }
};

template <>
struct Arbitrary<tp::Sync> {
  static Gen<tp::Sync> arbitrary() { return gen::build<tp::Sync>(gen::set(&tp::Sync::sync_seq)); }
};

template <>
struct Arbitrary<tp::FollowUp> {
  static Gen<tp::FollowUp> arbitrary() {
    return gen::build<tp::FollowUp>(gen::set(&tp::FollowUp::sync_seq), gen::set(&tp::FollowUp::tx_time_ns));
  }
};

template <>
struct Arbitrary<tp::Ack> {
  static Gen<tp::Ack> arbitrary() {
    using T = tp::MessageType;
    return gen::build<tp::Ack>(
        gen::set(&tp::Ack::request_type,
                 gen::element(T::kGetInfo, T::kGetConfig, T::kSetConfig, T::kGetStatus, T::kIdentify,
                              T::kPersistConfig, T::kFactoryReset, T::kReboot, T::kUpdateBegin,
                              T::kUpdateChunk, T::kUpdateVerify, T::kUpdateAbort, T::kGetLedLog)),
        gen::set(&tp::Ack::value));
  }
};

template <>
struct Arbitrary<tp::Info> {
  static Gen<tp::Info> arbitrary() {
    using tp::Info;
    return gen::build<Info>(
        gen::set(&Info::protocol_version),
        gen::set(&Info::hw_model, gen::element(tp::HwModel::kStm32f405Reference, tp::HwModel::kLinuxBoard,
                                               tp::HwModel::kSimulatedBoard)),
        gen::set(&Info::hw_revision), gen::set(&Info::fw_version), gen::set(&Info::bootloader_version),
        gen::set(&Info::serial), gen::set(&Info::uptime_ms), gen::set(&Info::capabilities),
        gen::set(&Info::node_id, tp::testing::node_id_gen()), gen::set(&Info::active_slot),
        gen::set(&Info::max_code_length, gen::inRange<uint8_t>(1, tp::kMaxCodeLength + 1)));
  }
};

template <>
struct Arbitrary<tp::ConfigReport> {
  static Gen<tp::ConfigReport> arbitrary() {
    return gen::build<tp::ConfigReport>(gen::set(&tp::ConfigReport::config));
  }
};

template <>
struct Arbitrary<tp::StatusReport> {
  static Gen<tp::StatusReport> arbitrary() {
    using tp::StatusReport;
    using tp::testing::enum_up_to;
    return gen::build<StatusReport>(
        gen::set(&StatusReport::sync_state, enum_up_to(tp::SyncState::kHoldover)),
        gen::set(&StatusReport::sync_source, enum_up_to(tp::SyncSource::kCan)),
        gen::set(&StatusReport::offset_ns), gen::set(&StatusReport::rate_ppb), gen::set(&StatusReport::holdover_ms),
        gen::set(&StatusReport::sync_accepted), gen::set(&StatusReport::sync_rejected),
        gen::set(&StatusReport::rx_malformed), gen::set(&StatusReport::can_errors),
        gen::set(&StatusReport::can_bus_off, gen::inRange<uint8_t>(0, 2)), gen::set(&StatusReport::flash_errors),
        gen::set(&StatusReport::watchdog_resets),
        // Any byte: a receiver must carry error codes it does not know.
        gen::set(&StatusReport::last_error, gen::cast<tp::Error>(gen::arbitrary<uint8_t>())),
        gen::set(&StatusReport::update_state, enum_up_to(tp::UpdateState::kFailed)),
        gen::set(&StatusReport::uptime_ms));
  }
};

template <>
struct Arbitrary<tp::LedLogEntry> {
  static Gen<tp::LedLogEntry> arbitrary() {
    using tp::LedLogEntry;
    return gen::build<LedLogEntry>(gen::set(&LedLogEntry::seq), gen::set(&LedLogEntry::rig_time_ns),
                                   gen::set(&LedLogEntry::marker, gen::inRange<uint8_t>(0, tp::kMarkersPerTarget)),
                                   gen::set(&LedLogEntry::duty));
  }
};

template <>
struct Arbitrary<tp::LedLog> {
  static Gen<tp::LedLog> arbitrary() {
    return gen::apply(
        [](uint32_t next, int count, std::array<tp::LedLogEntry, tp::kMaxLedLogEntries> entries) {
          tp::LedLog m;
          m.next = next;
          m.count = static_cast<uint8_t>(count);
          for (int i = 0; i < count; ++i) m.entries[i] = entries[i];
          return m;
        },
        gen::arbitrary<uint32_t>(), gen::inRange<int>(0, tp::kMaxLedLogEntries + 1),
        gen::arbitrary<std::array<tp::LedLogEntry, tp::kMaxLedLogEntries>>());
  }
};

template <>
struct Arbitrary<tp::ErrorResponse> {
  static Gen<tp::ErrorResponse> arbitrary() {
    using tp::ErrorResponse;
    return gen::build<ErrorResponse>(
        gen::set(&ErrorResponse::request_type, gen::cast<tp::MessageType>(gen::arbitrary<uint8_t>())),
        gen::set(&ErrorResponse::error, gen::cast<tp::Error>(gen::inRange<int>(1, 256))),
        gen::set(&ErrorResponse::detail));
  }
};

template <>
struct Arbitrary<tp::Message> {
  static Gen<tp::Message> arbitrary() {
    return gen::build<tp::Message>(
        gen::set(&tp::Message::seq),
        gen::set(&tp::Message::body,
                 tp::testing::body_gen(std::make_index_sequence<std::variant_size_v<tp::Body>>())));
  }
};

}  // namespace rc

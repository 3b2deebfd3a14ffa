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

// Random bodies of type `t` (a Body alternative's kType); of the first alternative otherwise.
rc::Gen<Body> body_of_type(MessageType t);
// Random bodies of every type.
rc::Gen<Body> any_body();

// The type of every Body alternative, in Body's order.
template <size_t... I>
std::vector<MessageType> body_types(std::index_sequence<I...>) {
  return {std::variant_alternative_t<I, Body>::kType...};
}
inline std::vector<MessageType> body_types() { return body_types(std::make_index_sequence<std::variant_size_v<Body>>()); }

}  // namespace tetrapulse::protocol::testing

// The generators' bodies are compiled once, in message_generators.cpp: each
// one instantiates a good deal of rapidcheck, and three test files use them.
namespace rc {

namespace tp = tetrapulse::protocol;

template <>
struct Arbitrary<tp::Code> {
  static Gen<tp::Code> arbitrary();
};
template <>
struct Arbitrary<tp::Config> {
  static Gen<tp::Config> arbitrary();
};
template <>
struct Arbitrary<tp::SetConfig> {
  static Gen<tp::SetConfig> arbitrary();
};
template <>
struct Arbitrary<tp::Identify> {
  static Gen<tp::Identify> arbitrary();
};
template <>
struct Arbitrary<tp::Reboot> {
  static Gen<tp::Reboot> arbitrary();
};
template <>
struct Arbitrary<tp::UpdateBegin> {
  static Gen<tp::UpdateBegin> arbitrary();
};
template <>
struct Arbitrary<tp::UpdateChunk> {
  static Gen<tp::UpdateChunk> arbitrary();
};
template <>
struct Arbitrary<tp::GetLedLog> {
  static Gen<tp::GetLedLog> arbitrary();
};
template <>
struct Arbitrary<tp::Sync> {
  static Gen<tp::Sync> arbitrary();
};
template <>
struct Arbitrary<tp::FollowUp> {
  static Gen<tp::FollowUp> arbitrary();
};
template <>
struct Arbitrary<tp::Ack> {
  static Gen<tp::Ack> arbitrary();
};
template <>
struct Arbitrary<tp::Info> {
  static Gen<tp::Info> arbitrary();
};
template <>
struct Arbitrary<tp::ConfigReport> {
  static Gen<tp::ConfigReport> arbitrary();
};
template <>
struct Arbitrary<tp::StatusReport> {
  static Gen<tp::StatusReport> arbitrary();
};
template <>
struct Arbitrary<tp::LedLogEntry> {
  static Gen<tp::LedLogEntry> arbitrary();
};
template <>
struct Arbitrary<tp::LedLog> {
  static Gen<tp::LedLog> arbitrary();
};
template <>
struct Arbitrary<tp::ErrorResponse> {
  static Gen<tp::ErrorResponse> arbitrary();
};
template <>
struct Arbitrary<tp::Message> {
  static Gen<tp::Message> arbitrary();
};

template <tp::MessageType kT>
struct Arbitrary<tp::EmptyMessage<kT>> {
  static Gen<tp::EmptyMessage<kT>> arbitrary() { return gen::just(tp::EmptyMessage<kT>{}); }
};

}  // namespace rc

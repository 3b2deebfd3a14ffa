#pragma once
// Dispatch over the Body variant without std::visit, whose "valueless" path would pull
// abort() into the firmware. Body's alternatives are trivially copyable, so it never is valueless.
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

#include "tetrapulse/protocol/message.hpp"

namespace tetrapulse::protocol::detail {

// f(alternative) for the alternative `body` holds; B is Body or const Body.
template <size_t I = 0, class B, class F>
decltype(auto) visit_body(B& body, F&& f) {
  if constexpr (I + 1 == std::variant_size_v<Body>) {
    return f(*std::get_if<I>(&body));
  } else {
    if (body.index() == I) return f(*std::get_if<I>(&body));
    return visit_body<I + 1>(body, std::forward<F>(f));
  }
}

// Makes `body` hold the default alternative whose kType is `type`; false if there is none.
template <size_t I = 0>
bool emplace_type(Body& body, MessageType type) {
  if constexpr (I == std::variant_size_v<Body>) {
    return false;
  } else {
    if (std::variant_alternative_t<I, Body>::kType == type) {
      body.template emplace<I>();
      return true;
    }
    return emplace_type<I + 1>(body, type);
  }
}

}  // namespace tetrapulse::protocol::detail

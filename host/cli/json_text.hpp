#pragma once
// JSON text for `--json` output: strings escaped per RFC 8259, objects built field by field.
#include <cstdint>
#include <string>

#include <fmt/format.h>

namespace tetrapulse::cli {

std::string json_string(const std::string& s);

// {"a": 1, "b": "x"} built in order; values are JSON text already (json_string for strings).
class JsonObject {
 public:
  JsonObject& raw(const std::string& key, const std::string& json_value) {
    text_ += (text_.empty() ? "" : ", ") + json_string(key) + ": " + json_value;
    return *this;
  }
  JsonObject& str(const std::string& key, const std::string& value) { return raw(key, json_string(value)); }
  template <class Number>
  JsonObject& num(const std::string& key, Number value) {
    return raw(key, fmt::format("{}", value));
  }
  JsonObject& flag(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
  std::string text() const { return "{" + text_ + "}"; }

 private:
  std::string text_;
};

}  // namespace tetrapulse::cli

#pragma once
// Typed, located access to YAML fields: every failure names the file, line and field.
#include <string>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "tetrapulse/datasets/dataset_error.hpp"

namespace tetrapulse::yaml_fields {

class Fields {
 public:
  explicit Fields(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  bool failed() const { return failed_; }
  const DatasetError& error() const { return error_; }

  // Records the first problem only; later calls are ignored.
  void fail(const YAML::Node& at, const std::string& message) {
    if (failed_) return;
    failed_ = true;
    error_ = DatasetError{file_, at.IsDefined() && at.Mark().line >= 0 ? at.Mark().line + 1 : 0, message};
  }
  void fail_line(int line, const std::string& message) {
    if (failed_) return;
    failed_ = true;
    error_ = DatasetError{file_, line, message};
  }

  // Child `key` of map `parent`; fails when missing and `required`.
  // A missing child is an undefined node (IsDefined() == false).
  YAML::Node child(const YAML::Node& parent, const std::string& key, const std::string& path, bool required = true) {
    if (failed_) return missing();
    if (!parent.IsMap()) {
      fail(parent, fmt::format("{}: expected a mapping", path.empty() ? "document" : path));
      return missing();
    }
    YAML::Node n = parent[key];
    if (!n.IsDefined() || n.IsNull()) {
      if (required) fail(parent, fmt::format("{}: missing required field", join(path, key)));
      return missing();
    }
    return n;
  }

  template <typename T>
  T scalar(const YAML::Node& n, const std::string& field, const char* what, T fallback = T{}) {
    if (failed_) return fallback;
    if (!n.IsScalar()) {
      fail(n, fmt::format("{}: expected {}", field, what));
      return fallback;
    }
    T v;
    if (!YAML::convert<T>::decode(n, v)) {
      fail(n, fmt::format("{}: expected {}, got '{}'", field, what, n.Scalar()));
      return fallback;
    }
    return v;
  }

  std::vector<double> numbers(const YAML::Node& n, const std::string& field) {
    std::vector<double> out;
    if (failed_) return out;
    if (!n.IsSequence()) {
      fail(n, fmt::format("{}: expected a list of numbers", field));
      return out;
    }
    for (size_t i = 0; i < n.size(); ++i) {
      out.push_back(scalar<double>(n[i], fmt::format("{}[{}]", field, i), "a number"));
    }
    return out;
  }

  static YAML::Node missing() { return YAML::Node(YAML::NodeType::Undefined); }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

 private:
  std::string file_;
  bool failed_ = false;
  DatasetError error_;
};

// A YAML double-quoted scalar holding `s` exactly.
inline std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// Parses `text` into a document; a syntax error becomes a located DatasetError.
inline DatasetResult<YAML::Node> load_yaml(const std::string& text, const std::string& name) {
  try {
    YAML::Node doc = YAML::Load(text);
    if (!doc.IsMap()) return dataset_error(name, 0, "expected a YAML mapping at the top level");
    return doc;
  } catch (const YAML::Exception& e) {
    return dataset_error(name, e.mark.line >= 0 ? e.mark.line + 1 : 0, "YAML syntax: " + e.msg);
  }
}

}  // namespace tetrapulse::yaml_fields

#include "map_reader.hpp"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace tetrapulse::sim {

std::string Range::describe() const {
  if (std::isinf(lo) && std::isinf(hi)) return "a number";
  if (std::isinf(hi)) return fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  if (std::isinf(lo)) return fmt::format("{} {}", hi_open ? "<" : "<=", hi);
  return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
}

MapReader::MapReader(yaml_fields::Fields& fields, const YAML::Node& node, std::string path,
                     std::vector<std::string> allowed)
    : f_(fields), node_(node), path_(std::move(path)) {
  if (f_.failed()) return;
  if (!node_.IsMap()) {
    f_.fail(node_, fmt::format("{}: expected a mapping", path_.empty() ? "document" : path_));
    return;
  }
  for (const auto& kv : node_) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
    bool known = false;
    for (const std::string& a : allowed) known = known || a == key;
    if (!known) {
      f_.fail(kv.first, fmt::format("{}: unknown field (expected one of: {})", path_of(key), fmt::join(allowed, ", ")));
      return;
    }
  }
}

bool MapReader::has(const std::string& key) const {
  if (!node_.IsMap()) return false;
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

YAML::Node MapReader::child(const std::string& key, bool required) { return f_.child(node_, key, path_, required); }

void MapReader::fail(const std::string& key, const std::string& message) {
  const YAML::Node at = has(key) ? node_[key] : node_;
  f_.fail(at, fmt::format("{}: {}", path_of(key), message));
}

double MapReader::number(const std::string& key, const Range& range, std::optional<double> fallback) {
  if (f_.failed()) return fallback.value_or(0.0);
  if (!has(key) && fallback) return *fallback;
  const YAML::Node n = child(key);
  const double v = f_.scalar<double>(n, path_of(key), "a number");
  if (f_.failed()) return fallback.value_or(0.0);
  if (!std::isfinite(v)) {
    fail(key, "not a finite number");
  } else if (!range.contains(v)) {
    fail(key, fmt::format("must be {}, got {}", range.describe(), v));
  }
  return v;
}

int64_t MapReader::integer(const std::string& key, const Range& range, std::optional<int64_t> fallback) {
  if (f_.failed()) return fallback.value_or(0);
  if (!has(key) && fallback) return *fallback;
  const YAML::Node n = child(key);
  const auto v = f_.scalar<int64_t>(n, path_of(key), "an integer");
  if (f_.failed()) return fallback.value_or(0);
  if (!range.contains(static_cast<double>(v))) fail(key, fmt::format("must be {}, got {}", range.describe(), v));
  return v;
}

bool MapReader::boolean(const std::string& key, std::optional<bool> fallback) {
  if (f_.failed()) return fallback.value_or(false);
  if (!has(key) && fallback) return *fallback;
  return f_.scalar<bool>(child(key), path_of(key), "true or false");
}

std::string MapReader::text(const std::string& key, std::optional<std::string> fallback) {
  if (f_.failed()) return fallback.value_or("");
  if (!has(key) && fallback) return *fallback;
  return f_.scalar<std::string>(child(key), path_of(key), "a string");
}

std::vector<double> MapReader::numbers(const std::string& key, int count, const Range& range,
                                       std::optional<std::vector<double>> fallback) {
  if (f_.failed()) return fallback.value_or(std::vector<double>{});
  if (!has(key) && fallback) return *fallback;
  std::vector<double> v = f_.numbers(child(key), path_of(key));
  if (f_.failed()) return fallback.value_or(std::vector<double>{});
  if (count >= 0 && static_cast<int>(v.size()) != count) {
    fail(key, fmt::format("expected {} numbers, got {}", count, v.size()));
    return v;
  }
  for (size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]) || !range.contains(v[i])) {
      f_.fail(node_[key][i], fmt::format("{}[{}]: must be {}, got {}", path_of(key), i, range.describe(), v[i]));
      break;
    }
  }
  return v;
}

Eigen::Vector3d MapReader::vec3(const std::string& key, const Range& range, std::optional<Eigen::Vector3d> fallback) {
  std::optional<std::vector<double>> fb;
  if (fallback) fb = std::vector<double>{fallback->x(), fallback->y(), fallback->z()};
  const std::vector<double> v = numbers(key, 3, range, fb);
  if (v.size() != 3) return fallback.value_or(Eigen::Vector3d::Zero());
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

}  // namespace tetrapulse::sim

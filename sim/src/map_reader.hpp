#pragma once
// Reading one YAML mapping of a scenario field by field, each value checked
// against its range, every failure located ("file:line: path.key: what").
// Unknown keys are errors. Built on the localizer's yaml_fields::Fields, which
// keeps the first failure; after it every read returns its fallback.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/datasets/yaml_fields.hpp"

namespace tetrapulse::sim {

// A closed, open or half-open interval of allowed values, and how to say it.
struct Range {
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;

  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string describe() const;

  static Range any() { return Range{}; }
  static Range positive() { return Range{0, INFINITY, true, false}; }
  static Range non_negative() { return Range{0, INFINITY, false, false}; }
  static Range closed(double a, double b) { return Range{a, b, false, false}; }
  static Range open_closed(double a, double b) { return Range{a, b, true, false}; }
  static Range closed_open(double a, double b) { return Range{a, b, false, true}; }
  static Range open(double a, double b) { return Range{a, b, true, true}; }
};

class MapReader {
 public:
  // Fails unless `node` is a mapping whose keys are all in `allowed`.
  MapReader(yaml_fields::Fields& fields, const YAML::Node& node, std::string path, std::vector<std::string> allowed);

  yaml_fields::Fields& fields() { return f_; }
  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool ok() const { return !f_.failed(); }
  std::string path_of(const std::string& key) const { return yaml_fields::Fields::join(path_, key); }

  bool has(const std::string& key) const;
  // The child node; a missing required one fails.
  YAML::Node child(const std::string& key, bool required = true);
  // Fails at `key`'s line with "path.key: message".
  void fail(const std::string& key, const std::string& message);

  // Without a fallback the field is required.
  double number(const std::string& key, const Range& range, std::optional<double> fallback = std::nullopt);
  int64_t integer(const std::string& key, const Range& range, std::optional<int64_t> fallback = std::nullopt);
  bool boolean(const std::string& key, std::optional<bool> fallback = std::nullopt);
  std::string text(const std::string& key, std::optional<std::string> fallback = std::nullopt);
  // A list of exactly `count` numbers (any count when count < 0), each in `range`.
  std::vector<double> numbers(const std::string& key, int count, const Range& range,
                              std::optional<std::vector<double>> fallback = std::nullopt);
  Eigen::Vector3d vec3(const std::string& key, const Range& range, std::optional<Eigen::Vector3d> fallback = std::nullopt);

 private:
  yaml_fields::Fields& f_;
  YAML::Node node_;
  std::string path_;
};

}  // namespace tetrapulse::sim

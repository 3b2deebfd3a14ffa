// targets.yaml (docs/rig-dataset.md): time base, modulation, targets with four markers each.
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/datasets/yaml_fields.hpp"

namespace tetrapulse {

using yaml_fields::Fields;

namespace {

// `appearance: light | dark` under `node`, when present.
void read_appearance(Fields& f, const YAML::Node& node, const std::string& path, Appearance* out) {
  YAML::Node a = f.child(node, "appearance", path, false);
  if (!a.IsDefined()) return;
  const std::string text = f.scalar<std::string>(a, path + ".appearance", "light or dark");
  if (f.failed()) return;
  if (text == "light") {
    *out = Appearance::kLight;
  } else if (text == "dark") {
    *out = Appearance::kDark;
  } else {
    f.fail(a, fmt::format("{}.appearance: '{}' is not light or dark", path, text));
  }
}

// `colour: NAME` or `colour: {u: U, v: V}` under `node`, when present.
void read_colour(Fields& f, const YAML::Node& node, const std::string& path, std::optional<MarkerColour>* out) {
  YAML::Node c = f.child(node, "colour", path, false);
  if (!c.IsDefined()) return;
  const std::string field = path + ".colour";
  if (c.IsScalar()) {
    const std::string name = c.Scalar();
    if (name == "none") {  // a marker without the colour its target gives the others
      out->reset();
      return;
    }
    *out = named_colour(name);
    if (!*out) f.fail(c, fmt::format("{}: '{}' is not a named colour ({})", field, name, named_colour_list()));
    return;
  }
  if (!c.IsMap()) {
    f.fail(c, fmt::format("{}: expected a colour name or {{u: U, v: V}}", field));
    return;
  }
  MarkerColour colour;
  colour.u = f.scalar<double>(f.child(c, "u", field), field + ".u", "a number (Cb - 128, 8-bit levels)");
  colour.v = f.scalar<double>(f.child(c, "v", field), field + ".v", "a number (Cr - 128, 8-bit levels)");
  if (f.failed()) return;
  if (!std::isfinite(colour.u) || !std::isfinite(colour.v) || std::abs(colour.u) > 128 || std::abs(colour.v) > 128) {
    f.fail(c, fmt::format("{}: u and v must lie in [-128, 128], got ({}, {})", field, colour.u, colour.v));
    return;
  }
  if (std::hypot(colour.u, colour.v) < 8) {
    f.fail(c, fmt::format("{}: ({}, {}) is too close to grey to tell apart (|u, v| < 8)", field, colour.u,
                          colour.v));
    return;
  }
  *out = colour;
}

void read_marker(Fields& f, const YAML::Node& m, const std::string& path, Marker* out) {
  const std::vector<double> p = f.numbers(f.child(m, "position_m", path), path + ".position_m");
  if (f.failed()) return;
  if (p.size() != 3) {
    f.fail(m["position_m"], fmt::format("{}.position_m: expected 3 numbers, got {}", path, p.size()));
    return;
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(p[i])) {
      f.fail(m["position_m"], fmt::format("{}.position_m[{}]: not a finite number", path, i));
      return;
    }
  }
  out->position_m = Eigen::Vector3d(p[0], p[1], p[2]);
  YAML::Node code = f.child(m, "code", path, false);
  if (code.IsDefined()) {
    const std::string text = f.scalar<std::string>(code, path + ".code", "a string of 0 and 1");
    if (f.failed()) return;
    std::string why;
    out->code = parse_code(text, &why);
    if (!out->code) f.fail(code, fmt::format("{}.code: '{}' {}", path, text, why));
  }
  read_appearance(f, m, path, &out->appearance);
  read_colour(f, m, path, &out->colour);
}

}  // namespace

DatasetResult<TargetsFile> parse_targets_yaml(const std::string& text, const std::string& name) {
  auto doc = yaml_fields::load_yaml(text, name);
  if (!doc) return tl::unexpected(doc.error());
  Fields f(name);
  TargetsFile out;

  YAML::Node tb = f.child(*doc, "timebase", "");
  out.timebase.synchronized = f.scalar<bool>(f.child(tb, "synchronized", "timebase"), "timebase.synchronized",
                                             "true or false");
  out.timebase.epoch_ns = f.scalar<int64_t>(f.child(tb, "epoch_ns", "timebase"), "timebase.epoch_ns",
                                            "an integer (ns)");
  out.timebase.bit_period_ns = f.scalar<int64_t>(f.child(tb, "bit_period_ns", "timebase"), "timebase.bit_period_ns",
                                                 "an integer (ns)");
  if (!f.failed() && out.timebase.bit_period_ns <= 0) {
    f.fail(tb["bit_period_ns"], fmt::format("timebase.bit_period_ns: must be positive, got {}",
                                            out.timebase.bit_period_ns));
  }

  YAML::Node mod = f.child(*doc, "modulation", "");
  const std::string kind = f.scalar<std::string>(f.child(mod, "kind", "modulation"), "modulation.kind", "a string");
  if (!f.failed()) {
    if (!protocol::modulation_from_name(kind.c_str(), &out.modulation.kind)) {
      f.fail(mod["kind"], fmt::format("modulation.kind: '{}' is not on_off, two_level or constant", kind));
    }
  }
  if (!f.failed() && out.modulation.kind == ModulationKind::kTwoLevel) {
    out.modulation.low = f.scalar<double>(f.child(mod, "low", "modulation"), "modulation.low", "a number");
    if (!f.failed() && !(out.modulation.low >= 0.0 && out.modulation.low < 1.0)) {
      f.fail(mod["low"], fmt::format("modulation.low: must be in [0, 1), got {}", out.modulation.low));
    }
  }

  YAML::Node targets = f.child(*doc, "targets", "");
  if (!f.failed() && (!targets.IsSequence() || targets.size() == 0)) {
    f.fail(targets, "targets: expected a non-empty list of targets");
  }
  std::set<int> ids;
  for (size_t i = 0; !f.failed() && i < targets.size(); ++i) {
    const YAML::Node t = targets[i];
    const std::string path = fmt::format("targets[{}]", i);
    Target target;
    target.id = f.scalar<int>(f.child(t, "id", path), path + ".id", "a non-negative integer");
    if (!f.failed() && target.id < 0) f.fail(t["id"], fmt::format("{}.id: must be non-negative", path));
    if (!f.failed() && !ids.insert(target.id).second) {
      f.fail(t["id"], fmt::format("{}.id: {} is used by another target", path, target.id));
    }
    YAML::Node name_node = f.child(t, "name", path, false);
    if (name_node.IsDefined()) target.name = f.scalar<std::string>(name_node, path + ".name", "a string");
    target.marker_diameter_m = f.scalar<double>(f.child(t, "marker_diameter_m", path), path + ".marker_diameter_m",
                                                "a number (m)");
    if (!f.failed() && !(target.marker_diameter_m > 0 && target.marker_diameter_m < 10)) {
      f.fail(t["marker_diameter_m"], fmt::format("{}.marker_diameter_m: must be positive (metres), got {}", path,
                                                 target.marker_diameter_m));
    }
    read_appearance(f, t, path, &target.appearance);
    read_colour(f, t, path, &target.colour);
    YAML::Node markers = f.child(t, "markers", path);
    if (!f.failed() && (!markers.IsSequence() || markers.size() != 4)) {
      f.fail(markers, fmt::format("{}.markers: expected exactly four markers, got {}", path,
                                  markers.IsSequence() ? std::to_string(markers.size()) : std::string("none")));
    }
    for (size_t k = 0; !f.failed() && k < 4; ++k) {
      target.markers[k].appearance = target.appearance;  // the target's unless the marker says its own
      target.markers[k].colour = target.colour;
      read_marker(f, markers[k], fmt::format("{}.markers[{}]", path, k), &target.markers[k]);
    }
    out.targets.push_back(std::move(target));
  }
  if (f.failed()) return tl::unexpected(f.error());
  return out;
}

DatasetResult<TargetsFile> read_targets_yaml(const std::string& path) {
  auto text = read_text_file(path);
  if (!text) return tl::unexpected(text.error());
  return parse_targets_yaml(*text, path);
}

namespace {

std::string colour_yaml(const MarkerColour& c) {
  return c.name.empty() ? fmt::format("{{u: {}, v: {}}}", c.u, c.v) : c.name;
}

bool same_colour(const std::optional<MarkerColour>& a, const std::optional<MarkerColour>& b) {
  if (!a || !b) return !a && !b;
  return a->u == b->u && a->v == b->v && a->name == b->name;
}

const char* appearance_name(Appearance a) { return a == Appearance::kDark ? "dark" : "light"; }

}  // namespace

std::string format_targets_yaml(const TargetsFile& t) {
  std::string out;
  out += fmt::format("timebase:\n  synchronized: {}\n  epoch_ns: {}\n  bit_period_ns: {}\n",
                     t.timebase.synchronized ? "true" : "false", t.timebase.epoch_ns, t.timebase.bit_period_ns);
  out += fmt::format("modulation:\n  kind: {}\n", protocol::modulation_name(t.modulation.kind));
  if (t.modulation.kind == ModulationKind::kTwoLevel) out += fmt::format("  low: {}\n", t.modulation.low);
  out += "targets:\n";
  for (const Target& target : t.targets) {
    out += fmt::format("  - id: {}\n    name: {}\n    marker_diameter_m: {}\n", target.id,
                       yaml_fields::quoted(target.name), target.marker_diameter_m);
    // Fields of the default (light, no colour) are left out: files of LED rigs stay as they were.
    if (target.appearance != Appearance::kLight) {
      out += fmt::format("    appearance: {}\n", appearance_name(target.appearance));
    }
    if (target.colour) out += fmt::format("    colour: {}\n", colour_yaml(*target.colour));
    out += "    markers:\n";
    for (const Marker& m : target.markers) {
      out += fmt::format("      - position_m: [{}, {}, {}]\n", m.position_m.x(), m.position_m.y(), m.position_m.z());
      if (m.code) out += fmt::format("        code: \"{}\"\n", code_text(*m.code));
      if (m.appearance != target.appearance) out += fmt::format("        appearance: {}\n", appearance_name(m.appearance));
      if (!same_colour(m.colour, target.colour)) {
        out += fmt::format("        colour: {}\n", m.colour ? colour_yaml(*m.colour) : std::string("none"));
      }
    }
  }
  return out;
}

}  // namespace tetrapulse

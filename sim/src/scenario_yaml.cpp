// Scenario files (sim/SCENARIOS.md): the targets.yaml sections are read by the
// localizer's own reader, so a scenario's targets mean exactly what the dataset
// will say; everything else is read here.
#include "tetrapulse/sim/scenario_yaml.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "map_reader.hpp"
#include "motion_yaml.hpp"
#include "scenario_codes.hpp"
#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/sim/builtin_scenarios.hpp"

namespace tetrapulse::sim {

using yaml_fields::Fields;

namespace {

constexpr double kDeg = M_PI / 180.0;
// The contract's bound on a free-running board's rate error (docs/rig-dataset.md).
constexpr double kMaxClockPpm = 200.0;

int64_t seconds_to_ns(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }

void read_frames(Fields& f, const YAML::Node& node, FrameSchedule* out) {
  MapReader r(f, node, "frames",
              {"start_ns", "period_ns", "exposure_ns", "count", "ci_count", "dropped", "drop_probability"});
  constexpr double kMaxFrames = 1e7;
  out->start_ns = r.integer("start_ns", Range::closed(-4e18, 4e18), 0);
  out->period_ns = r.integer("period_ns", Range::closed(1, 1e12));
  out->exposure_ns = r.integer("exposure_ns", Range::closed(1, 1e12));
  if (r.ok() && out->exposure_ns > out->period_ns) {
    r.fail("exposure_ns", fmt::format("must not exceed period_ns ({}), got {}", out->period_ns, out->exposure_ns));
  }
  out->count = r.integer("count", Range::closed(1, kMaxFrames));
  out->ci_count = r.integer("ci_count", Range::closed(1, kMaxFrames), std::min<int64_t>(60, out->count));
  const std::vector<double> dropped = r.numbers("dropped", -1, Range::closed(0, kMaxFrames), std::vector<double>{});
  for (size_t i = 0; i < dropped.size() && r.ok(); ++i) {
    if (dropped[i] != std::floor(dropped[i])) {
      f.fail(node["dropped"][i], fmt::format("frames.dropped[{}]: expected a frame number, got {}", i, dropped[i]));
    }
    out->dropped.push_back(static_cast<int64_t>(dropped[i]));
  }
  out->drop_probability = r.number("drop_probability", Range::closed_open(0, 1), 0.0);
}

void read_camera(Fields& f, const YAML::Node& node, CameraInfo* cam, MotionSpec* motion, RenderSettings* render) {
  MapReader r(f, node, "camera",
              {"name", "image_width", "image_height", "hfov_deg", "intrinsics", "distortion_model",
               "distortion_coefficients", "psf_sigma_px", "motion"});
  cam->name = r.text("name", "");
  cam->width = static_cast<int>(r.integer("image_width", Range::closed(1, 16384)));
  cam->height = static_cast<int>(r.integer("image_height", Range::closed(1, 16384)));
  const std::string model = r.text("distortion_model");
  if (r.ok()) {
    if (model == "plumb_bob") {
      cam->model = DistortionModel::kPlumbBob;
    } else if (model == "equidistant") {
      cam->model = DistortionModel::kEquidistant;
    } else {
      r.fail("distortion_model", fmt::format("'{}' is not plumb_bob or equidistant", model));
    }
  }
  const bool pinhole = cam->model == DistortionModel::kPlumbBob;
  if (r.ok() && r.has("hfov_deg") == r.has("intrinsics")) {
    r.fail(r.has("hfov_deg") ? "intrinsics" : "hfov_deg", "give exactly one of hfov_deg and intrinsics [fx, fy, cx, cy]");
  }
  if (r.has("hfov_deg")) {
    // Focal length from the horizontal field of view, ignoring distortion; principal point at the centre.
    const double hfov = r.number("hfov_deg", pinhole ? Range::open(0, 180) : Range::open(0, 360)) * kDeg;
    const double half_width = cam->width / 2.0;
    cam->fx = cam->fy = pinhole ? half_width / std::tan(hfov / 2) : half_width / (hfov / 2);
    cam->cx = (cam->width - 1) / 2.0;
    cam->cy = (cam->height - 1) / 2.0;
  } else {
    const std::vector<double> k = r.numbers("intrinsics", 4, Range::any());
    if (r.ok()) {
      cam->fx = k[0];
      cam->fy = k[1];
      cam->cx = k[2];
      cam->cy = k[3];
      if (!(cam->fx > 0 && cam->fy > 0)) r.fail("intrinsics", "fx and fy must be positive");
    }
  }
  const std::vector<double> d =
      r.numbers("distortion_coefficients", -1, Range::any(), std::vector<double>(pinhole ? 5 : 4, 0.0));
  if (r.ok()) {
    const bool count_ok = pinhole ? (d.size() == 4 || d.size() == 5) : d.size() == 4;
    if (!count_ok) {
      r.fail("distortion_coefficients",
             fmt::format("expected {} numbers for {}, got {}", pinhole ? "4 or 5 (k1 k2 p1 p2 [k3])" : "4 (k1 k2 k3 k4)",
                         model, d.size()));
    }
    for (size_t i = 0; i < d.size() && i < cam->distortion.size(); ++i) cam->distortion[i] = d[i];
  }
  render->psf_sigma_px = r.number("psf_sigma_px", Range::closed(0, 10), render->psf_sigma_px);
  *motion = read_motion(f, r.child("motion"), "camera.motion");
}

void read_sensor(Fields& f, const YAML::Node& node, SensorConfig* s) {
  MapReader r(f, node, "sensor",
              {"bit_depth", "gain_e_per_dn", "read_noise_e", "full_well_e", "black_level_dn", "background_e_per_ms",
               "texture_contrast", "texture_scale_px", "prnu", "dsnu_e", "noise", "blooming", "colour_filter"});
  s->bit_depth = static_cast<int>(r.integer("bit_depth", Range::closed(8, 16), s->bit_depth));
  if (r.ok() && s->bit_depth != 8 && s->bit_depth != 16) r.fail("bit_depth", fmt::format("must be 8 or 16, got {}", s->bit_depth));
  s->gain_e_per_dn = r.number("gain_e_per_dn", Range::positive(), s->gain_e_per_dn);
  s->read_noise_e = r.number("read_noise_e", Range::non_negative(), s->read_noise_e);
  s->full_well_e = r.number("full_well_e", Range::positive(), s->full_well_e);
  s->black_level_dn = r.number("black_level_dn", Range::non_negative(), s->black_level_dn);
  s->background_e_per_ms = r.number("background_e_per_ms", Range::non_negative(), s->background_e_per_ms);
  s->texture_contrast = r.number("texture_contrast", Range::closed(0, 1), s->texture_contrast);
  s->texture_scale_px = r.number("texture_scale_px", Range::closed(2, 1e5), s->texture_scale_px);
  s->prnu = r.number("prnu", Range::closed(0, 0.5), s->prnu);
  s->dsnu_e = r.number("dsnu_e", Range::non_negative(), s->dsnu_e);
  s->noise = r.boolean("noise", s->noise);
  s->blooming = r.number("blooming", Range::closed(0, 1), s->blooming);
  const std::string filter = r.text("colour_filter", "none");
  if (filter == "rggb") {
    s->bayer = true;
  } else if (filter != "none" && r.ok()) {
    r.fail("colour_filter", fmt::format("'{}' is not none or rggb", filter));
  }
  if (r.ok() && s->bayer && s->bit_depth != 8) r.fail("colour_filter", "a Bayer sensor writes 8-bit colour PNGs: bit_depth must be 8");
}

void read_render(Fields& f, const YAML::Node& node, RenderSettings* s) {
  MapReader r(f, node, "render", {"motion_blur_step_px", "max_substeps"});
  s->blur_step_px = r.number("motion_blur_step_px", Range::open_closed(0, 100), s->blur_step_px);
  s->max_substeps = static_cast<int>(r.integer("max_substeps", Range::closed(1, 1024), s->max_substeps));
}

// [[from_s, to_s], ...] as rig-time intervals.
TimeIntervals read_intervals(MapReader& r, const std::string& key) {
  std::vector<TimeInterval> out;
  const YAML::Node list = r.child(key, false);
  if (!list.IsDefined() || !r.ok()) return TimeIntervals{};
  if (!list.IsSequence()) {
    r.fail(key, "expected a list of [from_s, to_s] pairs");
    return TimeIntervals{};
  }
  for (size_t i = 0; i < list.size() && r.ok(); ++i) {
    const std::string path = fmt::format("{}[{}]", r.path_of(key), i);
    const std::vector<double> v = r.fields().numbers(list[i], path);
    if (!r.ok()) break;
    if (v.size() != 2 || !(v[1] > v[0])) {
      r.fields().fail(list[i], fmt::format("{}: expected [from_s, to_s] with from_s < to_s", path));
      break;
    }
    out.push_back(TimeInterval{seconds_to_ns(v[0]), seconds_to_ns(v[1])});
  }
  return TimeIntervals(std::move(out));
}

void read_board(Fields& f, const YAML::Node& node, const std::string& path, bool synchronized, BoardClockSpec* out) {
  MapReader r(f, node, path, {"clock_ppm", "clock_offset_ns", "sync_loss_s", "sync"});
  out->free_running = !synchronized;
  const std::string sync = r.text("sync", synchronized ? "gpio" : "none");
  if (r.ok()) {
    if (sync == "gpio" && synchronized) {
      out->sync = BoardSync::kGpio;
    } else if (sync == "can" && synchronized) {
      out->sync = BoardSync::kCan;
    } else if (sync == "none" && !synchronized) {
      out->sync = BoardSync::kNone;
    } else {
      r.fail("sync", synchronized ? fmt::format("'{}' is not gpio or can (the time base is synchronized)", sync)
                                  : fmt::format("'{}': the time base is not synchronized, so only none", sync));
    }
  }
  out->drift_ppm = r.number("clock_ppm", Range::closed(-kMaxClockPpm, kMaxClockPpm), 0.0);
  out->offset_ns = r.integer("clock_offset_ns", Range::closed(-4e18, 4e18), 0);
  out->sync_loss = read_intervals(r, "sync_loss_s");
  if (r.ok() && !synchronized && !out->sync_loss.empty()) {
    r.fail("sync_loss_s", "the time base is not synchronized, so there is no sync to lose");
  }
}

void read_occlusions(Fields& f, const YAML::Node& list, const std::string& path, std::array<TimeIntervals, 4>* out) {
  if (f.failed() || !list.IsDefined()) return;
  if (!list.IsSequence()) {
    f.fail(list, fmt::format("{}: expected a list of {{marker, from_s, to_s}}", path));
    return;
  }
  std::array<std::vector<TimeInterval>, 4> hidden;
  for (size_t i = 0; i < list.size() && !f.failed(); ++i) {
    MapReader r(f, list[i], fmt::format("{}[{}]", path, i), {"marker", "from_s", "to_s"});
    const auto marker = r.integer("marker", Range::closed(0, 3));
    const double from = r.number("from_s", Range::any());
    const double to = r.number("to_s", Range::any());
    if (r.ok() && !(to > from)) r.fail("to_s", fmt::format("must be later than from_s ({} s), got {} s", from, to));
    if (r.ok()) hidden[static_cast<size_t>(marker)].push_back(TimeInterval{seconds_to_ns(from), seconds_to_ns(to)});
  }
  for (size_t m = 0; m < 4; ++m) (*out)[m] = TimeIntervals(std::move(hidden[m]));
}

void read_target_simulation(Fields& f, const YAML::Node& node, size_t index, bool synchronized, TargetSimulation* out) {
  const std::string path = fmt::format("targets[{}]", index);
  MapReader r(f, node, path,
              {"id", "name", "marker_diameter_m", "markers", "radiance_e_per_ms", "board", "occlusions", "motion",
               "beam_exponent", "beam_axis", "radiance_spread", "paint_e_per_ms", "rgb", "appearance", "colour"});
  // The markers themselves were read by the targets.yaml reader; only unknown keys are checked here.
  const YAML::Node markers = r.child("markers");
  for (size_t k = 0; k < markers.size() && r.ok(); ++k) {
    MapReader m(f, markers[k], fmt::format("{}.markers[{}]", path, k), {"position_m", "code", "appearance", "colour"});
  }
  out->radiance_e_per_ms = r.number("radiance_e_per_ms", Range::non_negative(), out->radiance_e_per_ms);
  out->beam_exponent = r.number("beam_exponent", Range::closed(0, 100), out->beam_exponent);
  const Eigen::Vector3d axis = r.vec3("beam_axis", Range::closed(-1e6, 1e6), out->beam_axis_B);
  if (r.ok() && !(axis.norm() > 0)) r.fail("beam_axis", "must not be zero");
  if (r.ok()) out->beam_axis_B = axis.normalized();
  out->radiance_spread = r.number("radiance_spread", Range::closed(0, 2), out->radiance_spread);
  if (r.has("paint_e_per_ms")) out->paint_e_per_ms = r.number("paint_e_per_ms", Range::positive());
  out->rgb = r.vec3("rgb", Range::closed(0, 1), out->rgb);
  if (r.ok() && !(out->rgb.maxCoeff() > 0)) r.fail("rgb", "must not be black");
  const YAML::Node board = r.child("board", false);
  if (board.IsDefined()) {
    read_board(f, board, path + ".board", synchronized, &out->clock);
  } else {
    out->clock.free_running = !synchronized;
    out->clock.sync = synchronized ? BoardSync::kGpio : BoardSync::kNone;
  }
  read_occlusions(f, r.child("occlusions", false), path + ".occlusions", &out->occluded);
  out->motion = read_motion(f, r.child("motion"), path + ".motion");
}

void read_distractor(Fields& f, const YAML::Node& node, const std::string& path, Distractor* out) {
  MapReader r(f, node, path, {"name", "diameter_m", "radiance_e_per_ms", "flicker", "motion"});
  out->name = r.text("name", "");
  out->diameter_m = r.number("diameter_m", Range::open(0, 100));
  out->radiance_e_per_ms = r.number("radiance_e_per_ms", Range::non_negative());
  const YAML::Node flicker = r.child("flicker", false);
  if (flicker.IsDefined() && r.ok()) {
    MapReader fl(f, flicker, path + ".flicker", {"kind", "frequency_hz", "duty", "depth", "phase_deg"});
    const std::string kind = fl.text("kind");
    if (kind == "steady") {
      out->flicker.kind = Flicker::Kind::kSteady;
    } else if (kind == "square") {
      out->flicker.kind = Flicker::Kind::kSquare;
    } else if (kind == "sine") {
      out->flicker.kind = Flicker::Kind::kSine;
    } else if (fl.ok()) {
      fl.fail("kind", fmt::format("'{}' is not steady, square or sine", kind));
    }
    const bool steady = out->flicker.kind == Flicker::Kind::kSteady;
    out->flicker.frequency_hz = fl.number("frequency_hz", Range::positive(), steady ? std::optional<double>(0.0) : std::nullopt);
    out->flicker.duty = fl.number("duty", Range::open_closed(0, 1), 0.5);
    out->flicker.depth = fl.number("depth", Range::closed(0, 1), 1.0);
    out->flicker.phase = fl.number("phase_deg", Range::closed_open(0, 360), 0.0) / 360.0;
  }
  out->motion = read_motion(f, r.child("motion"), path + ".motion");
}

}  // namespace

DatasetResult<Scenario> parse_scenario(const std::string& text, const std::string& name) {
  auto doc = yaml_fields::load_yaml(text, name);
  if (!doc) return tl::unexpected(doc.error());
  Fields f(name);
  Scenario s;
  s.source_text = text;
  MapReader top(f, *doc, "",
                {"name", "description", "seed", "frames", "camera", "sensor", "render", "timebase", "modulation",
                 "codebook", "targets", "distractors", "lighting"});
  s.name = top.text("name", std::filesystem::path(name).stem().string());
  s.description = top.text("description", "");
  s.seed = static_cast<uint64_t>(top.integer("seed", Range::closed(0, 9e18), 1));
  read_frames(f, top.child("frames"), &s.frames);
  read_camera(f, top.child("camera"), &s.camera, &s.camera_motion, &s.render);
  if (top.has("sensor")) read_sensor(f, top.child("sensor"), &s.sensor);
  if (top.has("render")) read_render(f, top.child("render"), &s.render);
  if (top.has("lighting")) {
    MapReader l(f, top.child("lighting"), "lighting", {"direction", "ambient"});
    const Eigen::Vector3d d = l.vec3("direction", Range::closed(-1e6, 1e6), s.light_direction_W);
    if (l.ok() && !(d.norm() > 0)) l.fail("direction", "must not be zero");
    if (l.ok()) s.light_direction_W = d.normalized();
    s.ambient = l.number("ambient", Range::closed(0, 1), s.ambient);
  }
  if (f.failed()) return tl::unexpected(f.error());

  // timebase, modulation and targets: exactly as targets.yaml reads them.
  auto targets = parse_targets_yaml(text, name);
  if (!targets) return tl::unexpected(targets.error());
  s.targets = std::move(*targets);
  if (top.has("codebook")) apply_codebook(f, top.child("codebook"), &s.targets);

  const YAML::Node target_nodes = (*doc)["targets"];
  s.simulation.resize(s.targets.targets.size());
  for (size_t i = 0; i < s.simulation.size() && !f.failed(); ++i) {
    read_target_simulation(f, target_nodes[i], i, s.targets.timebase.synchronized, &s.simulation[i]);
  }
  const YAML::Node distractors = top.child("distractors", false);
  if (distractors.IsDefined() && !f.failed()) {
    if (!distractors.IsSequence()) f.fail(distractors, "distractors: expected a list");
    for (size_t i = 0; i < distractors.size() && !f.failed(); ++i) {
      s.distractors.emplace_back();
      read_distractor(f, distractors[i], fmt::format("distractors[{}]", i), &s.distractors.back());
    }
  }
  if (f.failed()) return tl::unexpected(f.error());
  return s;
}

DatasetResult<Scenario> load_scenario(const std::string& name_or_path) {
  if (const BuiltinScenario* builtin = find_builtin_scenario(name_or_path)) {
    return parse_scenario(builtin->text, builtin->name + ".yaml (built-in)");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(name_or_path, ec)) {
    return dataset_error(name_or_path, 0, "neither a built-in scenario (tetrapulse sim --list) nor a scenario file");
  }
  auto text = read_text_file(name_or_path);
  if (!text) return tl::unexpected(text.error());
  return parse_scenario(*text, name_or_path);
}

}  // namespace tetrapulse::sim

#include "tetrapulse/datasets/pose_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include <fmt/format.h>

#include "tetrapulse/localizer/code_clock.hpp"

namespace tetrapulse {

ErrorStats ErrorStats::of(std::vector<double> values) {
  ErrorStats s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / double(values.size());
  const auto quantile = [&](double q) {
    // Linear interpolation between order statistics.
    const double at = q * double(values.size() - 1);
    const size_t lo = size_t(std::floor(at)), hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (at - double(lo)) * (values[hi] - values[lo]);
  };
  s.median = quantile(0.5);
  s.p95 = quantile(0.95);
  s.max = values.back();
  return s;
}

int markers_lit_in_view(const CameraModel& camera, const TargetsFile& targets, const Target& target,
                        const Pose& pose, int64_t start_ns, int64_t exposure_ns, const CodeClock* board_clock) {
  const bool phase_known = targets.timebase.synchronized || board_clock != nullptr;
  const CodeClock clock = board_clock ? *board_clock : CodeClock::from(targets.timebase);
  int count = 0;
  for (const Marker& m : target.markers) {
    const Eigen::Vector3d p = pose.apply(m.position_m);
    Eigen::Vector2d px;
    if (!camera.project(p, &px)) continue;
    const double radius_px = camera.info().fx * target.marker_diameter_m / 2 / p.norm();
    if (!camera.in_image(px, radius_px)) continue;
    const bool lit = targets.modulation.kind != ModulationKind::kOnOff || !phase_known ||
                     mean_emission(clock, targets.modulation, m.code, start_ns, exposure_ns) >= 0.5;
    count += lit;
  }
  return count;
}

namespace {

struct Episode {
  int64_t start = 0;  // frame number
  int64_t end = 0;    // last visible frame number
  std::optional<int64_t> first_report;
};

void add_latency(const std::vector<Episode>& episodes, TargetEvaluation* e) {
  e->episodes = episodes.size();
  for (size_t i = 0; i < episodes.size(); ++i) {
    const Episode& ep = episodes[i];
    const int64_t latency = ep.first_report ? *ep.first_report - ep.start : ep.end - ep.start + 1;
    if (i == 0) e->first_latency_frames = latency;
    e->max_latency_frames = std::max(e->max_latency_frames, latency);
  }
}

}  // namespace

DatasetResult<Evaluation> evaluate_poses(const RigDataset& dataset, const std::vector<PoseRecord>& poses,
                                         const std::string& poses_name, const EvaluationOptions& options) {
  if (!dataset.has_groundtruth()) {
    return dataset_error(dataset.path_of("groundtruth.csv"), 0, "missing: evaluation needs the true poses");
  }
  const TargetsFile& tf = dataset.targets();
  const CameraModel camera(dataset.camera());
  Evaluation out;
  // One code length in frames separates episodes.
  out.episode_gap_frames = options.episode_gap_frames;
  if (out.episode_gap_frames <= 0) {
    uint32_t length = 1;
    for (const Target& t : tf.targets)
      for (const Marker& m : t.markers)
        if (m.code) length = std::max<uint32_t>(length, m.code->length);
    const auto& frames = dataset.frames();
    int64_t period = tf.timebase.bit_period_ns;
    if (frames.size() >= 2) {
      period = (frames.back().timestamp_ns - frames.front().timestamp_ns) /
               std::max<int64_t>(1, frames.back().frame - frames.front().frame);
    }
    out.episode_gap_frames =
        std::max<int64_t>(10, int64_t(std::ceil(double(length) * double(tf.timebase.bit_period_ns) / double(std::max<int64_t>(period, 1)))));
  }

  std::map<int64_t, size_t> frame_index;
  for (size_t i = 0; i < dataset.frames().size(); ++i) frame_index[dataset.frames()[i].frame] = i;
  std::map<std::pair<int64_t, int>, Pose> truth;
  for (const GroundTruthRecord& g : dataset.groundtruth()) truth[{g.frame, g.target}] = g.pose.pose();
  std::map<std::pair<int64_t, int>, const PoseRecord*> reported;
  for (const PoseRecord& p : poses) {
    if (!frame_index.count(p.frame)) {
      return dataset_error(poses_name, 0, fmt::format("frame {} is not in {}", p.frame, dataset.path_of("frames.csv")));
    }
    reported[{p.frame, p.target}] = &p;
  }

  std::vector<double> all_position, all_orientation;
  std::vector<Episode> all_episodes;
  for (const Target& target : tf.targets) {
    TargetEvaluation e;
    e.target = target.id;
    const auto known_clock = options.board_clocks.find(target.id);
    const CodeClock* board_clock = known_clock != options.board_clocks.end() ? &known_clock->second : nullptr;
    std::vector<double> position, orientation;
    std::vector<Episode> episodes;
    int64_t last_visible = std::numeric_limits<int64_t>::min() / 2;
    std::vector<std::pair<int64_t, bool>> visible;  // frame number, reported
    for (const FrameRecord& f : dataset.frames()) {
      const auto gt = truth.find({f.frame, target.id});
      const auto row = reported.find({f.frame, target.id});
      const bool has_row = row != reported.end();
      if (has_row) {
        ++e.rows;
        if (gt == truth.end()) {
          ++e.misidentified;
        } else {
          const Pose measured = row->second->pose.pose();
          const double dp = (measured.t - gt->second.t).norm();
          const double da = rotation_angle_between(measured.R, gt->second.R);
          position.push_back(dp);
          orientation.push_back(da);
          const double gross = std::max(options.gross_position_m, options.gross_position_relative * gt->second.t.norm());
          if (dp > gross || da > options.gross_orientation_rad) ++e.misidentified;
        }
      }
      if (gt == truth.end()) continue;
      if (markers_lit_in_view(camera, tf, target, gt->second, f.timestamp_ns, f.exposure_ns, board_clock) < 3) continue;
      visible.emplace_back(f.frame, has_row);
      if (f.frame - last_visible > out.episode_gap_frames) episodes.push_back(Episode{f.frame, f.frame, {}});
      episodes.back().end = f.frame;
      last_visible = f.frame;
    }
    // The first report at or after each episode's start and within it.
    for (Episode& ep : episodes)
      for (const PoseRecord& p : poses)
        if (p.target == target.id && p.frame >= ep.start && p.frame <= ep.end &&
            (!ep.first_report || p.frame < *ep.first_report)) {
          ep.first_report = p.frame;
        }
    // Coverage counts from each episode's first report (the frames before are its
    // latency); an episode never reported counts whole.
    size_t k = 0;
    for (const Episode& ep : episodes) {
      for (; k < visible.size() && visible[k].first <= ep.end; ++k) {
        ++e.visible_frames_total;
        if (ep.first_report && visible[k].first < *ep.first_report) continue;
        ++e.visible_frames;
        e.covered_frames += visible[k].second;
      }
    }
    add_latency(episodes, &e);
    e.position_m = ErrorStats::of(position);
    e.orientation_rad = ErrorStats::of(orientation);
    all_position.insert(all_position.end(), position.begin(), position.end());
    all_orientation.insert(all_orientation.end(), orientation.begin(), orientation.end());
    all_episodes.insert(all_episodes.end(), episodes.begin(), episodes.end());
    out.overall.rows += e.rows;
    out.overall.visible_frames += e.visible_frames;
    out.overall.visible_frames_total += e.visible_frames_total;
    out.overall.covered_frames += e.covered_frames;
    out.overall.misidentified += e.misidentified;
    out.targets.push_back(e);
  }
  // Rows naming targets that do not exist.
  for (const PoseRecord& p : poses)
    if (!tf.find(p.target)) ++out.overall.rows, ++out.overall.misidentified;
  out.overall.position_m = ErrorStats::of(all_position);
  out.overall.orientation_rad = ErrorStats::of(all_orientation);
  out.overall.episodes = all_episodes.size();
  for (const TargetEvaluation& e : out.targets) {
    if (e.first_latency_frames &&
        (!out.overall.first_latency_frames || *e.first_latency_frames > *out.overall.first_latency_frames)) {
      out.overall.first_latency_frames = e.first_latency_frames;
    }
    out.overall.max_latency_frames = std::max(out.overall.max_latency_frames, e.max_latency_frames);
  }
  return out;
}

}  // namespace tetrapulse

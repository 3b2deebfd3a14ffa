#include "marker_reassociation.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace tetrapulse::localizer_internal {
namespace {

struct Candidate {
  int64_t track = -1;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double reach = 0;  // distance to the nearest predicted marker pixel
};

}  // namespace

std::optional<Reassociation> reassociate(const PoseFrame& f, size_t t, const TargetRoster& roster,
                                         const MarkerPoseOptions& options, double max_distance) {
  const TrackedTarget& tt = roster[t];
  if (!tt.predicted) return std::nullopt;
  std::array<Eigen::Vector2d, 4> predicted;
  for (int m = 0; m < 4; ++m)
    if (!roster.project_marker(t, m, &predicted[size_t(m)])) return std::nullopt;
  double span = 0;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = i + 1; j < 4; ++j) span = std::max(span, (predicted[i] - predicted[j]).norm());
  const double tolerance = 3 + 0.15 * span;

  std::vector<Candidate> candidates;
  for (const BlobTrack& track : f.tracker.tracks()) {
    const TrackSample& newest = track.history().newest();
    if (newest.frame != f.stamp.frame || !newest.detected || newest.merged) continue;
    if (cut_by_border(track.last_blob(), f.camera.width(), f.camera.height())) continue;
    double reach = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& p : predicted) reach = std::min(reach, (newest.centroid - p).norm());
    if (reach > kReachPx) continue;
    if (const auto o = roster.owner(track.id()); o && o->target != t) continue;  // after the cheap test
    candidates.push_back(Candidate{track.id(), newest.centroid, reach});
  }
  if (candidates.size() < 4) return std::nullopt;
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.reach < b.reach; });
  if (candidates.size() > kMaxCandidates) candidates.resize(kMaxCandidates);

  const Target& target = f.targets.targets[t];
  std::optional<Reassociation> found;
  const int n = int(candidates.size());
  std::array<int, 4> pick{};
  for (pick[0] = 0; pick[0] < n; ++pick[0])
    for (pick[1] = 0; pick[1] < n; ++pick[1]) {
      if (pick[1] == pick[0]) continue;
      for (pick[2] = 0; pick[2] < n; ++pick[2]) {
        if (pick[2] == pick[0] || pick[2] == pick[1]) continue;
        for (pick[3] = 0; pick[3] < n; ++pick[3]) {
          if (pick[3] == pick[0] || pick[3] == pick[1] || pick[3] == pick[2]) continue;
          Eigen::Vector2d mean = Eigen::Vector2d::Zero();
          for (size_t m = 0; m < 4; ++m) mean += candidates[size_t(pick[m])].pixel - predicted[m];
          mean /= 4;
          bool together = true;
          for (size_t m = 0; m < 4 && together; ++m)
            together = (candidates[size_t(pick[m])].pixel - predicted[m] - mean).norm() <= tolerance;
          if (!together) continue;
          std::vector<SeenMarker> seen;
          for (int m = 0; m < 4; ++m) seen.push_back(SeenMarker{m, candidates[size_t(pick[size_t(m)])].pixel});
          auto pose = solve_marker_pose(f.camera, target, seen, tt.predicted, options);
          if (!pose || pose->used.size() != 4 || !(pose->rms_px <= options.max_rms_px) ||
              pose_distance(pose->pose, *tt.predicted) > max_distance)
            continue;
          if (found) return std::nullopt;  // two assignments fit: nothing is known
          found = Reassociation{};
          for (size_t m = 0; m < 4; ++m) found->tracks[m] = candidates[size_t(pick[m])].track;
          found->pose = *pose;
        }
      }
    }
  return found;
}

}  // namespace tetrapulse::localizer_internal

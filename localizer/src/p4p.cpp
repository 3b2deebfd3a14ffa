#include "tetrapulse/localizer/p4p.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {
namespace {

// The bearings as a camera saw them: observed pixels when a camera is given and
// every bearing projects (then errors are measured in pixels too).
struct Observations {
  const Bearing4& x;
  const CameraModel* camera = nullptr;
  std::array<Eigen::Vector2d, 4> px;

  Observations(const Bearing4& bearings, const CameraModel* cam) : x(bearings) {
    if (!cam) return;
    for (int i = 0; i < 4; ++i)
      if (!cam->project(x[i], &px[i])) return;
    camera = cam;
  }

  // Error of bearing i explained by target point X under `pose`: angle and, with a
  // camera, pixels. False when X is behind the camera or does not project.
  // rad may be null (the angle is not computed then).
  bool error(const Pose& pose, int i, const Eigen::Vector3d& X, double* rad, double* pixels) const {
    const Eigen::Vector3d y = pose.apply(X);
    const double along = y.dot(x[i]);
    if (!(along > 0)) return false;
    if (rad) *rad = std::atan2(y.cross(x[i]).norm(), along);
    if (!camera) return true;
    Eigen::Vector2d predicted;
    if (!camera->project(y, &predicted)) return false;
    *pixels = (predicted - px[i]).norm();
    return true;
  }
};

// The bearing to leave out of P3P: the other three are the furthest from coplanar
// (coplanar bearings put the camera in the markers' plane, P3P's degenerate case).
int check_bearing(const Bearing4& x) {
  int best = 3;
  double best_volume = -1;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d& a = x[(k + 1) % 4];
    const Eigen::Vector3d& b = x[(k + 2) % 4];
    const Eigen::Vector3d& c = x[(k + 3) % 4];
    const double volume = std::abs(a.dot(b.cross(c)));
    if (volume > best_volume) best_volume = volume, best = k;
  }
  return best;
}

bool same_pose(const Pose& a, const Pose& b) {
  return rotation_angle_between(a.R, b.R) < 1e-9 && (a.t - b.t).norm() < 1e-9 * (1 + b.t.norm());
}

}  // namespace

double P4PIdentification::margin() const {
  if (candidates.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (candidates.size() == 1) return std::numeric_limits<double>::infinity();
  return candidates[1].error(in_pixels) - candidates[0].error(in_pixels);
}

bool P4PIdentification::unambiguous(double max_error, double min_margin) const {
  return !candidates.empty() && candidates[0].error(in_pixels) <= max_error && margin() >= min_margin;
}

namespace {

// Known correspondence: of the poses P3P gives for each triple, the one with the
// smallest RMS error over all four bearings (pixels when the observations have them).
// A root is weighed on its left-out bearing first (the triple fits it exactly) and
// dropped when that error alone is no better than the best so far or max_cost (a
// sum of squares); its other errors are summed in bearing order, so the result is
// that of weighing every root on all four.
std::optional<P4PSolution> best_of_triples(const Observations& obs, const Point4& X, P3PSolver solver,
                                           double max_cost = std::numeric_limits<double>::infinity()) {
  const Bearing4& x = obs.x;
  const bool pixels = obs.camera != nullptr;
  std::optional<P4PSolution> best;
  double best_cost = max_cost;
  for (int left_out = 0; left_out < 4; ++left_out) {
    const int a = (left_out + 1) % 4, b = (left_out + 2) % 4, c = (left_out + 3) % 4;
    PoseCandidates poses;
    const int n = solve_p3p(solver, {x[a], x[b], x[c]}, {X[a], X[b], X[c]}, &poses);
    for (int k = 0; k < n; ++k) {
      std::array<double, 4> err{};
      double rad = 0;
      if (!obs.error(poses[k], left_out, X[left_out], pixels ? nullptr : &rad, &err[size_t(left_out)])) continue;
      if (!pixels) err[size_t(left_out)] = rad;
      if (!(err[size_t(left_out)] * err[size_t(left_out)] < best_cost)) continue;
      bool explained = true;
      for (int i = 0; i < 4 && explained; ++i) {
        if (i == left_out) continue;
        explained = obs.error(poses[k], i, X[i], pixels ? nullptr : &rad, &err[size_t(i)]);
        if (!pixels) err[size_t(i)] = rad;
      }
      if (!explained) continue;
      double cost = 0;
      for (double e : err) cost += e * e;
      if (cost < best_cost) {
        best_cost = cost;
        best = P4PSolution{poses[k], 0, std::numeric_limits<double>::quiet_NaN()};
      }
    }
  }
  if (!best) return best;
  // The angles of the chosen pose (in pixels only the chosen one needs them).
  double sum_rad = 0, sum_px = 0;
  for (int i = 0; i < 4; ++i) {
    double rad = 0, px = 0;
    obs.error(best->pose, i, X[i], &rad, &px);
    sum_rad += rad * rad;
    sum_px += px * px;
  }
  best->rms_error_rad = std::sqrt(sum_rad / 4);
  if (pixels) best->rms_error_px = std::sqrt(sum_px / 4);
  return best;
}

// The paper's ranking: P3P on a fixed triple, the check bearing's error.
void rank_by_check_bearing(const Bearing4& x, const Point4& X, const Observations& obs, P3PSolver solver,
                           std::vector<P4PHypothesis>* candidates) {
  const int d = check_bearing(x);
  const Bearing3 triple{x[(d + 1) % 4], x[(d + 2) % 4], x[(d + 3) % 4]};
  std::array<int, 4> perm{0, 1, 2, 3};  // perm[k]: marker seen by the k-th bearing after d
  do {
    const Point3x3 markers{X[perm[0]], X[perm[1]], X[perm[2]]};
    PoseCandidates poses;
    const int n = solve_p3p(solver, triple, markers, &poses);
    const size_t first_of_perm = candidates->size();
    for (int k = 0; k < n; ++k) {
      P4PHypothesis h;
      h.pose = poses[k];
      for (int j = 0; j < 3; ++j) h.marker_of[(d + 1 + j) % 4] = perm[j];
      h.marker_of[d] = perm[3];
      // The check bearing must be explained; the other three must be in front too.
      double px = 0;
      bool in_front = true;
      for (int j = 0; j < 4 && in_front; ++j)
        if (j != d) in_front = h.pose.apply(X[h.marker_of[j]]).dot(x[j]) > 0;
      if (!in_front || !obs.error(h.pose, d, X[perm[3]], &h.error_rad, &px)) continue;
      if (obs.camera) h.error_px = px;
      // A double root of P3P is one hypothesis, not two.
      bool duplicate = false;
      for (size_t j = first_of_perm; j < candidates->size() && !duplicate; ++j)
        duplicate = same_pose((*candidates)[j].pose, h.pose);
      if (!duplicate) candidates->push_back(h);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
}

void rank_by_best_triple(const Point4& X, const Observations& obs, P3PSolver solver,
                         std::vector<P4PHypothesis>* candidates) {
  std::array<int, 4> perm{0, 1, 2, 3};  // bearing i sees marker perm[i]
  do {
    const Point4 markers{X[perm[0]], X[perm[1]], X[perm[2]], X[perm[3]]};
    const auto solution = best_of_triples(obs, markers, solver);
    if (!solution) continue;
    candidates->push_back(P4PHypothesis{solution->pose, perm, solution->rms_error_rad, solution->rms_error_px});
  } while (std::next_permutation(perm.begin(), perm.end()));
}

}  // namespace

P4PIdentification identify_p4p(const Bearing4& x, const Point4& X, const P4POptions& options) {
  const Observations obs(x, options.camera);
  P4PIdentification result;
  result.in_pixels = obs.camera != nullptr;
  if (options.ranking == P4PRanking::kCheckBearing) {
    rank_by_check_bearing(x, X, obs, options.solver, &result.candidates);
  } else {
    rank_by_best_triple(X, obs, options.solver, &result.candidates);
  }
  const bool in_pixels = result.in_pixels;
  std::stable_sort(result.candidates.begin(), result.candidates.end(),
                   [in_pixels](const P4PHypothesis& a, const P4PHypothesis& b) {
                     return a.error(in_pixels) < b.error(in_pixels);
                   });
  return result;
}

std::optional<P4PSolution> solve_p4p(const Bearing4& x, const Point4& X, const P4POptions& options,
                                     double max_rms) {
  const Observations obs(x, options.camera);
  // Bounds the sum of four squares just above max_rms's, so that the caller's own
  // test of rms <= max_rms decides the boundary.
  const double max_cost = std::isfinite(max_rms) ? 4 * max_rms * max_rms * (1 + 1e-9)
                                                 : std::numeric_limits<double>::infinity();
  return best_of_triples(obs, X, options.solver, max_cost);
}

}  // namespace tetrapulse

#include "tetrapulse/localizer/pose_predictor.hpp"

#include <algorithm>
#include <array>

namespace tetrapulse {

const char* prediction_model_name(PredictionModel model) {
  return model == PredictionModel::kLinearRegression ? "regression" : "kalman";
}

PosePredictor::PosePredictor(PredictionOptions options) : options_(options), kalman_(options.kalman) {
  options_.regression_poses = std::clamp(options_.regression_poses, 1, kMaxRegressionPoses);
}

void PosePredictor::reset() {
  history_.clear();
  kalman_.reset();
  newest_ns_ = 0;
}

void PosePredictor::add(int64_t t_ns, const Pose& pose, double position_sigma_m, double rotation_sigma_rad) {
  if (!history_.empty() && t_ns <= newest_ns_) reset();
  history_.push(Stamped{t_ns, pose});
  newest_ns_ = t_ns;
  if (options_.model == PredictionModel::kConstantVelocity) {
    kalman_.update(t_ns, pose, position_sigma_m, rotation_sigma_rad);
  }
}

std::optional<Pose> PosePredictor::predict(int64_t t_ns) const {
  if (history_.empty() || t_ns - newest_ns_ > options_.max_extrapolation_ns) return std::nullopt;
  if (options_.model == PredictionModel::kConstantVelocity) return kalman_.predict(t_ns);
  return regress(t_ns);
}

Pose PosePredictor::regress(int64_t t_ns) const {
  const size_t n = std::min(history_.size(), size_t(options_.regression_poses));
  const Stamped& newest = history_.newest();
  if (n == 1) return newest.pose;
  // Least-squares lines in time (seconds from the newest pose, for conditioning)
  // through the translations and the rotation vectors relative to the newest.
  const size_t first = history_.size() - n;
  double mean_tau = 0;
  Eigen::Vector3d mean_t = Eigen::Vector3d::Zero(), mean_w = Eigen::Vector3d::Zero();
  std::array<double, kMaxRegressionPoses> tau{};
  std::array<Eigen::Vector3d, kMaxRegressionPoses> w;
  for (size_t i = 0; i < n; ++i) {
    const Stamped& s = history_[first + i];
    tau[i] = double(s.t_ns - newest.t_ns) * 1e-9;
    w[i] = so3_log(s.pose.R * newest.pose.R.transpose());
    mean_tau += tau[i];
    mean_t += s.pose.t;
    mean_w += w[i];
  }
  mean_tau /= double(n);
  mean_t /= double(n);
  mean_w /= double(n);
  double stt = 0;
  Eigen::Vector3d slope_t = Eigen::Vector3d::Zero(), slope_w = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const double d = tau[i] - mean_tau;
    stt += d * d;
    slope_t += d * (history_[first + i].pose.t - mean_t);
    slope_w += d * (w[i] - mean_w);
  }
  if (!(stt > 0)) return newest.pose;
  slope_t /= stt;
  slope_w /= stt;
  const double at = double(t_ns - newest.t_ns) * 1e-9 - mean_tau;
  return Pose{so3_exp(mean_w + at * slope_w) * newest.pose.R, mean_t + at * slope_t};
}

}  // namespace tetrapulse

#pragma once
// A target's pose at a coming exposure, predicted from the poses measured so far
// (Breitenmoser et al. 2011, Sec. IV-A). Poses as in pose.hpp (p_C = R p_T + t,
// metres, OpenCV camera frame); times in integer nanoseconds of rig time, the
// middle of each exposure.
//
//   kLinearRegression (the paper's): least-squares lines through the last k_R
//     translations and rotation vectors, each rotation taken relative to the
//     newest (R_i = exp([w_i]x) R_newest), evaluated at the asked time. k_R = 2
//     extrapolates the last motion; larger k_R smooths it.
//   kConstantVelocity: a Kalman filter on position, velocity, rotation and
//     angular velocity with white-noise acceleration (constant_velocity_kalman.hpp).
#include <cstdint>
#include <optional>

#include "tetrapulse/localizer/constant_velocity_kalman.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/ring_buffer.hpp"

namespace tetrapulse {

enum class PredictionModel { kLinearRegression, kConstantVelocity };
const char* prediction_model_name(PredictionModel model);

struct PredictionOptions {
  PredictionModel model = PredictionModel::kLinearRegression;
  int regression_poses = 2;  // k_R, 1..kMaxRegressionPoses (1: the last pose, held)
  KalmanNoise kalman;        // kConstantVelocity only
  // A prediction further than this from the newest pose is not made (the target
  // was lost for too long for any motion model), ns.
  int64_t max_extrapolation_ns = 300'000'000;
};

class PosePredictor {
 public:
  static constexpr int kMaxRegressionPoses = 16;

  PosePredictor() : PosePredictor(PredictionOptions{}) {}
  explicit PosePredictor(PredictionOptions options);

  // A measured pose at rig time t_ns (later than the previous one; an earlier or
  // equal time restarts the history). `position_sigma_m`, `rotation_sigma_rad`:
  // the measurement's standard deviations, used by the Kalman filter only.
  void add(int64_t t_ns, const Pose& pose, double position_sigma_m = 0.002, double rotation_sigma_rad = 0.005);
  void reset();

  // The pose at rig time t_ns; nullopt without history, or when t_ns lies more
  // than max_extrapolation_ns after the newest pose.
  std::optional<Pose> predict(int64_t t_ns) const;

  int64_t newest_ns() const { return newest_ns_; }
  size_t poses() const { return history_.size(); }

 private:
  struct Stamped {
    int64_t t_ns = 0;
    Pose pose;
  };
  Pose regress(int64_t t_ns) const;

  PredictionOptions options_;
  RingBuffer<Stamped, kMaxRegressionPoses> history_;
  ConstantVelocityKalman kalman_;
  int64_t newest_ns_ = 0;
};

}  // namespace tetrapulse

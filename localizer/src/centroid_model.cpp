#include "centroid_model.hpp"

#include <algorithm>

#include "tetrapulse/localizer/pose_refinement.hpp"

namespace tetrapulse::localizer_internal {

CentroidModel::CentroidModel(bool sphere) : sphere_(sphere), decided_(!sphere) {}

void CentroidModel::weigh(const CameraModel& camera, const Target& target, const std::vector<SeenMarker>& seen,
                          const Pose& pose, double rms_px, double sigma_px) {
  if (decided_ || target.marker_diameter_m <= 0 || seen.size() < 4) return;
  observations_.clear();
  for (const SeenMarker& s : seen) observations_.push_back({target.markers[size_t(s.marker)].position_m, s.pixel});
  // The current model's fit is the pose's own; only the other one is refined.
  const int current = sphere_ ? 0 : 1, other = 1 - current;
  double ssr[2];
  ssr[current] = rms_px * rms_px * double(observations_.size());
  RefinementOptions o;
  o.marker_diameter_m = target.marker_diameter_m;
  o.sphere_centroid = other == 0;
  o.sigma_px = sigma_px;
  o.covariance = false;  // only its residual is weighed
  const auto refined = refine_pose(camera, observations_, pose, o);
  if (!refined) return;  // a marker out of view under the other model: not a pose to weigh
  ssr[other] = refined->rms_px * refined->rms_px * double(observations_.size());
  ssr_[0] += ssr[0];
  ssr_[1] += ssr[1];
  if (++poses_ < kMinPoses) return;
  const double sigma2 = std::max(std::min(ssr_[0], ssr_[1]) / (2.0 * poses_), 1e-12);
  const double evidence = (ssr_[0] - ssr_[1]) / sigma2;
  if (evidence > kEvidence) {
    decided_ = true;
    sphere_ = false;
  } else if (evidence < -kEvidence || poses_ >= kMaxPoses) {
    decided_ = true;
  }
}

}  // namespace tetrapulse::localizer_internal

#pragma once
// Internal to Localizer: what a marker's blob centroid is the image of. A diffusing
// sphere lit all over images as the centroid of its silhouette (sphere_image.hpp);
// a small LED die, a flat disc facing the camera or a renderer that draws a spot at
// the projected centre images as the projection of its centre. targets.yaml gives
// the diameter but not which of the two a rig shows, and guessing wrong biases the
// centroids by up to 0.3 px at the corners of a wide lens. So clean four-marker
// poses are refined under both models, summing their squared residuals S_sphere
// and S_centre (pixels^2). Both models have the same parameters, so twice their
// log-likelihood ratio under Gaussian centroid noise is
//   D = (S_sphere - S_centre) / sigma^2,  sigma^2 = min(S) / dof,  dof = 2 per pose
// (8 coordinates, 6 pose parameters). A sequential test (Wald's): from
// kMinPoses poses on (sigma known well enough), the centre model is taken when
// D > kEvidence, the sphere model kept when D < -kEvidence (odds of e^5, about
// 150 to 1, either way); at kMaxPoses without a verdict the sphere model, the
// physics of a diffusing ball, stays. Most of a model's bias is absorbed by the
// pose, so the sums differ by a few per cent: 3 cm spheres at 1 m with 0.05 px
// noise need some hundred poses. The decision is made once and held (a model
// that changed back and forth would make the poses jump by its bias).
#include <vector>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/marker_pose.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse::localizer_internal {

class CentroidModel {
 public:
  static constexpr int kMinPoses = 100;
  static constexpr int kMaxPoses = 1000;
  static constexpr double kEvidence = 10;  // D, twice the log-likelihood ratio

  // sphere: the model to start with (LocalizerOptions' sphere_centroid); false
  // decides at once (nothing to weigh).
  explicit CentroidModel(bool sphere);

  bool sphere() const { return sphere_; }
  bool decided() const { return decided_; }

  // Weighs a pose of all four markers of `target` seen at `seen`: `pose` and its
  // RMS residual `rms_px` are their refinement under the current model (as
  // refine_pose gives it with centroid noise `sigma_px`), the other model is
  // refined from there. Poses of targets without a diameter are ignored.
  void weigh(const CameraModel& camera, const Target& target, const std::vector<SeenMarker>& seen, const Pose& pose,
             double rms_px, double sigma_px);

  // Summed squared residuals so far (pixels^2), for the summary and tests.
  double sphere_ssr() const { return ssr_[0]; }
  double centre_ssr() const { return ssr_[1]; }

 private:
  bool sphere_;
  bool decided_;
  int poses_ = 0;
  double ssr_[2] = {0, 0};  // sphere, centre
  std::vector<MarkerObservation> observations_;
};

}  // namespace tetrapulse::localizer_internal

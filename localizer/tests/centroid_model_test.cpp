// The centroid model is decided by the images: centroids rendered as the projections
// of the markers' centres switch it to the centre model, sphere images keep the
// sphere model, and the decision waits for enough poses.
#include "../src/centroid_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/sphere_image.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

using localizer_internal::CentroidModel;

enum class Centroids { kCentres, kSphereImages };

// Four-marker views of a 3 cm-marker target at 0.5-1.2 m across the wide camera,
// centroids with 0.05 px noise, weighed until the model decides (at most `poses`).
CentroidModel weigh_views(Centroids kind, int poses, int* weighed, uint64_t seed = 7) {
  const CameraModel camera(testing::wide_plumb_bob_camera());
  const Target target = testing::hardware_target("paper-large.yaml");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 0.05);
  CentroidModel model(true);
  *weighed = 0;
  while (*weighed < poses && !model.decided()) {
    const Pose pose = testing::random_visible_pose(rng, camera, target, 0.5, 1.2, 20);
    std::vector<SeenMarker> seen;
    for (int m = 0; m < 4; ++m) {
      const Eigen::Vector3d p = pose.R * target.markers[size_t(m)].position_m + pose.t;
      Eigen::Vector2d px;
      const bool ok = kind == Centroids::kCentres
                          ? camera.project(p, &px)
                          : sphere_image_centroid(camera, p, target.marker_diameter_m / 2, &px);
      if (!ok) {
        ADD_FAILURE() << "marker " << m << " out of view";
        return model;
      }
      seen.push_back({m, px + Eigen::Vector2d(noise(rng), noise(rng))});
    }
    // As the localizer does: the pose refined under the current model, then weighed.
    std::vector<MarkerObservation> observations;
    for (const SeenMarker& s : seen) observations.push_back({target.markers[size_t(s.marker)].position_m, s.pixel});
    RefinementOptions o;
    o.marker_diameter_m = target.marker_diameter_m;
    o.sphere_centroid = model.sphere();
    o.sigma_px = 0.05;
    const auto refined = refine_pose(camera, observations, pose, o);
    if (!refined) {
      ADD_FAILURE() << "refinement failed: " << refined.error().message;
      return model;
    }
    model.weigh(camera, target, seen, refined->pose, refined->rms_px, 0.05);
    ++*weighed;
  }
  std::printf("[measure] %s: %d poses weighed, residual sums sphere %.3f centre %.3f px^2 -> %s\n",
              kind == Centroids::kCentres ? "centre projections" : "sphere images", *weighed, model.sphere_ssr(),
              model.centre_ssr(), model.sphere() ? "sphere" : "centre");
  return model;
}

TEST(CentroidModel, CentreProjectionsSwitchToTheCentreModel) {
  int weighed = 0;
  const CentroidModel model = weigh_views(Centroids::kCentres, 1000, &weighed);
  EXPECT_TRUE(model.decided());
  EXPECT_LT(weighed, CentroidModel::kMaxPoses);
  EXPECT_FALSE(model.sphere());
}

TEST(CentroidModel, SphereImagesKeepTheSphereModel) {
  int weighed = 0;
  const CentroidModel model = weigh_views(Centroids::kSphereImages, 1000, &weighed);
  EXPECT_TRUE(model.decided());
  EXPECT_TRUE(model.sphere());
  EXPECT_LT(model.sphere_ssr(), model.centre_ssr());
}

TEST(CentroidModel, DecidesRightOnEveryOneOfFortyRigs) {
  int right = 0, most = 0;
  for (uint64_t seed = 100; seed < 120; ++seed) {
    int weighed = 0;
    right += !weigh_views(Centroids::kCentres, 2000, &weighed, seed).sphere();
    most = std::max(most, weighed);
    right += weigh_views(Centroids::kSphereImages, 2000, &weighed, seed).sphere();
    most = std::max(most, weighed);
  }
  std::printf("[measure] %d of 40 rigs decided right, after at most %d poses\n", right, most);
  EXPECT_EQ(right, 40);
}

TEST(CentroidModel, UndecidedBeforeEnoughPoses) {
  int weighed = 0;
  const CentroidModel model = weigh_views(Centroids::kCentres, CentroidModel::kMinPoses - 1, &weighed);
  EXPECT_FALSE(model.decided());
  EXPECT_TRUE(model.sphere()) << "the model does not change before it is decided";
}

TEST(CentroidModel, StartingWithTheCentreModelNeedsNoDecision) {
  const CentroidModel model(false);
  EXPECT_TRUE(model.decided());
  EXPECT_FALSE(model.sphere());
}

}  // namespace
}  // namespace tetrapulse

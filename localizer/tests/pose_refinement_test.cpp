// Pose refinement on the paper's large target seen by both camera models: convergence,
// covariance against Monte Carlo, the minimal three-marker case, Huber's loss, and
// the sphere-image measurement model.
#include "tetrapulse/localizer/pose_refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <fmt/format.h>

#include "tetrapulse/localizer/sphere_image.hpp"
#include "tetrapulse/localizer/testing/p3p_problems.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

using testing::hardware_target;
using testing::observe;
using testing::pose_error;
using testing::random_visible_pose;

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

std::vector<MarkerObservation> observations(const Target& target, const std::array<Eigen::Vector2d, 4>& px) {
  std::vector<MarkerObservation> obs;
  for (int i = 0; i < 4; ++i) obs.push_back({target.markers[i].position_m, px[i]});
  return obs;
}

// The pose moved by a random rotation of `angle` rad about the target origin and a
// random translation of `fraction` of its distance.
Pose perturbed(std::mt19937_64& rng, const Pose& pose, double angle, double fraction) {
  std::normal_distribution<double> g;
  const Eigen::Vector3d axis = Eigen::Vector3d{g(rng), g(rng), g(rng)}.normalized();
  const Eigen::Vector3d shift = Eigen::Vector3d{g(rng), g(rng), g(rng)}.normalized();
  return Pose{so3_exp(angle * axis) * pose.R, pose.t + fraction * pose.t.norm() * shift};
}

// (w, v) with estimate = (exp([w]x) R, t + v) of the truth: the refinement's parameters.
Vector6 perturbation(const Pose& estimate, const Pose& truth) {
  const Eigen::AngleAxisd aa(estimate.R * truth.R.transpose());
  Vector6 d;
  d << aa.angle() * aa.axis(), estimate.t - truth.t;
  return d;
}

std::string fmt_ratio(const Vector6& r) {
  return fmt::format("{:.2f} {:.2f} {:.2f} | {:.2f} {:.2f} {:.2f}", r(0), r(1), r(2), r(3), r(4), r(5));
}

class PoseRefinement : public ::testing::TestWithParam<CameraInfo> {
 protected:
  CameraModel camera_{GetParam()};
  Target target_ = hardware_target("paper-large.yaml");
};

TEST_P(PoseRefinement, ConvergesToTheTruePoseFromPerturbedStarts) {
  std::mt19937_64 rng(41);
  for (const auto& [angle_deg, fraction] : {std::pair{5.0, 0.05}, std::pair{20.0, 0.2}}) {
    int failed = 0, iterations = 0;
    const int trials = 500;
    for (int i = 0; i < trials; ++i) {
      const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 4.0, 2.0);
      const auto obs = observations(target_, observe(rng, camera_, target_, truth, 0.0));
      const Pose start = perturbed(rng, truth, angle_deg * M_PI / 180, fraction);
      const auto refined = refine_pose(camera_, obs, start);
      if (!refined) {
        ++failed;  // a start that puts a marker out of the model's field
        continue;
      }
      iterations += refined->iterations;
      failed += !(refined->converged && pose_error(refined->pose, truth) < 1e-8 && refined->rms_px < 1e-6);
    }
    std::printf("%s, start %.0f deg / %.0f %% off: %d of %d not converged to 1e-8, %.1f iterations on average\n",
                GetParam().name.c_str(), angle_deg, 100 * fraction, failed, trials, double(iterations) / trials);
    EXPECT_LE(failed, angle_deg < 10 ? 0 : trials / 50);
  }
}

TEST_P(PoseRefinement, WithoutTheCovarianceGivesTheSamePoseAndResidual) {
  std::mt19937_64 rng(43);
  RefinementOptions with;
  with.marker_diameter_m = 0.03;
  RefinementOptions without = with;
  without.covariance = false;
  for (int i = 0; i < 50; ++i) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 4.0, 2.0);
    const auto obs = observations(target_, observe(rng, camera_, target_, truth, 0.1));
    const Pose start = perturbed(rng, truth, 5 * M_PI / 180, 0.05);
    const auto a = refine_pose(camera_, obs, start, with);
    const auto b = refine_pose(camera_, obs, start, without);
    ASSERT_EQ(bool(a), bool(b));
    if (!a) continue;
    EXPECT_TRUE(a->has_covariance);
    EXPECT_FALSE(b->has_covariance);
    EXPECT_EQ(a->pose.R, b->pose.R);
    EXPECT_EQ(a->pose.t, b->pose.t);
    EXPECT_EQ(a->rms_px, b->rms_px);
    EXPECT_EQ(a->sigma_px, b->sigma_px);
    EXPECT_EQ(a->iterations, b->iterations);
  }
}

TEST_P(PoseRefinement, CovarianceIsSigmaSquaredTimesTheInverseNormalMatrix) {
  // Exact views, sigma given: the covariance is sigma^2 (J^T J)^-1, J the derivative of
  // the four projections by (w, v), here by central differences.
  std::mt19937_64 rng(7);
  const double sigma = 0.3, h = 1e-6;
  for (int pose_index = 0; pose_index < 20; ++pose_index) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 4.0, 20.0);
    std::array<Eigen::Vector2d, 4> exact;
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(camera_.project(truth.apply(target_.markers[i].position_m), &exact[i]));
    RefinementOptions options;
    options.sigma_px = sigma;
    const auto refined = refine_pose(camera_, observations(target_, exact), truth, options);
    ASSERT_TRUE(refined && refined->has_covariance);
    const auto projections = [&](const Vector6& d) {
      const Pose p{so3_exp(d.head<3>()) * refined->pose.R, refined->pose.t + d.tail<3>()};
      Eigen::Matrix<double, 8, 1> out;
      for (int i = 0; i < 4; ++i) {
        Eigen::Vector2d px;
        EXPECT_TRUE(camera_.project(p.apply(target_.markers[i].position_m), &px));
        out.segment<2>(2 * i) = px;
      }
      return out;
    };
    Eigen::Matrix<double, 8, 6> J;
    for (int k = 0; k < 6; ++k) {
      const Vector6 d = h * Vector6::Unit(k);
      J.col(k) = (projections(d) - projections(-d)) / (2 * h);
    }
    const Matrix6 expected = sigma * sigma * (J.transpose() * J).inverse();
    EXPECT_LE((refined->covariance - expected).norm(), 1e-5 * expected.norm()) << "pose " << pose_index;
    EXPECT_EQ(refined->covariance, refined->covariance.transpose()) << "pose " << pose_index;
  }
}

TEST_P(PoseRefinement, CovarianceAgreesWithMonteCarlo) {
  // 1000 noisy views of each of three poses; the empirical covariance of the refined
  // (w, v) against the predicted sigma^2 (J^T J)^-1, sigma given and sigma estimated.
  std::mt19937_64 rng(42);
  const double sigma = 0.5;
  const int trials = 1000;
  for (int pose_index = 0; pose_index < 3; ++pose_index) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.8, 2.0, 20.0);
    Matrix6 empirical = Matrix6::Zero(), predicted_given = Matrix6::Zero(), predicted_estimated = Matrix6::Zero();
    for (int i = 0; i < trials; ++i) {
      const auto obs = observations(target_, observe(rng, camera_, target_, truth, sigma));
      RefinementOptions given;
      given.sigma_px = sigma;
      const auto a = refine_pose(camera_, obs, truth, given);
      const auto b = refine_pose(camera_, obs, truth);
      ASSERT_TRUE(a && b && a->has_covariance && b->has_covariance);
      const Vector6 d = perturbation(a->pose, truth);
      empirical += d * d.transpose() / trials;
      predicted_given += a->covariance / trials;
      predicted_estimated += b->covariance / trials;
    }
    const Vector6 ratio_given = empirical.diagonal().cwiseQuotient(predicted_given.diagonal());
    const Vector6 ratio_estimated = empirical.diagonal().cwiseQuotient(predicted_estimated.diagonal());
    std::printf("%s, pose %d: empirical/predicted variance, sigma given [%s], estimated [%s]\n",
                GetParam().name.c_str(), pose_index, fmt_ratio(ratio_given).c_str(), fmt_ratio(ratio_estimated).c_str());
    for (int k = 0; k < 6; ++k) {
      EXPECT_NEAR(ratio_given(k), 1.0, 0.2) << "parameter " << k;
      EXPECT_NEAR(ratio_estimated(k), 1.0, 0.2) << "parameter " << k;
    }
  }
}

TEST_P(PoseRefinement, TwoMergedMarkersAreOneObservationOfTheirLightsCentroid) {
  // Markers 2 and 3 merged into one blob whose centroid is the flux-weighted mean
  // of their projections (share 0.35 of marker 3): with markers 0 and 1 the pose
  // is exact, and from 5 degrees off it converges to it. Treating the blob as
  // marker 2's centroid instead would be off.
  std::mt19937_64 rng(45);
  int failed = 0, biased = 0;
  const int trials = 300;
  for (int i = 0; i < trials; ++i) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 4.0, 2.0);
    const auto px = observe(rng, camera_, target_, truth, 0.0);
    const double share = 0.35;
    std::vector<MarkerObservation> obs = {{target_.markers[0].position_m, px[0]},
                                          {target_.markers[1].position_m, px[1]}};
    obs.push_back({target_.markers[2].position_m, (1 - share) * px[2] + share * px[3], target_.markers[3].position_m,
                   share});
    const Pose start = perturbed(rng, truth, 5 * M_PI / 180, 0.05);
    const auto refined = refine_pose(camera_, obs, start);
    failed += !(refined && pose_error(refined->pose, truth) < 1e-7);
    std::vector<MarkerObservation> naive = obs;
    naive[2].partner_share = 0;
    const auto wrong = refine_pose(camera_, naive, truth);
    biased += wrong && pose_error(wrong->pose, truth) > 1e-4;
  }
  EXPECT_LE(failed, trials / 100);
  EXPECT_GE(biased, trials * 9 / 10);
}

TEST_P(PoseRefinement, ThreeMarkersConvergeToTheTruePose) {
  // Three markers: six residuals for six unknowns. Noise-free, the fit is exact.
  std::mt19937_64 rng(43);
  int failed = 0;
  const int trials = 500;
  for (int i = 0; i < trials; ++i) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 3.0, 2.0);
    auto obs = observations(target_, observe(rng, camera_, target_, truth, 0.0));
    obs.erase(obs.begin() + i % 4);
    const auto refined = refine_pose(camera_, obs, perturbed(rng, truth, 0.02, 0.01));
    ASSERT_TRUE(refined.has_value());
    failed += !(refined->converged && refined->rms_px < 1e-6 && pose_error(refined->pose, truth) < 1e-8);
  }
  std::printf("%s, three markers: %d of %d not converged to the true pose\n", GetParam().name.c_str(), failed,
              trials);
  EXPECT_LE(failed, trials / 100);
}

TEST_P(PoseRefinement, ThreeMarkersHaveACovarianceOnlyWithAGivenSigma) {
  // No redundancy to estimate sigma from: the covariance needs it given. (Near the
  // danger cylinder noise can leave three markers without an exact fit; the least-
  // squares pose then sits where J^T J is singular and has no covariance at all.)
  std::mt19937_64 rng(47);
  int exact = 0;
  for (int i = 0; i < 100; ++i) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 3.0, 2.0);
    auto obs = observations(target_, observe(rng, camera_, target_, truth, 0.3));
    obs.pop_back();
    const auto estimated = refine_pose(camera_, obs, truth);
    ASSERT_TRUE(estimated.has_value());
    EXPECT_FALSE(estimated->has_covariance);
    RefinementOptions given;
    given.sigma_px = 0.3;
    const auto with_sigma = refine_pose(camera_, obs, truth, given);
    ASSERT_TRUE(with_sigma.has_value());
    if (with_sigma->rms_px < 1e-6) {
      ++exact;
      EXPECT_TRUE(with_sigma->has_covariance);
      EXPECT_EQ(with_sigma->sigma_px, 0.3);
    }
  }
  EXPECT_GE(exact, 90);
}

TEST_P(PoseRefinement, SphereCentroidModelRemovesTheSilhouetteBias) {
  // Blobs are the centroids of 3 cm spheres' images; refining with the sphere model
  // recovers the pose exactly, refining on centre projections does not.
  std::mt19937_64 rng(44);
  const double radius = 0.015;
  double worst_with = 0, worst_pose_with = 0, mean_without = 0, mean_bias_mm = 0, worst_bias_mm = 0;
  const int trials = 200;
  for (int i = 0; i < trials; ++i) {
    const Pose truth = random_visible_pose(rng, camera_, target_, 0.5, 1.5, 10.0);
    std::vector<MarkerObservation> obs;
    for (const Marker& m : target_.markers) {
      Eigen::Vector2d px;
      ASSERT_TRUE(sphere_image_centroid(camera_, truth.apply(m.position_m), radius, &px, 64));
      obs.push_back({m.position_m, px});
    }
    RefinementOptions with;
    with.marker_diameter_m = 2 * radius;
    RefinementOptions without = with;
    without.sphere_centroid = false;
    const auto a = refine_pose(camera_, obs, truth, with);
    const auto b = refine_pose(camera_, obs, truth, without);
    ASSERT_TRUE(a && b);
    EXPECT_TRUE(a->converged) << a->iterations << " iterations, rms " << a->rms_px << " initial " << a->initial_rms_px;
    worst_with = std::max(worst_with, a->rms_px);
    worst_pose_with = std::max(worst_pose_with, pose_error(a->pose, truth));
    mean_without += b->rms_px / trials;
    const double bias_mm = 1000 * (b->pose.t - truth.t).norm();
    mean_bias_mm += bias_mm / trials;
    worst_bias_mm = std::max(worst_bias_mm, bias_mm);
  }
  std::printf("%s: sphere model RMS <= %.1e px, pose error <= %.1e; centre model RMS %.3f px, "
              "position bias %.2f mm on average, %.2f mm at worst (0.5-1.5 m)\n",
              GetParam().name.c_str(), worst_with, worst_pose_with, mean_without, mean_bias_mm, worst_bias_mm);
  EXPECT_LT(worst_with, 1e-4);
  EXPECT_LT(worst_pose_with, 1e-6);
  EXPECT_GT(worst_bias_mm, 100 * 1000 * worst_pose_with);  // the model matters
}

TEST(PoseRefinementLoss, HuberDownweightsAnOutlier) {
  // Six markers (the paper's four and two more), 0.2 px noise, one blob 15 px off.
  const CameraModel camera(testing::wide_plumb_bob_camera());
  Target target = hardware_target("paper-large.yaml");
  std::vector<Eigen::Vector3d> points;
  for (const Marker& m : target.markers) points.push_back(m.position_m);
  points.push_back({0.1, 0.1, 0.1});
  points.push_back({-0.1, -0.05, 0.2});
  std::mt19937_64 rng(45);
  std::normal_distribution<double> noise(0.0, 0.2);
  int huber_better = 0;
  const int trials = 300;
  for (int i = 0; i < trials; ++i) {
    const Pose truth = random_visible_pose(rng, camera, target, 0.8, 2.0, 20.0);
    std::vector<MarkerObservation> obs;
    for (const auto& X : points) {
      Eigen::Vector2d px;
      ASSERT_TRUE(camera.project(truth.apply(X), &px));
      obs.push_back({X, px + Eigen::Vector2d{noise(rng), noise(rng)}});
    }
    obs[i % obs.size()].pixel += Eigen::Vector2d(15.0 * std::cos(i), 15.0 * std::sin(i));
    RefinementOptions huber;
    huber.huber_px = 1.0;
    const auto plain = refine_pose(camera, obs, truth);
    const auto robust = refine_pose(camera, obs, truth, huber);
    ASSERT_TRUE(plain && robust);
    EXPECT_TRUE(robust->converged) << robust->iterations << " iterations, rms " << robust->rms_px;
    huber_better += pose_error(robust->pose, truth) < pose_error(plain->pose, truth);
  }
  std::printf("Huber (1 px) closer to the truth than least squares in %d of %d trials\n", huber_better, trials);
  EXPECT_GE(huber_better, trials * 9 / 10);
}

TEST(PoseRefinementInput, BadInputIsAnErrorNamingTheMarker) {
  const CameraModel camera(testing::wide_plumb_bob_camera());
  const Target target = hardware_target("paper-large.yaml");
  const Pose truth{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 2)};
  std::mt19937_64 rng(46);
  auto obs = observations(target, observe(rng, camera, target, truth, 0.0));

  const std::vector<MarkerObservation> two(obs.begin(), obs.begin() + 2);
  const auto too_few = refine_pose(camera, two, truth);
  ASSERT_FALSE(too_few);
  EXPECT_EQ(too_few.error().kind, RefinementError::Kind::kTooFewMarkers);

  auto nan = obs;
  nan[2].pixel.x() = NAN;
  const auto not_finite = refine_pose(camera, nan, truth);
  ASSERT_FALSE(not_finite);
  EXPECT_EQ(not_finite.error().kind, RefinementError::Kind::kNotFinite);
  EXPECT_NE(not_finite.error().message.find("marker 2"), std::string::npos) << not_finite.error().message;

  const Pose behind{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -2)};
  const auto not_in_view = refine_pose(camera, obs, behind);
  ASSERT_FALSE(not_in_view);
  EXPECT_EQ(not_in_view.error().kind, RefinementError::Kind::kNotInView);
  EXPECT_NE(not_in_view.error().message.find("marker 0"), std::string::npos) << not_in_view.error().message;
}

INSTANTIATE_TEST_SUITE_P(Cameras, PoseRefinement,
                         ::testing::Values(testing::wide_plumb_bob_camera(), testing::fisheye_camera()),
                         [](const ::testing::TestParamInfo<CameraInfo>& camera) { return camera.param.name; });

}  // namespace
}  // namespace tetrapulse

// Per-solve time of the P3P solvers (ours and OpenCV's) on the same pre-generated
// triples, and of identification and refinement for one four-marker target.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "tetrapulse/localizer/p3p_kneip.hpp"
#include "tetrapulse/localizer/p3p_lambda_twist.hpp"
#include "tetrapulse/localizer/p4p.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/testing/p3p_problems.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

constexpr int kProblems = 1024;  // cycled through (about 250 kB: in L2), the same for every solver

// Well-conditioned triples (p3p_problems.hpp), and the same as OpenCV takes them:
// object points, and image points as normalized coordinates x/z (K = identity).
struct P3PInputs {
  std::vector<testing::P3PProblem> problems;
  std::vector<std::vector<cv::Point3d>> object;
  std::vector<std::vector<cv::Point2d>> image;

  P3PInputs() {
    std::mt19937_64 rng(2024);
    for (int i = 0; i < kProblems; ++i) {
      const auto p = testing::random_p3p_problem(rng, testing::P3PCondition::kWell);
      problems.push_back(p);
      object.emplace_back();
      image.emplace_back();
      for (int k = 0; k < 3; ++k) {
        object.back().emplace_back(p.X[k].x(), p.X[k].y(), p.X[k].z());
        image.back().emplace_back(p.x[k].x() / p.x[k].z(), p.x[k].y() / p.x[k].z());
      }
    }
  }
};

const P3PInputs& p3p_inputs() {
  static const P3PInputs inputs;
  return inputs;
}

template <int (*Solve)(const Bearing3&, const Point3x3&, PoseCandidates*)>
void BM_P3P(benchmark::State& state) {
  const auto& in = p3p_inputs();
  PoseCandidates poses;
  size_t i = 0;
  for (auto _ : state) {
    const auto& p = in.problems[i++ % kProblems];
    benchmark::DoNotOptimize(Solve(p.x, p.X, &poses));
    benchmark::ClobberMemory();
  }
}
BENCHMARK_TEMPLATE(BM_P3P, p3p_kneip)->Name("P3P/kneip");
BENCHMARK_TEMPLATE(BM_P3P, p3p_lambda_twist)->Name("P3P/lambda_twist");

// cv::solveP3P on the same triples. Its time includes input checks and copies,
// undistortPoints with K = identity, a Rodrigues conversion per pose and the
// allocation of its output Mats.
void BM_OpenCvSolveP3P(benchmark::State& state) {
  const auto& in = p3p_inputs();
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const int flags = int(state.range(0));
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ % kProblems;
    benchmark::DoNotOptimize(cv::solveP3P(in.object[k], in.image[k], K, cv::noArray(), rvecs, tvecs, flags));
  }
}
BENCHMARK(BM_OpenCvSolveP3P)->Name("P3P/opencv_ap3p")->Arg(cv::SOLVEPNP_AP3P);
BENCHMARK(BM_OpenCvSolveP3P)->Name("P3P/opencv_p3p")->Arg(cv::SOLVEPNP_P3P);

// One four-marker target: the paper's large target, 0.5-4 m from the wide plumb_bob
// camera, 0.3 px blob noise.
struct TargetViews {
  CameraModel camera{testing::wide_plumb_bob_camera()};
  Target target = testing::hardware_target("paper-large.yaml");
  std::vector<Bearing4> bearings;
  std::vector<std::vector<MarkerObservation>> observations;
  std::vector<Pose> truths;

  TargetViews() {
    std::mt19937_64 rng(2025);
    for (int i = 0; i < 512; ++i) {
      const Pose truth = testing::random_visible_pose(rng, camera, target, 0.5, 4.0, 2.0);
      const auto px = testing::observe(rng, camera, target, truth, 0.3);
      Bearing4 x;
      std::vector<MarkerObservation> obs;
      for (int k = 0; k < 4; ++k) {
        camera.unproject(px[k], &x[k]);
        obs.push_back({target.markers[k].position_m, px[k]});
      }
      bearings.push_back(x);
      observations.push_back(obs);
      truths.push_back(truth);
    }
  }
  Point4 points() const {
    Point4 X;
    for (int k = 0; k < 4; ++k) X[k] = target.markers[k].position_m;
    return X;
  }
};

const TargetViews& target_views() {
  static const TargetViews views;
  return views;
}

void BM_IdentifyP4P(benchmark::State& state) {
  const auto& v = target_views();
  const Point4 X = v.points();
  const P4POptions options{kDefaultP3PSolver, &v.camera, P4PRanking(state.range(0))};
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(identify_p4p(v.bearings[i++ % v.bearings.size()], X, options));
}
BENCHMARK(BM_IdentifyP4P)->Name("P4P/identify_best_triple")->Arg(int(P4PRanking::kBestTriple));
BENCHMARK(BM_IdentifyP4P)->Name("P4P/identify_check_bearing")->Arg(int(P4PRanking::kCheckBearing));

void BM_SolveP4P(benchmark::State& state) {
  const auto& v = target_views();
  const Point4 X = v.points();
  const P4POptions options{kDefaultP3PSolver, &v.camera};
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(solve_p4p(v.bearings[i++ % v.bearings.size()], X, options));
}
BENCHMARK(BM_SolveP4P)->Name("P4P/known_order");

// Refinement of 4 markers from the known-order P4P pose (as the pipeline runs it),
// with centre projections or with the sphere-image model (3 cm markers).
void BM_RefinePose(benchmark::State& state) {
  const auto& v = target_views();
  const Point4 X = v.points();
  std::vector<Pose> starts;
  for (const auto& x : v.bearings) starts.push_back(solve_p4p(x, X, {kDefaultP3PSolver, &v.camera})->pose);
  RefinementOptions options;
  options.marker_diameter_m = 0.03;
  options.sphere_centroid = state.range(0) != 0;
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ % starts.size();
    benchmark::DoNotOptimize(refine_pose(v.camera, v.observations[k], starts[k], options));
  }
}
BENCHMARK(BM_RefinePose)->Name("refine_pose/4_markers_centre")->Arg(0);
BENCHMARK(BM_RefinePose)->Name("refine_pose/4_markers_sphere")->Arg(1);

}  // namespace
}  // namespace tetrapulse

BENCHMARK_MAIN();

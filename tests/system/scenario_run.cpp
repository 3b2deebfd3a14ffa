#include "scenario_run.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <unistd.h>

#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/target_appearance.hpp"
#include "tetrapulse/datasets/frame_source.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"
#include "tetrapulse/sim/dataset_simulation.hpp"

namespace tetrapulse::system_testing {

namespace {

namespace fs = std::filesystem;

PoseErrors errors_of(const Pose& pose, const Pose& truth) {
  return PoseErrors{(pose.t - truth.t).norm(), rotation_angle_between(truth.R, pose.R)};
}

// A folder that is removed when it goes out of scope.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const std::string& stem) {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() / (stem + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string path() const { return path_.string(); }

 private:
  fs::path path_;
};

// The oracle's pose from blobs with true correspondences (see scenario_run.hpp).
std::optional<Pose> oracle_pose(const CameraModel& camera, const Target& target, const Pose& truth,
                                const std::vector<Blob>& blobs) {
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  std::vector<char> taken(blobs.size(), 0);
  const bool fisheye = camera.info().model == DistortionModel::kEquidistant;
  for (const Marker& marker : target.markers) {
    const Eigen::Vector3d p = truth.apply(marker.position_m);
    Eigen::Vector2d px;
    if (!camera.project(p, &px)) continue;
    const double radius = camera.info().fx * target.marker_diameter_m / 2 / p.norm();
    int nearest = -1;
    double best = std::max(3.0, radius);
    for (size_t b = 0; b < blobs.size(); ++b) {
      const double d = (blobs[b].centroid - px).norm();
      if (!taken[b] && d < best) best = d, nearest = int(b);
    }
    if (nearest < 0) continue;
    taken[size_t(nearest)] = 1;
    const Eigen::Vector2d& c = blobs[size_t(nearest)].centroid;
    if (fisheye) {
      // OpenCV's solvePnP has no fisheye model: normalized image points instead.
      Eigen::Vector3d bearing;
      if (!camera.unproject(c, &bearing) || bearing.z() <= 0) continue;
      image.emplace_back(bearing.x() / bearing.z(), bearing.y() / bearing.z());
    } else {
      image.emplace_back(c.x(), c.y());
    }
    object.emplace_back(marker.position_m.x(), marker.position_m.y(), marker.position_m.z());
  }
  if (object.size() < 3) return std::nullopt;
  const CameraInfo& info = camera.info();
  cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist = cv::Mat::zeros(1, 5, CV_64F);
  if (!fisheye) {
    K.at<double>(0, 0) = info.fx, K.at<double>(1, 1) = info.fy;
    K.at<double>(0, 2) = info.cx, K.at<double>(1, 2) = info.cy;
    for (int i = 0; i < 5; ++i) dist.at<double>(0, i) = info.distortion[size_t(i)];
  }
  cv::Mat rvec, tvec;
  try {
    if (object.size() == 3) {
      // Three markers have up to four poses: the oracle starts at the true one.
      cv::Mat R;
      cv::eigen2cv(Eigen::Matrix3d(truth.R), R);
      cv::Rodrigues(R, rvec);
      tvec = (cv::Mat_<double>(3, 1) << truth.t.x(), truth.t.y(), truth.t.z());
      if (!cv::solvePnP(object, image, K, dist, rvec, tvec, true, cv::SOLVEPNP_ITERATIVE)) return std::nullopt;
    } else {
      if (!cv::solvePnP(object, image, K, dist, rvec, tvec, false, cv::SOLVEPNP_SQPNP)) return std::nullopt;
      cv::solvePnPRefineLM(object, image, K, dist, rvec, tvec);
    }
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
  cv::Mat R;
  cv::Rodrigues(rvec, R);
  Pose pose;
  cv::cv2eigen(R, pose.R);
  pose.t = Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return pose;
}

}  // namespace

tl::expected<ScenarioRun, std::string> run_scenario(const sim::Scenario& scenario, uint64_t seed, int64_t frames,
                                                    const LocalizerOptions& options) {
  TemporaryFolder folder("tp_system_" + scenario.name);
  sim::SimulationOptions sim_options;
  sim_options.out = folder.path();
  sim_options.seed = seed;
  sim_options.frames = frames;
  if (auto s = sim::simulate_dataset(scenario, sim_options); !s) return tl::unexpected(s.error().what());
  auto dataset = RigDataset::open(folder.path());
  if (!dataset) return tl::unexpected(dataset.error().what());

  ScenarioRun run;
  run.scenario = scenario;
  run.frames = dataset->frames();
  run.frame_period_ns = scenario.frames.period_ns;
  for (const Target& t : scenario.targets.targets)
    for (const Marker& m : t.markers)
      if (m.code && scenario.targets.modulation.kind != ModulationKind::kConstant) {
        const int64_t length_ns = int64_t(m.code->length) * scenario.targets.timebase.bit_period_ns;
        run.code_length_frames = std::max(run.code_length_frames, (length_ns + run.frame_period_ns - 1) / run.frame_period_ns);
      }

  Localizer localizer(dataset->camera(), dataset->targets(), options);
  auto source = dataset_frames(*dataset);
  auto localized = localize_frames(*source, localizer, [&](const Frame& f, const std::vector<TargetPose>& poses) {
    for (const TargetPose& p : poses) {
      PoseRecord r;
      r.frame = f.frame;
      r.timestamp_ns = p.mid_exposure_ns;
      r.target = p.target_id;
      r.pose = PoseFields::from(p.pose);
      r.markers = p.markers;
      r.reprojection_px = p.rms_px;
      run.poses.push_back(r);
    }
    return DatasetResult<void>{};
  });
  if (!localized) return tl::unexpected(localized.error().what());
  if (localized->skipped > 0) return tl::unexpected(std::to_string(localized->skipped) + " frames could not be localized");
  // The simulation knows the free-running boards' clocks: coverage then counts the
  // frames whose markers are truly lit.
  EvaluationOptions evaluation_options;
  evaluation_options.board_clocks = sim::free_running_code_clocks(scenario);
  auto evaluation = evaluate_poses(*dataset, run.poses, "poses", evaluation_options);
  if (!evaluation) return tl::unexpected(evaluation.error().what());
  run.evaluation = *evaluation;

  std::map<std::pair<int64_t, int>, Pose> truth;
  for (const GroundTruthRecord& g : dataset->groundtruth()) truth[{g.frame, g.target}] = g.pose.pose();
  for (const PoseRecord& p : run.poses) {
    const auto it = truth.find({p.frame, p.target});
    if (it != truth.end()) run.localizer_errors[it->first] = errors_of(p.pose.pose(), it->second);
  }

  // The oracle, frame by frame.
  const CameraModel camera(dataset->camera());
  // The extractors the localizer uses for these targets (one per look: light, dark, a colour).
  const RigLooks looks = rig_looks(BlobExtractorConfig{}, dataset->targets());
  std::vector<BlobExtractor> extractors(looks.configs.begin(), looks.configs.end());
  std::vector<BlobExtraction> extractions(extractors.size());
  std::vector<Blob> blobs;
  for (size_t i = 0; i < run.frames.size(); ++i) {
    auto image = dataset->load_image(i);
    if (!image) return tl::unexpected(image.error().what());
    for (size_t l = 0; l < extractors.size(); ++l)
      if (auto r = extractors[l].extract(*image, 0, &extractions[l]); !r) return tl::unexpected(r.error().message);
    const auto& targets = dataset->targets().targets;
    for (size_t t = 0; t < targets.size(); ++t) {
      const auto it = truth.find({run.frames[i].frame, targets[t].id});
      if (it == truth.end()) continue;
      // The blobs of the looks this target's markers have.
      blobs.clear();
      for (size_t l = 0; l < extractors.size(); ++l) {
        const auto& of = looks.look_of[t];
        if (std::find(of.begin(), of.end(), int(l)) == of.end()) continue;
        blobs.insert(blobs.end(), extractions[l].blobs.begin(), extractions[l].blobs.end());
      }
      if (const auto pose = oracle_pose(camera, targets[t], it->second, blobs)) {
        run.oracle_errors[it->first] = errors_of(*pose, it->second);
      }
    }
  }
  return run;
}

sim::Scenario only_targets(sim::Scenario scenario, const std::vector<int>& ids) {
  std::vector<Target> targets;
  std::vector<sim::TargetSimulation> simulation;
  for (size_t t = 0; t < scenario.targets.targets.size(); ++t)
    if (std::find(ids.begin(), ids.end(), scenario.targets.targets[t].id) != ids.end()) {
      targets.push_back(scenario.targets.targets[t]);
      simulation.push_back(scenario.simulation[t]);
    }
  scenario.targets.targets = targets;
  scenario.simulation = simulation;
  return scenario;
}

OracleComparison compare_with_oracle(const ScenarioRun& run) {
  OracleComparison c;
  for (const auto& [key, mine] : run.localizer_errors) {
    const auto it = run.oracle_errors.find(key);
    if (it == run.oracle_errors.end()) continue;
    ++c.pairs;
    c.localizer.position_m += mine.position_m, c.localizer.orientation_rad += mine.orientation_rad;
    c.oracle.position_m += it->second.position_m, c.oracle.orientation_rad += it->second.orientation_rad;
  }
  if (c.pairs > 0) {
    const double n = double(c.pairs);
    c.localizer.position_m /= n, c.localizer.orientation_rad /= n;
    c.oracle.position_m /= n, c.oracle.orientation_rad /= n;
  }
  return c;
}

}  // namespace tetrapulse::system_testing

#include "tetrapulse/localizer/localizer.hpp"

#include "tetrapulse/localizer/target_appearance.hpp"

#include <fmt/format.h>

#include "code_checks.hpp"
#include "code_reading.hpp"
#include "frame_blobs.hpp"
#include "marker_tracks.hpp"
#include "new_targets.hpp"
#include "roi_planner.hpp"
#include "target_poses.hpp"
#include "target_roster.hpp"

namespace tetrapulse {

using namespace localizer_internal;

namespace {

IdentificationOptions identification_options(const LocalizerOptions& o) {
  IdentificationOptions id = o.identification;
  id.solver = o.p3p;
  return id;
}

TargetPoseOptions pose_options(const LocalizerOptions& o) {
  TargetPoseOptions p;
  p.pose = o.pose;
  p.pose.solver = o.p3p;
  p.max_outlier_frames = o.max_outlier_frames;
  p.forget_after_ns = o.forget_after_ns;
  return p;
}

CodeCheckOptions check_options(const LocalizerOptions& o) {
  CodeCheckOptions c;
  c.verify_samples = o.verify_samples;
  c.verify_max_errors = o.verify_max_errors;
  c.frequency_check_frames = o.frequency_check_frames;
  c.clock_samples = std::max(o.identification.max_samples, o.verify_samples);
  return c;
}

bool any_frequency_code(const std::vector<RigCode>& codes) {
  for (const RigCode& c : codes)
    if (c.frequency) return true;
  return false;
}

}  // namespace

// The stages of a frame, in the order process() runs them.
struct Localizer::State {
  State(const CameraInfo& info, const TargetsFile& file, const LocalizerOptions& opts)
      : camera(info),
        targets(file),
        options(opts),
        rig(rig_codes(targets)),
        frequency_coded(any_frequency_code(rig)),
        roster(camera, targets, options.prediction, options.min_roi_radius_px),
        looks(rig_looks(options.blobs, targets)),
        colour(std::any_of(looks.configs.begin(), looks.configs.end(),
                           [](const BlobExtractorConfig& c) { return c.colour.has_value(); })),
        blobs(looks, options.full_search_interval),
        reading(targets, options.bits, options.frequency,
                std::max(options.identification.max_samples, options.verify_samples), frequency_coded),
        checks(targets, frequency_code_of(targets, rig), check_options(options)),
        new_targets(camera, targets, identification_options(options), frequency_coded),
        poses(pose_options(options)),
        centroids(options.pose.sphere_centroid) {}

  tl::expected<std::vector<TargetPose>, LocalizerError> process(const cv::Mat& image, int64_t start, int64_t exposure);
  tl::expected<void, LocalizerError> check_frame(const cv::Mat& image, int64_t start, int64_t exposure) const;
  // Once the frame period is known (the second frame): how long tracks coast and searches last.
  void learn_frame_period(int64_t start, int64_t exposure);

  CameraModel camera;
  TargetsFile targets;
  LocalizerOptions options;
  std::vector<RigCode> rig;  // the rig's distinct codes (frequency_identifier.hpp)
  bool frequency_coded;      // some marker plays a frequency code
  TargetRoster roster;
  RoiPlan plan;
  // How the markers look, from targets.yaml: one extractor per look.
  RigLooks looks;
  bool colour;  // some look is a colour: frames must be in colour
  FrameBlobs blobs;
  BlobTracker tracker;
  CodeReading reading;
  CodeChecks checks;
  NewTargets new_targets;
  TargetPoseOptions poses;
  CentroidModel centroids;
  ExposureStamp stamp;
  int64_t frames = 0;
  int64_t previous_start = 0;
  int64_t frame_period_ns = 0;  // 0 until the second frame
};

tl::expected<void, LocalizerError> Localizer::State::check_frame(const cv::Mat& image, int64_t start,
                                                                int64_t exposure) const {
  if (colour && (image.channels() != 3 || image.depth() != CV_8U)) {
    return tl::unexpected(LocalizerError{"targets.yaml gives the markers a colour: frames must be 8-bit colour"});
  }
  if (image.cols != camera.width() || image.rows != camera.height()) {
    return tl::unexpected(LocalizerError{
        fmt::format("image is {}x{}, the camera {}x{}", image.cols, image.rows, camera.width(), camera.height())});
  }
  if (exposure <= 0) return tl::unexpected(LocalizerError{fmt::format("exposure of {} ns is not positive", exposure)});
  if (frames > 0 && start <= previous_start) {
    return tl::unexpected(LocalizerError{
        fmt::format("exposure starts at {} ns, not after the previous frame's {} ns", start, previous_start)});
  }
  return {};
}

void Localizer::State::learn_frame_period(int64_t start, int64_t exposure) {
  frame_period_ns = start - previous_start;
  // On-off codes darken a marker for a run of 0 bits: its track must outlive it.
  tracker.set_max_coast_frames(
      std::max(tracker.config().max_coast_frames, coast_frames_for(targets, frame_period_ns, exposure)));
  blobs.set_search_burst(search_burst_frames(targets, frame_period_ns, exposure));
}

tl::expected<std::vector<TargetPose>, LocalizerError> Localizer::State::process(const cv::Mat& image, int64_t start,
                                                                                int64_t exposure) {
  if (auto ok = check_frame(image, start, exposure); !ok) return tl::unexpected(ok.error());
  if (frames == 1) learn_frame_period(start, exposure);
  stamp = ExposureStamp{frames, start, exposure};
  const int64_t mid = stamp.middle_ns();

  // 1. Prediction: each identified target's pose at mid-exposure, and where to look.
  roster.predict(mid);
  plan_rois(roster, tracker, camera, mid, frame_period_ns, options.min_roi_radius_px, &plan);
  // 2. Blobs, with the whole image searched while something is not tracked.
  const bool coded = targets.modulation.kind != ModulationKind::kConstant;
  if (auto r = blobs.extract(image, plan, roster.needs_search(), !coded); !r)
    return tl::unexpected(LocalizerError{r.error().message});
  // 3. Tracks, and the new ones that become markers of identified targets.
  tracker.update(stamp, blobs.extraction(), plan.gates);
  roster.drop_ended_tracks(tracker);
  claim_new_tracks(tracker, blobs.search_hits(), mid, frame_period_ns, &roster);
  // 4. Codes read from the tracks' light; 5. checked on the tracks identified targets own.
  reading.update(tracker, stamp.frame);
  checks.check(tracker, reading, stamp.frame, mid, &roster);
  // 6. New targets among the tracks nobody owns.
  new_targets.identify(tracker, reading, stamp, &roster);
  // 7. Poses.
  std::vector<TargetPose> out;
  for (size_t t = 0; t < roster.size(); ++t) {
    if (!roster[t].identified) continue;
    const PoseFrame frame{camera, targets, tracker, stamp, frame_period_ns};
    if (auto p = solve_target_pose(frame, t, checks.frequency_of(t), poses, &roster, &centroids)) out.push_back(*p);
  }
  previous_start = start;
  ++frames;
  return out;
}

Localizer::Localizer(const CameraInfo& camera, const TargetsFile& targets, LocalizerOptions options)
    : state_(std::make_unique<State>(camera, targets, options)) {}
Localizer::~Localizer() = default;
Localizer::Localizer(Localizer&&) noexcept = default;
Localizer& Localizer::operator=(Localizer&&) noexcept = default;

tl::expected<std::vector<TargetPose>, LocalizerError> Localizer::process(const cv::Mat& image,
                                                                         int64_t exposure_start_ns,
                                                                         int64_t exposure_ns) {
  return state_->process(image, exposure_start_ns, exposure_ns);
}

const CameraModel& Localizer::camera() const { return state_->camera; }
const TargetsFile& Localizer::targets() const { return state_->targets; }
const BlobExtraction& Localizer::extraction() const { return state_->blobs.extraction(); }
const BlobTracker& Localizer::tracker() const { return state_->tracker; }
bool Localizer::searched_whole_image() const { return state_->blobs.searched(); }

bool Localizer::measures_sphere_images() const { return state_->centroids.sphere(); }

std::vector<TrackLabel> Localizer::track_labels() const {
  std::vector<TrackLabel> out;
  for (const BlobTrack& track : state_->tracker.tracks()) {
    TrackLabel label;
    label.track_id = track.id();
    if (const auto o = state_->roster.owner(track.id())) {
      label.target_id = state_->targets.targets[o->target].id;
      label.marker = o->marker;
    }
    out.push_back(label);
  }
  return out;
}

std::optional<CodeClock> Localizer::clock_of(int target_id) const {
  for (size_t t = 0; t < state_->roster.size(); ++t) {
    if (state_->targets.targets[t].id != target_id || !state_->roster[t].identified) continue;
    return state_->roster[t].clock.estimated();
  }
  return std::nullopt;
}

}  // namespace tetrapulse

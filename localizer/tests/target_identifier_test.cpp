// Identification from blob tracks: codes within their error budget name targets
// and markers, geometry checks them, and an ambiguous hypothesis is never reported.
// The tracks come from the real BlobTracker fed with the markers' projected
// pixels and the light the contract says they emit during each exposure.
#include "tetrapulse/localizer/target_identifier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <optional>
#include <random>

#include "tetrapulse/localizer/p4p.hpp"
#include "tetrapulse/localizer/pose_refinement.hpp"
#include "tetrapulse/localizer/testing/target_views.hpp"

namespace tetrapulse {
namespace {

constexpr int64_t kFrameNs = 10'000'000;  // 100 fps, one frame per 10 ms bit
constexpr int64_t kExposureNs = 2'000'000;
constexpr int64_t kFirstStartNs = 4'000'000;  // exposures in the middle of the bits

Code code(const char* text) { return *parse_code(text, nullptr); }

// Two targets of the paper's geometry, each marker with its own 12-bit code
// (sim/scenarios/swarm.yaml's first two targets).
TargetsFile two_coded_targets(ModulationKind kind = ModulationKind::kTwoLevel) {
  TargetsFile f;
  f.timebase = Timebase{0, kFrameNs, true};
  f.modulation = Modulation{kind, kind == ModulationKind::kTwoLevel ? 0.3 : 0.0};
  const char* codes[2][4] = {{"010011100101", "011001001001", "100111110010", "010010010110"},
                             {"100110101100", "101101010110", "100101100110", "011100101010"}};
  for (int i = 0; i < 2; ++i) {
    Target t = testing::hardware_target("paper-large.yaml");
    t.id = 10 + i;
    for (int m = 0; m < 4; ++m) t.markers[size_t(m)].code = code(codes[i][m]);
    f.targets.push_back(t);
  }
  return f;
}

// What the camera shows: some targets at fixed poses, each with the board clock
// its LEDs follow; `flip` corrupts a marker's light in listed frames (a read error).
struct Shown {
  size_t target = 0;
  Pose pose;
  CodeClock clock;
  std::map<int, std::vector<int64_t>> flip;  // marker -> frames whose bit reads inverted
  int hidden = -1;                            // a marker in view that shows no light (occluded)
  double radius_scale = 1.0;                  // blob radius over the sphere's image radius
};

// Feeds frames [0, frames) to a tracker and asks the identifier after each one.
// Returns, per target index, the first frame it was identified and the
// identification then.
struct Watch {
  std::map<size_t, std::pair<int64_t, Identification>> first;
  std::map<int64_t, Eigen::Vector2d> track_pixel;  // newest blob of each track
  int identifications = 0;                         // all reported, also repeats
};

// unmeasured: tracks (by id) whose pixels are handed over as not measured this
// frame (as a dark track's prediction or a merged blob's part is).
Watch watch(const CameraModel& camera, const TargetsFile& targets, const std::vector<Shown>& shown, int frames,
        uint64_t seed, IdentificationOptions options = {}, const std::vector<int64_t>& unmeasured = {}) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, 1);
  BlobTracker tracker;
  TargetIdentifier identifier(camera, targets, options);
  std::map<int64_t, TrackBits> bits;
  Watch out;
  for (int k = 0; k < frames; ++k) {
    const ExposureStamp stamp{k, kFirstStartNs + k * kFrameNs, kExposureNs};
    BlobExtraction e;
    for (const Shown& s : shown) {
      const Target& target = targets.targets[s.target];
      for (int m = 0; m < 4; ++m) {
        if (m == s.hidden) continue;
        const Marker& marker = target.markers[size_t(m)];
        double level = mean_emission(s.clock, targets.modulation, marker.code, stamp.timestamp_ns, kExposureNs);
        const auto it = s.flip.find(m);
        if (it != s.flip.end() && std::count(it->second.begin(), it->second.end(), int64_t(k))) {
          level = level > 0.65 ? targets.modulation.low : 1.0;
        }
        if (!(level > 0)) continue;  // on_off: dark
        const Eigen::Vector3d p = s.pose.apply(marker.position_m);
        Blob b;
        if (!camera.project(p, &b.centroid) || !camera.in_image(b.centroid)) continue;  // out of view: no blob
        b.centroid += 0.1 * Eigen::Vector2d(noise(rng), noise(rng));
        b.radius = s.radius_scale * camera.info().fx * target.marker_diameter_m / 2 / p.norm();
        b.area = int(M_PI * b.radius * b.radius) + 1;
        b.intensity = 3000 * level * (1 + 0.02 * noise(rng));
        e.blobs.push_back(b);
      }
    }
    tracker.update(stamp, e);
    std::vector<CandidateTrack> candidates;
    for (const BlobTrack& track : tracker.tracks()) {
      read_track_bits(track.history(), targets.modulation, BitReading{}, 0, &bits[track.id()]);
      CandidateTrack c;
      c.track = &track;
      c.bits = &bits[track.id()];
      c.pixel = track.position();
      c.radius_px = track.last_blob().radius;
      c.measured = std::find(unmeasured.begin(), unmeasured.end(), track.id()) == unmeasured.end();
      candidates.push_back(c);
      out.track_pixel[track.id()] = track.position();
    }
    std::vector<bool> wanted(targets.targets.size());
    for (size_t t = 0; t < wanted.size(); ++t) wanted[t] = !out.first.count(t);
    for (const Identification& id : identifier.identify(candidates, wanted)) {
      ++out.identifications;
      if (!out.first.count(id.target)) out.first[id.target] = {k, id};
    }
  }
  return out;
}

// Whether each marker's track sits on that marker's pixel (the right correspondence).
void expect_correct(const CameraModel& camera, const TargetsFile& targets, const Shown& s, const Watch& r) {
  ASSERT_TRUE(r.first.count(s.target)) << "target " << s.target << " never identified";
  const Identification& id = r.first.at(s.target).second;
  for (int m = 0; m < 4; ++m) {
    Eigen::Vector2d px;
    ASSERT_TRUE(camera.project(s.pose.apply(targets.targets[s.target].markers[size_t(m)].position_m), &px));
    EXPECT_LT((r.track_pixel.at(id.track_of[size_t(m)]) - px).norm(), 1.0) << "marker " << m;
  }
  EXPECT_LT((id.pose.t - s.pose.t).norm(), 0.02);
}

// Two poses side by side, 1.2 m away, turned differently.
std::vector<Pose> two_poses() {
  return {Pose{so3_exp(Eigen::Vector3d(2.6, 0.2, 0.3)), Eigen::Vector3d(-0.35, 0.05, 1.2)},
          Pose{so3_exp(Eigen::Vector3d(2.9, -0.3, -0.9)), Eigen::Vector3d(0.35, -0.05, 1.3)}};
}

class Identify : public ::testing::Test {
 protected:
  CameraModel camera{testing::wide_plumb_bob_camera()};
};

TEST_F(Identify, SynchronizedCodesNameBothTargetsAndMarkersWithinOneCodeLength) {
  for (ModulationKind kind : {ModulationKind::kTwoLevel, ModulationKind::kOnOff}) {
    const TargetsFile targets = two_coded_targets(kind);
    const auto poses = two_poses();
    const CodeClock clock = CodeClock::from(targets.timebase);
    const std::vector<Shown> shown{{0, poses[0], clock, {}}, {1, poses[1], clock, {}}};
    const Watch r = watch(camera, targets, shown, 36, 1);
    for (const Shown& s : shown) {
      expect_correct(camera, targets, s, r);
      EXPECT_LE(r.first.at(s.target).first, 12) << modulation_name(kind);  // one code length, in frames
    }
  }
}

TEST_F(Identify, SameGeometryDifferentCodesNeverSwapped) {
  // Random poses of the two (geometrically identical) targets: every
  // identification names the right target and markers.
  std::mt19937_64 rng(7);
  const TargetsFile targets = two_coded_targets();
  const CodeClock clock = CodeClock::from(targets.timebase);
  for (int trial = 0; trial < 12; ++trial) {
    const size_t which = size_t(trial % 2);
    const Pose pose = testing::random_visible_pose(rng, camera, targets.targets[which], 0.7, 2.0, 20);
    const std::vector<Shown> shown{{which, pose, clock, {}}};
    const Watch r = watch(camera, targets, shown, 30, 100 + uint64_t(trial));
    EXPECT_FALSE(r.first.count(1 - which)) << trial;
    expect_correct(camera, targets, shown[0], r);
  }
}

TEST_F(Identify, AReadErrorWithinTheBudgetIsTolerated) {
  // One wrong bit on one marker: 1 error allowed per 16 bits read, so the
  // target is identified once enough bits are read, and correctly.
  const TargetsFile targets = two_coded_targets();
  const CodeClock clock = CodeClock::from(targets.timebase);
  const Shown s{0, two_poses()[0], clock, {{2, {4}}}};
  const Watch r = watch(camera, targets, {s}, 36, 2);
  expect_correct(camera, targets, s, r);
}

TEST_F(Identify, CodesBeyondTheirRadiusAreNotIdentified) {
  // The board plays the codes shifted by 5 bits (another phase of every code):
  // no target's codes fit within the error budget, so nothing is reported,
  // although the geometry is a perfect match.
  const TargetsFile targets = two_coded_targets();
  CodeClock shifted = CodeClock::from(targets.timebase);
  shifted.origin_ns += 5 * kFrameNs;
  const Watch r = watch(camera, targets, {{0, two_poses()[0], shifted, {}}}, 48, 3);
  EXPECT_EQ(r.identifications, 0);
}

TEST_F(Identify, APixelNotMeasuredThisFrameNeverDecidesGeometry) {
  // Two markers' pixels are never blobs of the frame (dark tracks' extrapolations,
  // merged blobs' parts: where a permutation of the markers can fit): the codes
  // fit, but the target waits. With one of them measured it is identified.
  const TargetsFile targets = two_coded_targets();
  const CodeClock clock = CodeClock::from(targets.timebase);
  const Shown s{0, two_poses()[0], clock, {}};
  const Watch seen = watch(camera, targets, {s}, 36, 5);
  expect_correct(camera, targets, s, seen);
  ASSERT_FALSE(seen.track_pixel.empty());
  std::vector<int64_t> ids;
  for (const auto& [id, px] : seen.track_pixel) ids.push_back(id);
  ASSERT_GE(ids.size(), 4u);
  const Watch unseen = watch(camera, targets, {s}, 36, 5, {}, {ids[0], ids[1]});
  EXPECT_EQ(unseen.identifications, 0);
  const Watch one_unseen = watch(camera, targets, {s}, 36, 5, {}, {ids[0]});
  expect_correct(camera, targets, s, one_unseen);
}

TEST_F(Identify, TwoTargetsAlikeInCodesAndGeometryAreNeverReported) {
  // Target 1 is a copy of target 0, codes included: whichever is shown, the
  // evidence cannot tell them apart, so neither is named.
  TargetsFile targets = two_coded_targets();
  targets.targets[1].markers = targets.targets[0].markers;
  const CodeClock clock = CodeClock::from(targets.timebase);
  const Watch r = watch(camera, targets, {{0, two_poses()[0], clock, {}}}, 48, 4);
  EXPECT_EQ(r.identifications, 0);
}

TEST_F(Identify, ConstantMarkersAreIdentifiedByGeometryAloneOrNotAtAll) {
  // Random views of one passive target: the permutation that fits names the
  // markers; where another permutation fits about as well (views in which the
  // geometry is ambiguous) nothing is reported, and that stays rare.
  TargetsFile targets = two_coded_targets(ModulationKind::kConstant);
  targets.targets.resize(1);
  std::mt19937_64 rng(11);
  int identified = 0;
  constexpr int kTrials = 40;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Pose pose = testing::random_visible_pose(rng, camera, targets.targets[0], 0.7, 2.0, 20);
    const Shown s{0, pose, CodeClock::from(targets.timebase), {}};
    const Watch r = watch(camera, targets, {s}, 2, 20 + uint64_t(trial));
    if (r.first.empty()) continue;
    ++identified;
    expect_correct(camera, targets, s, r);
  }
  EXPECT_GE(identified, kTrials * 3 / 4);
}

TEST_F(Identify, ConstantMarkersWhoseBlobsAreTooSmallForThePoseAreNotATarget) {
  // Four blobs of two passive targets can fit a third pose; their sizes then
  // disagree with it (the pose puts the spheres nearer than their blobs say).
  // Blobs of 0.6 the pose's image radius: nothing is named; of 1.6 (an LED's
  // halo, blooming): the target is, as with sizes that agree.
  TargetsFile targets = two_coded_targets(ModulationKind::kConstant);
  targets.targets.resize(1);
  const Pose pose = two_poses()[0];
  Shown small{0, pose, CodeClock::from(targets.timebase), {}};
  small.radius_scale = 0.6;
  EXPECT_EQ(watch(camera, targets, {small}, 4, 3).identifications, 0);
  Shown large = small;
  large.radius_scale = 1.6;
  expect_correct(camera, targets, large, watch(camera, targets, {large}, 4, 3));
  Shown exact = small;
  exact.radius_scale = 1.0;
  expect_correct(camera, targets, exact, watch(camera, targets, {exact}, 4, 3));
}

TEST_F(Identify, ConstantMarkersOfTwoTargetsAlikeAreNeverReported) {
  // Passive targets of the same geometry: geometry fits both equally.
  const TargetsFile targets = two_coded_targets(ModulationKind::kConstant);
  const Watch r = watch(camera, targets, {{0, two_poses()[0], CodeClock::from(targets.timebase), {}}}, 10, 5);
  EXPECT_EQ(r.identifications, 0);
}

TEST_F(Identify, FreeRunningBoardsPhaseIsFoundWithinThreeCodePeriods) {
  // Boards running free with unknown origins (and 150 ppm fast): identified,
  // correctly, with a clock whose bit edges agree with the board's.
  TargetsFile targets = two_coded_targets();
  targets.timebase.synchronized = false;
  const auto poses = two_poses();
  const CodeClock a{37'300'000, kFrameNs, 1 + 150e-6}, b{-81'700'000, kFrameNs, 1 - 120e-6};
  const std::vector<Shown> shown{{0, poses[0], a, {}}, {1, poses[1], b, {}}};
  const Watch r = watch(camera, targets, shown, 60, 6);
  for (const Shown& s : shown) {
    expect_correct(camera, targets, s, r);
    const auto& [frame, id] = r.first.at(s.target);
    EXPECT_LE(frame, 3 * 12);
    // Same bit number, modulo the code length, at this frame's mid-exposure.
    const int64_t mid = kFirstStartNs + frame * kFrameNs + kExposureNs / 2;
    EXPECT_EQ(((id.clock.bit_number(mid) - s.clock.bit_number(mid)) % 12 + 12) % 12, 0) << s.target;
  }
}

// The pose of `target` moved sideways from `start` until exactly one marker is
// out of view (its centre `out` image radii past the border) and the others
// `in` radii inside; which one is out is written to *missing.
std::optional<Pose> one_marker_out(const CameraModel& camera, const Target& target, Pose start, double out, double in,
                                   int* missing) {
  for (int step = 0; step < 400; ++step, start.t.x() -= 0.005) {
    int outside = 0, inside = 0;
    for (int m = 0; m < 4; ++m) {
      const Eigen::Vector3d p = start.apply(target.markers[size_t(m)].position_m);
      const double r = camera.info().fx * target.marker_diameter_m / 2 / p.norm();
      Eigen::Vector2d px;
      if (!camera.project(p, &px)) break;
      if (camera.in_image(px, in * r)) ++inside;
      if (!camera.in_image(px, -out * r)) ++outside, *missing = m;
    }
    if (outside == 1 && inside == 3) return start;
  }
  return std::nullopt;
}

// How far inside the border the outermost marker's centre lies, in its image
// radii (negative: outside); that marker goes to *which.
double least_margin(const CameraModel& camera, const Target& target, const Pose& pose, int* which) {
  double least = INFINITY;
  for (int m = 0; m < 4; ++m) {
    const Eigen::Vector3d p = pose.apply(target.markers[size_t(m)].position_m);
    const double r = camera.info().fx * target.marker_diameter_m / 2 / p.norm();
    Eigen::Vector2d px;
    if (!camera.project(p, &px)) return -INFINITY;
    const double inside = std::min({px.x() + 0.5, camera.width() - 0.5 - px.x(), px.y() + 0.5,
                                    camera.height() - 0.5 - px.y()}) / r;
    if (inside < least) least = inside, *which = m;
  }
  return least;
}

TEST_F(Identify, AMarkerOutOfViewLeavesThreeThatNameTheTarget) {
  // One marker past the image's border (a drone at the edge of the view): each
  // marker's own code names the three tracks, the one P3P root that puts the
  // fourth marker out of view gives the pose; the missing marker has no track.
  for (ModulationKind kind : {ModulationKind::kTwoLevel, ModulationKind::kOnOff}) {
    const TargetsFile targets = two_coded_targets(kind);
    int missing = -1;
    const auto pose = one_marker_out(camera, targets.targets[0], two_poses()[0], 2, 2, &missing);
    ASSERT_TRUE(pose);
    const Shown s{0, *pose, CodeClock::from(targets.timebase), {}};
    const Watch r = watch(camera, targets, {s}, 36, 8);
    ASSERT_TRUE(r.first.count(0)) << modulation_name(kind);
    const auto& [frame, id] = r.first.at(0);
    // Three tracks read three quarters of four's bits a frame (measured: frame 8
    // two_level, 16 on_off).
    EXPECT_LE(frame, 12 * 4 / 3 + IdentificationOptions{}.min_edge_frames) << modulation_name(kind);
    EXPECT_EQ(id.track_of[size_t(missing)], -1);
    for (int m = 0; m < 4; ++m) {
      if (m == missing) continue;
      Eigen::Vector2d px;
      ASSERT_TRUE(camera.project(pose->apply(targets.targets[0].markers[size_t(m)].position_m), &px));
      ASSERT_TRUE(r.track_pixel.count(id.track_of[size_t(m)])) << m;
      EXPECT_LT((r.track_pixel.at(id.track_of[size_t(m)]) - px).norm(), 1.0) << "marker " << m;
    }
    EXPECT_LT((id.pose.t - pose->t).norm(), 0.02);
    // Without the three-track pass nothing is found.
    IdentificationOptions four_only;
    four_only.edge_identification = false;
    EXPECT_EQ(watch(camera, targets, {s}, 36, 8, four_only).identifications, 0);
  }
}

// A view of `target` whose best wrong assignment of its four exact pixels fits
// at an RMS within [low, high] px (p4p.hpp, refined as the identifier does).
std::optional<Pose> view_with_rival(const CameraModel& camera, const Target& target, double low, double high,
                                    uint64_t seed) {
  std::mt19937_64 rng(seed);
  Point4 X;
  for (size_t m = 0; m < 4; ++m) X[m] = target.markers[m].position_m;
  for (int trial = 0; trial < 20000; ++trial) {
    const Pose pose = testing::random_visible_pose(rng, camera, target, 0.8, 2.5, 20);
    Bearing4 x;
    bool ok = true;
    for (size_t m = 0; m < 4; ++m) {
      Eigen::Vector2d px;
      ok = ok && camera.project(pose.apply(X[m]), &px) && camera.unproject(px, &x[m]);
    }
    if (!ok) continue;
    const P4PIdentification found = identify_p4p(x, X, {kDefaultP3PSolver, &camera});
    if (found.candidates.size() < 2 || !found.in_pixels) continue;
    // As the identifier weighs it: refined from its P4P pose (centre projections).
    const P4PHypothesis& c = found.candidates[1];
    std::vector<MarkerObservation> observations;
    for (size_t i = 0; i < 4; ++i) {
      Eigen::Vector2d px;
      camera.project(pose.apply(X[i]), &px);
      observations.push_back({X[size_t(c.marker_of[i])], px});
    }
    RefinementOptions refine;
    refine.max_iterations = 10;
    refine.sphere_centroid = false;
    const auto refined = refine_pose(camera, observations, c.pose, refine);
    const double rival = refined ? std::min(refined->rms_px, c.error_px) : c.error_px;
    if (rival >= low && rival <= high) return pose;
  }
  return std::nullopt;
}

TEST_F(Identify, ARivalAssignmentThatFitsFarWorseIsRefutedInItsFirstFrame) {
  // A code per target (all four markers play it: the codes name the target,
  // geometry its markers). Where a wrong assignment fits at 0.8-0.95 px against
  // 0.1 px noise (drones of crowd-on-off: 0.86-0.98 px), it is refuted in the frame the codes are read far enough, as
  // for a view with no rival; one at 0.15-0.25 px is weighed over
  // min_geometry_frames frames first (two frames later).
  TargetsFile targets = two_coded_targets();
  targets.targets.resize(1);
  for (Marker& m : targets.targets[0].markers) m.code = targets.targets[0].markers[0].code;
  const Target& target = targets.targets[0];
  const CodeClock clock = CodeClock::from(targets.timebase);
  const auto first_frame = [&](const Pose& pose) {
    const Watch r = watch(camera, targets, {Shown{0, pose, clock, {}}}, 30, 5);
    expect_correct(camera, targets, Shown{0, pose, clock, {}}, r);
    return r.first.count(0) ? r.first.at(0).first : int64_t(-1);
  };
  const auto clear = view_with_rival(camera, target, 3.0, 1e9, 1);
  const auto far = view_with_rival(camera, target, 0.8, 0.95, 2);
  const auto close = view_with_rival(camera, target, 0.15, 0.25, 3);
  ASSERT_TRUE(clear && far && close);
  const int64_t without_rival = first_frame(*clear);
  ASSERT_GE(without_rival, 0);
  EXPECT_EQ(first_frame(*far), without_rival);
  EXPECT_EQ(first_frame(*close), without_rival + 2);
}

TEST_F(Identify, ThreeMarkersOfOneCodeAreNeverNamedWrongly) {
  // All four markers play one code (a code per target): the codes cannot say
  // which three are in view, and several assignments usually put the fourth out
  // of view: the target waits, and is never named wrongly (random views moved
  // to the border).
  TargetsFile targets = two_coded_targets();
  targets.targets.resize(1);
  for (Marker& m : targets.targets[0].markers) m.code = targets.targets[0].markers[0].code;
  std::mt19937_64 rng(12);
  int named = 0, wrong = 0, views = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const Pose start = testing::random_visible_pose(rng, camera, targets.targets[0], 0.7, 2.0, 20);
    int missing = -1;
    const auto pose = one_marker_out(camera, targets.targets[0], start, 2, 2, &missing);
    if (!pose) continue;
    ++views;
    const Shown s{0, *pose, CodeClock::from(targets.timebase), {}};
    const Watch r = watch(camera, targets, {s}, 24, 30 + uint64_t(trial));
    if (!r.first.count(0)) continue;
    ++named;
    const Identification& id = r.first.at(0).second;
    wrong += id.track_of[size_t(missing)] != -1 || (id.pose.t - pose->t).norm() > 0.02;
  }
  EXPECT_GE(views, 8);
  EXPECT_EQ(wrong, 0) << named << " named of " << views;
  EXPECT_LT(named, views);  // measured: none of 11 views named
}

TEST_F(Identify, AnOccludedMarkerAtTheBorderNeverLetsAnotherAssignmentThrough) {
  // All four in view near the border, one occluded: the true assignment puts the
  // fourth marker in view where no blob is, so it fails; no other assignment of
  // the three that puts it out of view may be named instead. A code per target
  // (codes cannot help) and a code per marker.
  for (bool per_target : {true, false}) {
    TargetsFile targets = two_coded_targets();
    targets.targets.resize(1);
    if (per_target)
      for (Marker& m : targets.targets[0].markers) m.code = targets.targets[0].markers[0].code;
    std::mt19937_64 rng(13);
    int views = 0, named = 0;
    for (int trial = 0; trial < 16; ++trial) {
      const Pose start = testing::random_visible_pose(rng, camera, targets.targets[0], 0.7, 2.0, 20);
      int out = -1;
      auto pose = one_marker_out(camera, targets.targets[0], start, 2, 2, &out);
      if (!pose) continue;
      // Back in until the outermost marker is 2 image radii inside, then hide it.
      for (int step = 0; step < 400 && least_margin(camera, targets.targets[0], *pose, &out) < 2; ++step)
        pose->t.x() += 0.005;
      if (least_margin(camera, targets.targets[0], *pose, &out) < 2) continue;
      ++views;
      Shown s{0, *pose, CodeClock::from(targets.timebase), {}};
      s.hidden = out;
      const Watch r = watch(camera, targets, {s}, 24, 50 + uint64_t(trial));
      named += r.identifications > 0;
    }
    EXPECT_GE(views, 8) << per_target;
    EXPECT_EQ(named, 0) << per_target << ": " << named << " of " << views;
  }
}

}  // namespace
}  // namespace tetrapulse

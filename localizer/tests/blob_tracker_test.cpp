#include "tetrapulse/localizer/blob_tracker.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "spot_renderer.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse {
namespace {

constexpr int64_t kFramePeriod = 10'000'000;  // 100 Hz

ExposureStamp stamp(int64_t frame) { return ExposureStamp{frame, frame * kFramePeriod, 2'000'000}; }

Blob blob_at(const Eigen::Vector2d& p, double intensity = 1000) {
  Blob b;
  b.centroid = p;
  b.intensity = intensity;
  b.area = 20;
  return b;
}

BlobExtraction blobs(std::initializer_list<Eigen::Vector2d> points) {
  BlobExtraction e;
  for (const auto& p : points) e.blobs.push_back(blob_at(p));
  return e;
}

// The track whose newest detection is nearest `p`.
int64_t track_near(const BlobTracker& tracker, const Eigen::Vector2d& p) {
  int64_t id = -1;
  double best = 1e9;
  for (const BlobTrack& t : tracker.tracks())
    if ((t.position() - p).norm() < best) {
      best = (t.position() - p).norm();
      id = t.id();
    }
  return id;
}

TEST(BlobTracker, KeepsIdentitiesThroughACrossingByConstantVelocity) {
  // A overtakes B's column between frames 5 and 6. From frame 5's positions
  // the least-distance matching of frame 6 swaps them: only the motion keeps
  // them apart.
  auto a = [](int k) { return Eigen::Vector2d(100 + 10.0 * k, 50); };
  auto b = [](int k) { return Eigen::Vector2d(180 - 4.0 * k, 52); };
  const double swapped = (a(5) - b(6)).squaredNorm() + (b(5) - a(6)).squaredNorm();
  const double kept = (a(5) - a(6)).squaredNorm() + (b(5) - b(6)).squaredNorm();
  ASSERT_LT(swapped, kept);

  BlobTrackerConfig config;
  config.gate_radius_px = 12;  // covers the first, unpredicted step
  BlobTracker tracker(config);
  tracker.update(stamp(0), blobs({a(0), b(0)}));
  const int64_t id_a = track_near(tracker, a(0)), id_b = track_near(tracker, b(0));
  ASSERT_NE(id_a, id_b);
  for (int k = 1; k <= 12; ++k) {
    tracker.update(stamp(k), blobs({b(k), a(k)}));
    ASSERT_EQ(tracker.tracks().size(), 2u) << "frame " << k;
    EXPECT_EQ((tracker.find(id_a)->position() - a(k)).norm(), 0) << "frame " << k;
    EXPECT_EQ((tracker.find(id_b)->position() - b(k)).norm(), 0) << "frame " << k;
  }
  EXPECT_NEAR(tracker.find(id_a)->velocity_px_per_s().x(), 1000, 1e-6);  // 10 px a frame at 100 Hz
}

TEST(BlobTracker, KeepsIdentitiesWithTheCallersPrediction) {
  // Two markers circling fast around one point, half a turn apart: a
  // constant-velocity image prediction fails, a pose prediction does not.
  auto at = [](int marker, int k) {
    const double angle = 0.9 * k + M_PI * marker;
    return Eigen::Vector2d(200 + 15 * std::cos(angle), 100 + 15 * std::sin(angle));
  };
  BlobTracker own;
  BlobTracker guided;
  own.update(stamp(0), blobs({at(0, 0), at(1, 0)}));
  guided.update(stamp(0), blobs({at(0, 0), at(1, 0)}));
  const int64_t id0 = track_near(guided, at(0, 0)), id1 = track_near(guided, at(1, 0));
  bool own_lost = false;
  for (int k = 1; k <= 20; ++k) {
    const std::vector<TrackGate> gates = {{id0, at(0, k), 3.0}, {id1, at(1, k), 3.0}};
    guided.update(stamp(k), blobs({at(1, k), at(0, k)}), gates);
    own.update(stamp(k), blobs({at(1, k), at(0, k)}));
    ASSERT_EQ(guided.tracks().size(), 2u);
    EXPECT_LT((guided.find(id0)->position() - at(0, k)).norm(), 1e-9);
    EXPECT_LT((guided.find(id1)->position() - at(1, k)).norm(), 1e-9);
    own_lost = own_lost || own.find(id0) == nullptr || (own.find(id0)->position() - at(0, k)).norm() > 1e-9;
  }
  EXPECT_TRUE(own_lost);  // the scenario does need the caller's prediction
}

TEST(BlobTracker, CoastsThroughAZeroRunThenDeletes) {
  const Code code = *parse_code("1100010", nullptr);
  ASSERT_EQ(longest_zero_run(code), 3);
  TargetsFile targets;
  targets.modulation.kind = ModulationKind::kOnOff;
  targets.timebase.bit_period_ns = kFramePeriod;
  targets.targets.resize(1);
  targets.targets[0].markers[0].code = code;
  BlobTrackerConfig config;
  config.max_coast_frames = coast_frames_for(targets, kFramePeriod);
  ASSERT_EQ(config.max_coast_frames, 4);
  BlobTracker tracker(config);
  const Eigen::Vector2d p(40, 30);
  int64_t id = -1;
  for (int k = 0; k < 21; ++k) {
    tracker.update(stamp(k), code.bit(uint32_t(k)) ? blobs({p}) : BlobExtraction{});
    ASSERT_EQ(tracker.tracks().size(), 1u) << "frame " << k;
    if (id < 0) id = tracker.tracks()[0].id();
    EXPECT_EQ(tracker.tracks()[0].id(), id);
  }
  const auto& history = tracker.find(id)->history();
  ASSERT_EQ(history.size(), 21u);
  for (size_t i = 0; i < history.size(); ++i) {
    EXPECT_EQ(history[i].frame, int64_t(i));
    EXPECT_EQ(history[i].detected, code.bit(uint32_t(i)));
    EXPECT_EQ(history[i].measured, code.bit(uint32_t(i)));  // no ROI measured the dark frames
    EXPECT_EQ(history[i].timestamp_ns, int64_t(i) * kFramePeriod);
  }
  // Gone for good after frame 19 (frame 20 is a 0 bit already): coasts to
  // frame 23, deleted in frame 24 having missed more than max_coast_frames.
  ASSERT_TRUE(code.bit(19));
  ASSERT_FALSE(code.bit(20));
  for (int k = 21; k < 24; ++k) {
    tracker.update(stamp(k), BlobExtraction{});
    EXPECT_EQ(tracker.tracks().size(), 1u);
    EXPECT_EQ(tracker.tracks()[0].missed(), k - 19);
  }
  tracker.update(stamp(24), BlobExtraction{});
  EXPECT_TRUE(tracker.tracks().empty());
  // A blob there now starts a new track with a new id.
  tracker.update(stamp(25), blobs({p}));
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NE(tracker.tracks()[0].id(), id);
}

TEST(BlobTracker, TakesRoiMeasurementsByTagIncludingAbsentOnes) {
  BlobTracker tracker;
  tracker.update(stamp(0), blobs({{40, 30}, {90, 30}}));
  ASSERT_EQ(tracker.tracks().size(), 2u);
  const int64_t id = tracker.tracks()[0].id(), other = tracker.tracks()[1].id();
  BlobExtraction e;
  RoiMeasurement absent;
  absent.tag = id;
  absent.status = RoiStatus::kAbsent;
  absent.intensity = -3.5;
  e.rois.push_back(absent);
  RoiMeasurement unknown;
  unknown.tag = 999;  // no such track: ignored
  unknown.status = RoiStatus::kDetected;
  unknown.blob = blob_at({10, 10});
  e.rois.push_back(unknown);
  RoiMeasurement found;
  found.tag = other;
  found.status = RoiStatus::kDetected;
  found.blob = blob_at({91, 30.5}, 777);
  found.intensity = 777;
  e.rois.push_back(found);
  tracker.update(stamp(1), e);
  ASSERT_EQ(tracker.tracks().size(), 2u);
  const TrackSample& s = tracker.find(id)->history().newest();
  EXPECT_FALSE(s.detected);
  EXPECT_TRUE(s.measured);
  EXPECT_EQ(s.intensity, -3.5);
  EXPECT_EQ(s.centroid, Eigen::Vector2d(40, 30));
  EXPECT_EQ(tracker.find(id)->missed(), 1);
  const TrackSample& t = tracker.find(other)->history().newest();
  EXPECT_TRUE(t.detected);
  EXPECT_EQ(t.intensity, 777);
  EXPECT_EQ(tracker.find(other)->missed(), 0);
}

// find() is a binary search over tracks kept in id order: with tracks born and
// deleted at random over many frames, the order holds and every id (live, deleted,
// never given) is found exactly where a scan finds it.
TEST(BlobTracker, FindsEveryTrackByIdAsTracksComeAndGo) {
  BlobTrackerConfig config;
  config.max_coast_frames = 2;
  BlobTracker tracker(config);
  std::mt19937 rng(4);
  std::bernoulli_distribution shows(0.6);
  int64_t largest = -1;
  size_t most = 0;
  for (int k = 0; k < 200; ++k) {
    // A grid of 40 places 60 px apart, each lit or not this frame: tracks end
    // after missing three frames and start again with new ids.
    BlobExtraction e;
    for (int i = 0; i < 40; ++i)
      if (shows(rng)) e.blobs.push_back(blob_at(Eigen::Vector2d(30 + 60 * (i % 8), 30 + 60 * (i / 8))));
    tracker.update(stamp(k), e);
    const auto& tracks = tracker.tracks();
    most = std::max(most, tracks.size());
    for (size_t i = 1; i < tracks.size(); ++i) ASSERT_LT(tracks[i - 1].id(), tracks[i].id()) << "frame " << k;
    for (const BlobTrack& t : tracks) largest = std::max(largest, t.id());
    for (int64_t id = -2; id <= largest + 2; ++id) {
      const BlobTrack* scanned = nullptr;
      for (const BlobTrack& t : tracks)
        if (t.id() == id) scanned = &t;
      ASSERT_EQ(tracker.find(id), scanned) << "frame " << k << " id " << id;
    }
  }
  EXPECT_GT(largest, 100);  // many tracks came and went
  EXPECT_GE(most, 30u);
}

TEST(BlobTracker, HistoryKeepsTheNewest64Samples) {
  BlobTracker tracker;
  for (int k = 0; k < 100; ++k) tracker.update(stamp(k), blobs({{40, 30}}));
  const auto& h = tracker.tracks().at(0).history();
  ASSERT_EQ(h.size(), kTrackHistory);
  EXPECT_EQ(h[0].frame, 100 - int64_t(kTrackHistory));
  EXPECT_EQ(h.newest().frame, 99);
}

TEST(BlobTracker, LongestZeroRunCountsAcrossTheWrap) {
  EXPECT_EQ(longest_zero_run(*parse_code("0110", nullptr)), 2);
  EXPECT_EQ(longest_zero_run(*parse_code("0000", nullptr)), 4);
  EXPECT_EQ(longest_zero_run(*parse_code("1", nullptr)), 0);
  EXPECT_EQ(longest_zero_run(*parse_code("1000110", nullptr)), 3);
  TargetsFile targets;
  targets.modulation.kind = ModulationKind::kOnOff;
  targets.timebase.bit_period_ns = 20'000'000;
  targets.targets.resize(1);
  targets.targets[0].markers[2].code = *parse_code("1000110", nullptr);
  EXPECT_EQ(coast_frames_for(targets, 10'000'000), 3 * 2 + 1);  // two frames a bit
  targets.modulation.kind = ModulationKind::kTwoLevel;
  EXPECT_EQ(coast_frames_for(targets, 10'000'000), 1);
}

// End to end on rendered frames: whole-image extraction starts the tracks,
// then ROI mode follows four on_off markers and the tracks' histories read
// back each marker's code, zero bits included.
TEST(BlobTracker, FollowsOnOffMarkersInRoiModeAndReadsTheirCodes) {
  const std::vector<std::string> codes = {"1101001110", "1011100100", "1101110100", "1110010101"};
  const std::vector<Eigen::Vector2d> start = {{60.3, 50.2}, {140.7, 60.9}, {80.1, 120.4}, {150.5, 130.6}};
  const Eigen::Vector2d drift(0.8, -0.3);  // px a frame
  auto frame_image = [&](int k) {
    cv::Mat1d img(180, 220, 18.0);
    for (size_t m = 0; m < 4; ++m)
      if (codes[m][size_t(k) % codes[m].size()] == '1') test::add_gaussian(&img, start[m] + k * drift, 1.4, 160);
    test::add_noise(&img, 2.5, uint32_t(50 + k));
    return test::quantise(img, CV_8U);
  };
  BlobExtractor extractor;
  BlobTrackerConfig config;
  config.max_coast_frames = 3;  // the longest zero run (2 bits, a frame each) + 1
  BlobTracker tracker(config);
  BlobExtraction out;
  const int first = 0;  // every code starts with a 1
  ASSERT_TRUE(extractor.extract(frame_image(first), 4, &out));
  ASSERT_EQ(out.blobs.size(), 4u);
  tracker.update(stamp(first), out);
  std::map<size_t, int64_t> id_of;  // marker -> track
  for (size_t m = 0; m < 4; ++m) id_of[m] = track_near(tracker, start[m] + first * drift);
  std::vector<BlobRoi> rois;
  for (int k = first + 1; k < first + 40; ++k) {
    tracker.predict_rois(stamp(k), 4.0, &rois);
    ASSERT_TRUE(extractor.extract(frame_image(k), rois, &out));
    tracker.update(stamp(k), out);
    ASSERT_EQ(tracker.tracks().size(), 4u) << "frame " << k;
  }
  for (size_t m = 0; m < 4; ++m) {
    const BlobTrack* track = tracker.find(id_of[m]);
    ASSERT_NE(track, nullptr);
    int64_t last_seen = 0;
    for (size_t i = 0; i < track->history().size(); ++i)
      if (track->history()[i].detected) last_seen = track->history()[i].frame;
    EXPECT_LT((track->position() - (start[m] + double(last_seen) * drift)).norm(), 0.1);
    double peak = 0;
    for (size_t i = 0; i < track->history().size(); ++i) peak = std::max(peak, track->history()[i].intensity);
    int wrong = 0;
    for (size_t i = 0; i < track->history().size(); ++i) {
      const TrackSample& s = track->history()[i];
      EXPECT_TRUE(s.measured);
      const bool bit = codes[m][size_t(s.frame) % codes[m].size()] == '1';
      wrong += (s.intensity > 0.5 * peak) != bit || s.detected != bit;
    }
    EXPECT_EQ(wrong, 0) << "marker " << m;
  }
}

}  // namespace
}  // namespace tetrapulse

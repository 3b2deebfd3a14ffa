// The `frequency` scenario end to end, up to identities: the virtual rig renders it
// (firmware boards in the loop, free-running, codes of different lengths per marker),
// blobs are extracted and tracked, and each track's samples go to a FrequencyIdentifier.
// Every track must be identified within two of the book's longest apparent periods
// (46 frames), never as a target other than the one whose projected centre is nearest,
// and stay identified (coverage) once it is.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "tetrapulse/localizer/blob_extractor.hpp"
#include "tetrapulse/localizer/blob_tracker.hpp"
#include "tetrapulse/localizer/frequency_identifier.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace tetrapulse {
namespace {

namespace fs = std::filesystem;

TEST(FrequencyRig, EveryTrackIdentifiedSoonNeverWrong) {
  const fs::path dir = fs::temp_directory_path() / ("tp_frequency_rig_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string command = std::string("'") + TETRAPULSE_CLI + "' sim frequency --frames 200 --out '" +
                              dir.string() + "' >/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  auto d = RigDataset::open(dir.string());
  ASSERT_TRUE(d) << d.error().what();
  BlobExtractor extractor;
  BlobTracker tracker;
  struct Seen {
    int64_t born = -1, first = -1;
    int frames = 0, decided = 0, wrong = 0;
  };
  std::map<int64_t, FrequencyIdentifier> ids;
  std::map<int64_t, Seen> seen;
  const CameraInfo& K = d->camera();
  for (size_t i = 0; i < d->frames().size(); ++i) {
    auto image = d->load_image(i);
    ASSERT_TRUE(image);
    BlobExtraction blobs;
    ASSERT_TRUE(extractor.extract(*image, 16, &blobs));
    const FrameRecord& f = d->frames()[i];
    tracker.update(ExposureStamp{f.frame, f.timestamp_ns, f.exposure_ns}, blobs);
    for (const BlobTrack& t : tracker.tracks()) {
      if (t.history().size() == 0) continue;
      FrequencyIdentifier& id = ids.try_emplace(t.id(), d->targets()).first->second;
      id.push(t.history()[t.history().size() - 1]);
      Seen& s = seen[t.id()];
      if (s.born < 0) s.born = f.frame;
      ++s.frames;
      const FrequencyDecision& decision = id.decision();
      if (decision.kind != FrequencyDecision::Kind::kFrequency) continue;
      if (s.first < 0) s.first = f.frame;
      ++s.decided;
      // The true target: the one whose centre projects nearest (pinhole; targets are 80 px apart).
      int nearest = -1;
      double best = 1e9;
      for (const GroundTruthRecord& g : d->groundtruth()) {
        if (g.frame != f.frame) continue;
        const Eigen::Vector3d& p = g.pose.t;
        const Eigen::Vector2d uv(K.fx * p.x() / p.z() + K.cx, K.fy * p.y() / p.z() + K.cy);
        if ((uv - t.position()).norm() < best) best = (uv - t.position()).norm(), nearest = g.target;
      }
      const size_t target = id.codes()[static_cast<size_t>(decision.code)].markers.front().first;
      if (d->targets().targets[target].id != nearest) ++s.wrong;
    }
  }
  fs::remove_all(dir);
  ASSERT_EQ(seen.size(), 16u) << "four targets, four markers each, one track each";
  int slowest = 0, wrong = 0;
  double coverage = 1;
  for (const auto& [track, s] : seen) {
    ASSERT_GE(s.first, 0) << "track " << track << " never identified";
    slowest = std::max(slowest, static_cast<int>(s.first - s.born + 1));
    wrong += s.wrong;
    coverage = std::min(coverage, static_cast<double>(s.decided) / static_cast<double>(s.frames - (s.first - s.born)));
  }
  std::printf("[measure] frequency scenario, 200 frames: 16 tracks identified within %d frames, %d wrong, coverage %.3f\n",
              slowest, wrong, coverage);
  EXPECT_LE(slowest, 46);
  EXPECT_EQ(wrong, 0);
  EXPECT_GE(coverage, 0.99);
}

}  // namespace
}  // namespace tetrapulse

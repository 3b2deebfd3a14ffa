// From the sync master's exposures and the camera's images to frames.csv: images matched
// to the exposure they came from, dropped frames skipped, bad recordings named; the
// exposures file read back as the sync master wrote it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tetrapulse/host/recorded_frames.hpp"

namespace tetrapulse::host {
namespace {

constexpr int64_t kPeriod = 33'333'333;
constexpr int64_t kExposure = 5'000'000;

// Trigger pulses k = first..first+count-1 at k * period (rig time), stamped `jitter(k)` late.
std::vector<Exposure> trigger_exposures(int64_t first, int64_t count) {
  std::vector<Exposure> out;
  for (int64_t k = first; k < first + count; ++k) {
    const int64_t jitter = (k * 7919) % 20'000;  // the set-value ioctl's few microseconds
    out.push_back(Exposure{k, k * kPeriod + jitter, kExposure});
  }
  return out;
}

std::string image_name(int64_t k) { return "frames/" + std::to_string(k) + ".png"; }

TEST(RecordedFrames, EachImageGoesToTheExposureItCameFromAndDropsSkipNumbers) {
  const auto exposures = trigger_exposures(40, 30);
  std::vector<CapturedImage> images;
  for (const Exposure& e : exposures) {
    if (e.frame == 40 || e.frame == 55 || e.frame == 56) continue;  // the camera lost these
    // Readout and transfer: 3..13 ms after the exposure ended.
    images.push_back(CapturedImage{image_name(e.frame), e.timestamp_ns + e.exposure_ns + 3'000'000 + (e.frame % 11) * 1'000'000});
  }
  auto frames = frames_from_exposures(exposures, images);
  ASSERT_TRUE(frames) << frames.error().what();
  ASSERT_EQ(frames->size(), images.size());
  for (const FrameRecord& r : *frames) {
    const Exposure& e = exposures[static_cast<size_t>(r.frame + 41 - 40)];
    EXPECT_EQ(r.frame, e.frame - 41) << "frame 0 is the first pulse with an image";
    EXPECT_EQ(r.timestamp_ns, e.timestamp_ns);
    EXPECT_EQ(r.exposure_ns, kExposure);
    EXPECT_EQ(r.file, image_name(e.frame));
  }
  EXPECT_EQ((*frames)[13].frame, 13);
  EXPECT_EQ((*frames)[14].frame, 16) << "frames 14 and 15 (pulses 55, 56) were dropped";
}

TEST(RecordedFrames, ImagesThatFitNoExposureAreNamed) {
  const auto exposures = trigger_exposures(0, 10);
  const int64_t end3 = exposures[3].timestamp_ns + kExposure;
  auto early = frames_from_exposures(exposures, {CapturedImage{"a.png", exposures[0].timestamp_ns + 1}});
  ASSERT_FALSE(early);
  EXPECT_EQ(early.error().what().rfind("a.png: arrived at ", 0), 0u) << early.error().what();
  EXPECT_NE(early.error().what().find("before any exposure ended"), std::string::npos);
  const int64_t end9 = exposures[9].timestamp_ns + kExposure;
  auto late = frames_from_exposures(exposures, {CapturedImage{"b.png", end9 + 60'000'000}});
  ASSERT_FALSE(late);
  EXPECT_NE(late.error().what().find("b.png: arrived"), std::string::npos) << late.error().what();
  auto twice = frames_from_exposures(exposures, {CapturedImage{"c.png", end3 + 1}, CapturedImage{"d.png", end3 + 2}});
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().what().find("d.png: comes from the same exposure (frame 3) as c.png"), std::string::npos)
      << twice.error().what();
}

TEST(RecordedFrames, TheSyncMastersFileBecomesADatasetsFramesCsv) {
  const auto dir = std::filesystem::temp_directory_path() / ("tp_recorded_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto exposures = trigger_exposures(-3, 8);
  {
    auto writer = ExposureLogWriter::create((dir / "exposures.csv").string());
    ASSERT_TRUE(writer) << writer.error().what();
    for (const Exposure& e : exposures) ASSERT_TRUE((*writer)->write(e));
  }
  auto read = read_exposures_file((dir / "exposures.csv").string());
  ASSERT_TRUE(read) << read.error().what();
  ASSERT_EQ(read->size(), exposures.size());
  for (size_t k = 0; k < exposures.size(); ++k) EXPECT_EQ((*read)[k].timestamp_ns, exposures[k].timestamp_ns);

  std::vector<CapturedImage> images;
  for (const Exposure& e : exposures) images.push_back(CapturedImage{image_name(e.frame), e.timestamp_ns + kExposure + 1});
  auto frames = frames_from_exposures(*read, images);
  ASSERT_TRUE(frames) << frames.error().what();
  ASSERT_TRUE(write_frames_csv(dir.string(), *frames));
  auto back = read_frames_csv((dir / "frames.csv").string());
  ASSERT_TRUE(back) << back.error().what();
  ASSERT_EQ(back->size(), exposures.size());
  EXPECT_EQ(back->front().frame, 0);
  EXPECT_EQ(back->front().timestamp_ns, exposures.front().timestamp_ns);
  EXPECT_EQ(back->back().frame, 7);

  std::ofstream(dir / "bad.csv") << "frame,timestamp_ns,exposure_ns\n0,100,5\n1,2x00,5\n";
  auto bad = read_exposures_file((dir / "bad.csv").string());
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().what().find("bad.csv:3"), std::string::npos) << bad.error().what();
  auto missing = read_exposures_file((dir / "none.csv").string());
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, HostErrorKind::kBadFile);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tetrapulse::host

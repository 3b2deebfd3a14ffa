// What publishing into ROS 2 adds to the localizer per frame, on the four-targets
// sequence (four_targets_sequence.hpp: 4 poses per frame), with readers in another
// process (tetrapulse_ros2_listener on rt/tf, reliable, keep last 100, and on
// target 1's pose topic, best effort) matched before timing starts. Each frame's
// publish: one TFMessage of 4 transforms on /tf and 4 PoseWithCovarianceStamped.
//   BM_LocalizerTracking                 Localizer::process per frame, the four
//                                        targets tracked (as in localizer_pipeline_bench)
//   BM_LocalizerTrackingPublishing       the same, then publish(poses) as `localize
//                                        --ros2` does it: handed to the background
//                                        publisher's thread (background_publisher.hpp)
//   BM_LocalizerTrackingPublishingInline the same with the DDS writes in the
//                                        localizer's thread
//   BM_PublishInline                     the DDS writes of one frame's 4 poses alone
// The */process_time rows count the CPU time of every thread of the process (the
// publisher's and Cyclone DDS's own), the others the localizer's thread.
// Runs only inside tests/netns/isolated --cyclone (BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include <unistd.h>

#include <opencv2/core/utility.hpp>

#include "child_process.hpp"
#include "four_targets_sequence.hpp"
#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/ros2/background_publisher.hpp"
#include "tetrapulse/ros2/dds_pose_publisher.hpp"

namespace {

using namespace tetrapulse;

constexpr int kWarmUp = 30;
ros2::PosePublisher* g_inline = nullptr;      // the DDS publisher
ros2::PosePublisher* g_background = nullptr;  // it, behind the background queue

// Hands every call to the DDS publisher, which the bench keeps (so that both ways
// of publishing share one participant).
class Forward final : public ros2::PosePublisher {
  ros2::Ros2Result<void> do_publish(const std::vector<TargetPose>& p) override { return g_inline->publish(p); }
  ros2::Ros2Result<void> do_publish_status(const ros2::LocalizerStatus& s) override {
    return g_inline->publish_status(s);
  }
  int do_wait_for_readers(int64_t t, int64_t s) override { return g_inline->wait_for_readers(t, s); }
  bool do_wait_for_acknowledgments(int64_t t) override { return g_inline->wait_for_acknowledgments(t); }
  ros2::PublishCounters do_counters() const override { return g_inline->counters(); }
};

// One frame per iteration from frame kWarmUp on, the localizer restarted (untimed)
// at the end of the sequence; each frame's poses published through `publisher`.
void time_frames(benchmark::State& state, ros2::PosePublisher* publisher) {
  cv::setNumThreads(1);
  const bench::Sequence& s = bench::four_targets_sequence();
  const auto fresh = [&] {
    auto l = std::make_unique<Localizer>(s.scenario.camera, s.scenario.targets);
    for (int k = 0; k < kWarmUp; ++k) benchmark::DoNotOptimize(l->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns));
    return l;
  };
  auto localizer = fresh();
  int k = kWarmUp;
  int64_t poses = 0;
  for (auto _ : state) {
    if (k == bench::kSequenceFrames) {
      state.PauseTiming();
      localizer = fresh();
      k = kWarmUp;
      state.ResumeTiming();
    }
    auto out = localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
    if (out) {
      poses += int64_t(out->size());
      if (publisher != nullptr && !publisher->publish(*out)) state.SkipWithError("publish failed");
    }
    ++k;
  }
  state.counters["poses_per_frame"] = double(poses) / double(state.iterations());
}

void BM_LocalizerTracking(benchmark::State& state) { time_frames(state, nullptr); }
BENCHMARK(BM_LocalizerTracking)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LocalizerTracking)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();

void BM_LocalizerTrackingPublishing(benchmark::State& state) {
  time_frames(state, g_background);
  // What the queue still holds is written before the next benchmark (after the timed loop).
  g_background->wait_for_acknowledgments(10'000'000'000);
}
BENCHMARK(BM_LocalizerTrackingPublishing)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LocalizerTrackingPublishing)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();

void BM_LocalizerTrackingPublishingInline(benchmark::State& state) { time_frames(state, g_inline); }
BENCHMARK(BM_LocalizerTrackingPublishingInline)->Unit(benchmark::kMicrosecond);

void BM_PublishInline(benchmark::State& state) {
  const bench::Sequence& s = bench::four_targets_sequence();
  Localizer localizer(s.scenario.camera, s.scenario.targets);
  std::vector<TargetPose> poses;
  for (int k = 0; k < 60; ++k) poses = *localizer.process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
  for (auto _ : state) {
    if (!g_inline->publish(poses)) state.SkipWithError("publish failed");
  }
  state.counters["poses"] = double(poses.size());
}
BENCHMARK(BM_PublishInline)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  const char* netns = std::getenv("TETRAPULSE_IN_NETNS");
  if (netns == nullptr || std::strcmp(netns, "1") != 0 || std::getenv("CYCLONEDDS_URI") == nullptr) {
    std::fprintf(stderr, "ros2_publish_bench: run it through tests/netns/isolated --cyclone\n");
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  const bench::Sequence& s = bench::four_targets_sequence();
  const std::string dir = "/tmp/ros2_publish_bench_" + std::to_string(::getpid());
  std::system(("mkdir -p " + dir).c_str());
  using ros2::testing::ChildProcess;
  ChildProcess tf({TETRAPULSE_ROS2_LISTENER, "tf", "--out", dir + "/tf.csv", "--timeout-ms", "3600000"}, {},
                  dir + "/tf.err");
  ChildProcess pose({TETRAPULSE_ROS2_LISTENER, "pose", "--topic", "rt/tetrapulse/target_1/pose", "--best-effort",
                     "--out", dir + "/pose.csv", "--timeout-ms", "3600000"},
                    {}, dir + "/pose.err");
  std::string line;
  if (!tf.read_line(&line, 20'000) || !pose.read_line(&line, 20'000)) {
    std::fprintf(stderr, "ros2_publish_bench: the listeners did not start\n");
    return 1;
  }
  ros2::DdsPublisherOptions options;
  options.node_name = "tetrapulse_bench";
  options.frame_id = s.scenario.camera.name.empty() ? "camera" : s.scenario.camera.name;
  for (const Target& t : s.scenario.targets.targets) options.target_ids.push_back(t.id);
  auto publisher = ros2::open_dds_publisher(options);
  if (!publisher) {
    std::fprintf(stderr, "ros2_publish_bench: %s\n", publisher.error().message.c_str());
    return 1;
  }
  g_inline = publisher->get();
  // As localize --ros2 on a replay: 256 frames queued, waiting for room when full.
  auto background = ros2::publish_in_background(std::make_unique<Forward>(), 256, ros2::WhenQueueFull::kWait);
  g_background = background.get();
  const int readers = g_inline->wait_for_readers(20'000'000'000, 200'000'000);
  std::fprintf(stderr, "ros2_publish_bench: %d readers matched\n", readers);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_background->wait_for_acknowledgments(10'000'000'000);
  background.reset();
  const ros2::PublishCounters c = g_inline->counters();
  publisher->reset();
  std::fprintf(stderr, "ros2_publish_bench: %llu transforms, %llu poses published; tf reader: %s; pose reader: %s\n",
               static_cast<unsigned long long>(c.transforms), static_cast<unsigned long long>(c.poses),
               tf.wait(30'000) == 0 ? tf.read_rest(1000).c_str() : "did not end",
               pose.wait(30'000) == 0 ? pose.read_rest(1000).c_str() : "did not end");
  std::system(("rm -rf " + dir).c_str());
  return 0;
}

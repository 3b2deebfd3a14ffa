// What publishing into ROS 2 adds to the localizer per frame, on the four-targets
// sequence (four_targets_sequence.hpp: 4 poses per frame), with readers in another
// process (tetrapulse_ros2_listener --count-only on rt/tf, reliable, keep last 100,
// and on target 1's pose topic, best effort) matched before timing starts. Each frame's
// publish: one TFMessage of 4 transforms on /tf and 4 PoseWithCovarianceStamped.
//   BM_LocalizerTracking   Localizer::process per frame, the four targets tracked
//                          (as in localizer_pipeline_bench)
//   BM_PublishInline       the DDS writes of one frame's 4 poses alone
//   BM_PublishingOverhead/MODE  side by side in one run: blocks of frames 30-239
//                          localized without publishing and with it, alternately
//                          (so that the shared machine's load changes alike for
//                          both), each frame's process() + publish() timed on the
//                          localizer's thread (CPU and wall). MODE: background =
//                          as `localize --ros2` does it, handed to the background
//                          publisher's thread (background_publisher.hpp); inline =
//                          the DDS writes in the localizer's thread; queue_only =
//                          the hand-off to a publisher that writes nothing.
//                          Counters: us per frame without / with (all pairs), and
//                          the overhead % of the median pair; cpu = the localizer's
//                          thread, wall = the same frames' wall time, process =
//                          every thread of this process (the publisher's and
//                          Cyclone DDS's) until all is written and acknowledged.
// When this program is pinned to some CPUs (taskset), the readers run on the others.
// --no-readers: no listener at all. Runs only inside tests/netns/isolated --cyclone
// (BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include <sched.h>
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

std::unique_ptr<Localizer> fresh_localizer() {
  const bench::Sequence& s = bench::four_targets_sequence();
  auto l = std::make_unique<Localizer>(s.scenario.camera, s.scenario.targets);
  for (int k = 0; k < kWarmUp; ++k) benchmark::DoNotOptimize(l->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns));
  return l;
}

void BM_LocalizerTracking(benchmark::State& state) {
  cv::setNumThreads(1);
  const bench::Sequence& s = bench::four_targets_sequence();
  auto localizer = fresh_localizer();
  int k = kWarmUp;
  for (auto _ : state) {
    if (k == bench::kSequenceFrames) {
      state.PauseTiming();
      localizer = fresh_localizer();
      k = kWarmUp;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns));
    ++k;
  }
}
BENCHMARK(BM_LocalizerTracking)->Unit(benchmark::kMicrosecond);

// The background queue's hand-off alone: a publisher that writes nothing.
class Nothing final : public ros2::PosePublisher {
  ros2::Ros2Result<void> do_publish(const std::vector<TargetPose>&) override { return {}; }
  ros2::Ros2Result<void> do_publish_status(const ros2::LocalizerStatus&) override { return {}; }
  int do_wait_for_readers(int64_t, int64_t) override { return 0; }
  bool do_wait_for_acknowledgments(int64_t) override { return true; }
  ros2::PublishCounters do_counters() const override { return {}; }
};

int64_t clock_ns(clockid_t id) {
  timespec t{};
  clock_gettime(id, &t);
  return int64_t(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

struct BlockTimes {
  int64_t cpu_ns = 0;      // the localizer's thread, over its frames
  int64_t wall_ns = 0;     // the same frames, wall clock
  int64_t process_ns = 0;  // every thread of the process, over the frames and until all is written
  int64_t frames = 0;
};

// Frames kWarmUp..end through a fresh localizer (warm-up untimed), each frame's
// process() and, with a publisher, publish() timed together.
void time_block(ros2::PosePublisher* publisher, BlockTimes* times) {
  const bench::Sequence& s = bench::four_targets_sequence();
  auto localizer = fresh_localizer();
  const int64_t process0 = clock_ns(CLOCK_PROCESS_CPUTIME_ID);
  for (int k = kWarmUp; k < bench::kSequenceFrames; ++k) {
    const int64_t cpu0 = clock_ns(CLOCK_THREAD_CPUTIME_ID), wall0 = clock_ns(CLOCK_MONOTONIC);
    auto out = localizer->process(s.images[size_t(k)], s.starts[size_t(k)], s.exposure_ns);
    if (out && publisher != nullptr) benchmark::DoNotOptimize(publisher->publish(*out));
    times->cpu_ns += clock_ns(CLOCK_THREAD_CPUTIME_ID) - cpu0;
    times->wall_ns += clock_ns(CLOCK_MONOTONIC) - wall0;
    ++times->frames;
  }
  // What the queue still holds is written before the next block (in process time only).
  if (publisher != nullptr) publisher->wait_for_acknowledgments(10'000'000'000);
  times->process_ns += clock_ns(CLOCK_PROCESS_CPUTIME_ID) - process0;
}

void BM_PublishingOverhead(benchmark::State& state) {
  cv::setNumThreads(1);
  std::unique_ptr<ros2::PosePublisher> queue_only;
  ros2::PosePublisher* publisher = g_background;
  if (state.range(0) == 1) publisher = g_inline;
  if (state.range(0) == 2) {
    queue_only = ros2::publish_in_background(std::make_unique<Nothing>(), 256, ros2::WhenQueueFull::kWait);
    publisher = queue_only.get();
  }
  BlockTimes off, on;
  std::vector<double> cpu_ratios, wall_ratios, process_ratios;  // with / without, per pair of blocks
  bool publishing_first = false;
  for (auto _ : state) {
    BlockTimes pair_off, pair_on;
    time_block(publishing_first ? publisher : nullptr, publishing_first ? &pair_on : &pair_off);
    time_block(publishing_first ? nullptr : publisher, publishing_first ? &pair_off : &pair_on);
    publishing_first = !publishing_first;
    cpu_ratios.push_back(double(pair_on.cpu_ns) / double(pair_off.cpu_ns));
    wall_ratios.push_back(double(pair_on.wall_ns) / double(pair_off.wall_ns));
    process_ratios.push_back(double(pair_on.process_ns) / double(pair_off.process_ns));
    for (auto [from, to] : {std::pair{&pair_off, &off}, std::pair{&pair_on, &on}}) {
      to->cpu_ns += from->cpu_ns;
      to->wall_ns += from->wall_ns;
      to->process_ns += from->process_ns;
      to->frames += from->frames;
    }
  }
  // The median pair: a burst of another job's load on the shared machine spoils one
  // pair, not the result.
  const auto median_pct = [](std::vector<double> r) {
    std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
    return 100.0 * (r[r.size() / 2] - 1.0);
  };
  const auto us = [](int64_t ns, int64_t frames) { return double(ns) * 1e-3 / double(frames); };
  state.counters["alone_cpu_us"] = us(off.cpu_ns, off.frames);
  state.counters["with_cpu_us"] = us(on.cpu_ns, on.frames);
  state.counters["cpu_overhead_pct"] = median_pct(cpu_ratios);
  state.counters["alone_wall_us"] = us(off.wall_ns, off.frames);
  state.counters["with_wall_us"] = us(on.wall_ns, on.frames);
  state.counters["wall_overhead_pct"] = median_pct(wall_ratios);
  state.counters["alone_process_us"] = us(off.process_ns, off.frames);
  state.counters["with_process_us"] = us(on.process_ns, on.frames);
  state.counters["process_overhead_pct"] = median_pct(process_ratios);
}
BENCHMARK(BM_PublishingOverhead)->ArgName("background")->Arg(0)->Iterations(41)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PublishingOverhead)->ArgName("inline")->Arg(1)->Iterations(41)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PublishingOverhead)->ArgName("queue_only")->Arg(2)->Iterations(41)->Unit(benchmark::kMillisecond);

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

// "taskset -c LIST" for the CPUs this process may not run on (empty when it may run on all).
std::vector<std::string> other_cpus() {
  cpu_set_t mine;
  CPU_ZERO(&mine);
  if (sched_getaffinity(0, sizeof mine, &mine) != 0) return {};
  std::string list;
  for (long cpu = 0; cpu < sysconf(_SC_NPROCESSORS_ONLN); ++cpu) {
    if (!CPU_ISSET(cpu, &mine)) list += (list.empty() ? "" : ",") + std::to_string(cpu);
  }
  if (list.empty()) return {};
  return {"/usr/bin/taskset", "-c", list};
}

}  // namespace

int main(int argc, char** argv) {
  const char* netns = std::getenv("TETRAPULSE_IN_NETNS");
  if (netns == nullptr || std::strcmp(netns, "1") != 0 || std::getenv("CYCLONEDDS_URI") == nullptr) {
    std::fprintf(stderr, "ros2_publish_bench: run it through tests/netns/isolated --cyclone\n");
    return 1;
  }
  // --no-readers: nobody subscribes (the writes then stay in this process).
  bool readers_wanted = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--no-readers") == 0) {
      readers_wanted = false;
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      break;
    }
  }
  benchmark::Initialize(&argc, argv);
  const bench::Sequence& s = bench::four_targets_sequence();
  const std::string dir = "/tmp/ros2_publish_bench_" + std::to_string(::getpid());
  std::system(("mkdir -p " + dir).c_str());
  using ros2::testing::ChildProcess;
  std::unique_ptr<ChildProcess> tf, pose;
  if (readers_wanted) {
    const auto listener = [&](std::vector<std::string> args, const std::string& name) {
      std::vector<std::string> command = other_cpus();
      command.push_back(TETRAPULSE_ROS2_LISTENER);
      command.insert(command.end(), args.begin(), args.end());
      for (const char* a : {"--out", "", "--timeout-ms", "3600000"}) command.push_back(a);
      command[command.size() - 3] = dir + "/" + name + ".csv";
      return std::make_unique<ChildProcess>(command, std::vector<std::string>{}, dir + "/" + name + ".err");
    };
    tf = listener({"tf", "--count-only"}, "tf");
    pose = listener({"pose", "--topic", "rt/tetrapulse/target_1/pose", "--best-effort", "--count-only"}, "pose");
    std::string line;
    if (!tf->read_line(&line, 20'000) || !pose->read_line(&line, 20'000)) {
      std::fprintf(stderr, "ros2_publish_bench: the listeners did not start\n");
      return 1;
    }
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
  const int readers = readers_wanted ? g_inline->wait_for_readers(20'000'000'000, 200'000'000) : 0;
  std::fprintf(stderr, "ros2_publish_bench: %d readers matched\n", readers);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_background->wait_for_acknowledgments(10'000'000'000);
  background.reset();
  const ros2::PublishCounters c = g_inline->counters();
  publisher->reset();
  std::fprintf(stderr, "ros2_publish_bench: %llu transforms, %llu poses published\n",
               static_cast<unsigned long long>(c.transforms), static_cast<unsigned long long>(c.poses));
  for (ChildProcess* p : {tf.get(), pose.get()}) {
    if (p != nullptr) {
      std::fprintf(stderr, "ros2_publish_bench: reader: %s", p->wait(30'000) == 0 ? p->read_rest(1000).c_str() : "did not end\n");
    }
  }
  std::system(("rm -rf " + dir).c_str());
  return 0;
}

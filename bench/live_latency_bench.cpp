// Live latency, exposure end -> pose out, through the real GigE Vision stack: the
// four-targets scene (four_targets_sequence.hpp) served at 100 Hz as GVSP packets by
// the live tests' fake camera (tests/live/fake_gige_server.cpp, in this process, on
// 127.0.0.1), received by host::Camera's Aravis backend (packet resend on), and
// localized frame by frame; a pose line is formatted for every pose, as `localize
// --camera` writes them. Each buffer is stamped with CLOCK_MONOTONIC when the fake
// camera fills it (the exposure's end), so one frame's time here is transfer +
// reassembly + hand-over + localizer + output. The benchmark's time is the mean over
// frames (manual time); p50_ms/p99_ms the nearest-rank percentiles.
//   BM_LiveGvspLatency/L: L per thousand GVSP packets lost (resent on request).
//   BM_LiveGvspHeadroom/W: the live loop's host CPU per frame against the camera's
//     frame period, no loss: W = 752, the four-targets scene (752x480) at 100 Hz;
//     W = 1280, the scale scene's 16 targets (1280x960, scale_targets_sequence.hpp)
//     at 60 Hz. Host CPU is the process's less the fake camera's thread: Aravis'
//     stream thread reassembling GVSP, and the loop grabbing, localizing and
//     formatting. Counters host_cpu_ms (per frame) and headroom (period / that).
// Both report both sets of counters. Opens sockets: run it through
// tests/netns/isolated (loopback only, by address).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <optional>
#include <pthread.h>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "../tests/live/fake_gige_server.hpp"
#include "four_targets_sequence.hpp"
#include "scale_targets_sequence.hpp"
#include "tetrapulse/datasets/pose_writer.hpp"
#include "tetrapulse/host/camera.hpp"
#include "tetrapulse/host/rig_clock.hpp"
#include "tetrapulse/localizer/localizer.hpp"

namespace {

using namespace tetrapulse;

struct Served {
  const bench::Sequence* sequence = nullptr;
  ArvFakeCamera* fake = nullptr;
  size_t next = 0;
  std::mutex mutex;
  std::map<uint64_t, size_t> image_of;  // GVSP block id -> the image it carries
  std::optional<size_t> image(uint64_t block_id) {
    std::lock_guard<std::mutex> lock(mutex);
    const auto it = image_of.find(block_id);
    if (it == image_of.end()) return std::nullopt;
    return it->second;
  }
};

void fill(ArvBuffer* buffer, void* data, guint32, guint32, ArvPixelFormat) {
  auto* s = static_cast<Served*>(data);
  // Past the sequence's end: its last image again (the benchmark stops before).
  const size_t k = std::min(s->next++, s->sequence->images.size() - 1);
  const cv::Mat& image = s->sequence->images[k];
  {
    // Block ids are 16 bits and wrap; the benchmark's frames are far fewer.
    std::lock_guard<std::mutex> lock(s->mutex);
    s->image_of[arv_buffer_get_frame_id(buffer)] = k;
  }
  size_t unused = 0;
  auto* pixels = static_cast<uint8_t*>(const_cast<void*>(arv_buffer_get_data(buffer, &unused)));
  if (pixels && arv_fake_camera_get_payload(s->fake) >= image.total()) std::memcpy(pixels, image.data, image.total());
  arv_buffer_set_timestamp(buffer, static_cast<guint64>(host::monotonic_now_ns()));
}

int64_t percentile(std::vector<int64_t> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, rank == 0 ? 0 : rank - 1)];
}

// CPU time of a clock (process or thread), ns.
int64_t cpu_ns(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

// `seq` served at `rate_hz` with `lost_per_thousand` GVSP packets lost, one frame an
// iteration.
void run_live(benchmark::State& state, const bench::Sequence& seq, double rate_hz, int64_t lost_per_thousand) {
  cv::setNumThreads(1);
  Served served;
  served.sequence = &seq;
  served.fake = arv_fake_camera_new("TP-BENCH-1");
  arv_fake_camera_set_fill_pattern(served.fake, fill, &served);
  live_test::FakeGigeOptions o;
  o.lost_ratio = static_cast<double>(lost_per_thousand) / 1000.0;
  live_test::FakeGigeCounters sent;
  std::atomic<bool> stop{false};
  std::thread server([&] { live_test::serve_fake_gige(served.fake, o, 600, stop, &sent); });
  const auto finish = [&] {
    stop = true;
    server.join();
    g_object_unref(served.fake);
  };
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // listening
  auto camera = host::open_camera("aravis:127.0.0.1");
  if (!camera) {
    finish();
    state.SkipWithError(camera.error().what().c_str());
    return;
  }
  host::CameraSettings settings;
  settings.width = seq.scenario.camera.width;
  settings.height = seq.scenario.camera.height;
  settings.pixel_format = "Mono8";
  settings.frame_rate_hz = rate_hz;
  if (auto c = (*camera)->configure(settings); !c || !(*camera)->start()) {
    finish();
    state.SkipWithError("aravis:127.0.0.1: configure/start failed");
    return;
  }
  Localizer localizer(seq.scenario.camera, seq.scenario.targets, LocalizerOptions{});
  std::vector<int64_t> latency;
  int64_t poses = 0, bad = 0;
  clockid_t server_clock{};
  const bool server_timed = pthread_getcpuclockid(server.native_handle(), &server_clock) == 0;
  const int64_t process0 = cpu_ns(CLOCK_PROCESS_CPUTIME_ID), server0 = server_timed ? cpu_ns(server_clock) : 0;
  for (auto _ : state) {
    auto f = (*camera)->grab(2000);
    if (!f || !*f) {
      state.SkipWithError("aravis:127.0.0.1: no frame within 2 s");
      break;
    }
    if ((*f)->bad) {
      ++bad;
      state.SetIterationTime(0);
      continue;
    }
    // The block id names the image the fake camera filled; the localizer gets that
    // frame's rig time (the buffer's stamp is the host's clock).
    const auto image = served.image((*f)->sequence);
    if (!image) {
      state.SkipWithError(("block " + std::to_string((*f)->sequence) + ": not a frame the camera filled").c_str());
      break;
    }
    const size_t i = *image;
    const auto out = localizer.process((*f)->image, seq.starts[i], seq.exposure_ns);
    if (!out) {
      state.SkipWithError(out.error().message.c_str());
      break;
    }
    std::string lines;
    for (const TargetPose& p : *out) lines += format_pose_line(PoseFormat::kCsv, static_cast<int64_t>(i), p);
    benchmark::DoNotOptimize(lines);
    poses += static_cast<int64_t>(out->size());
    const int64_t ns = host::monotonic_now_ns() - (*f)->camera_ns;
    latency.push_back(ns);
    state.SetIterationTime(static_cast<double>(ns) * 1e-9);
  }
  const int64_t process1 = cpu_ns(CLOCK_PROCESS_CPUTIME_ID), server1 = server_timed ? cpu_ns(server_clock) : 0;
  (*camera)->stop();
  const std::string transport = (*camera)->transport_summary();
  camera->reset();
  finish();
  state.counters["p50_ms"] = static_cast<double>(percentile(latency, 50)) / 1e6;
  state.counters["p99_ms"] = static_cast<double>(percentile(latency, 99)) / 1e6;
  state.counters["poses_per_frame"] = latency.empty() ? 0.0 : static_cast<double>(poses) / static_cast<double>(latency.size());
  state.counters["bad_buffers"] = static_cast<double>(bad);
  state.counters["resent"] = static_cast<double>(sent.packets_resent);
  const double frames = double(std::max<int64_t>(state.iterations(), 1));
  const double host_cpu_ms = double((process1 - process0) - (server1 - server0)) / 1e6 / frames;
  state.counters["host_cpu_ms"] = server_timed ? host_cpu_ms : 0.0;
  state.counters["headroom"] = server_timed && host_cpu_ms > 0 ? 1000.0 / rate_hz / host_cpu_ms : 0.0;
  state.SetLabel(transport);
}

void BM_LiveGvspLatency(benchmark::State& state) {
  run_live(state, bench::four_targets_sequence(), 100, state.range(0));
}

void BM_LiveGvspHeadroom(benchmark::State& state) {
  if (state.range(0) == 1280) {
    run_live(state, bench::scale_sequence(16), 60, 0);
  } else {
    run_live(state, bench::four_targets_sequence(), 100, 0);
  }
}

// 200 frames of the 240 rendered (2 s at 100 Hz), so that no image is served twice;
// 110 of the scale scene's 120.
BENCHMARK(BM_LiveGvspLatency)->Arg(0)->Arg(10)->Iterations(200)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LiveGvspHeadroom)->Arg(752)->Iterations(200)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LiveGvspHeadroom)->Arg(1280)->Iterations(110)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

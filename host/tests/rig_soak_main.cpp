// rig_soak [--seconds N | --long] [--no-localizer]: the soak of host_rig_reliability_test
// (rig_reliability.hpp) for N seconds of rig time (default 600; --long: 4 hours), a line a
// minute, the figures at the end; --no-localizer leaves out the minute's burst of frames
// (to tell the rig's memory from the localizer's). Exit 0 when every check holds.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "rig_reliability.hpp"

int main(int argc, char** argv) {
  using namespace tetrapulse::host::testing;
  long long seconds = 600;
  int burst_frames = 60;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--long") == 0) {
      seconds = 4 * 3600;
    } else if (std::strcmp(argv[i], "--no-localizer") == 0) {
      burst_frames = 0;
    } else if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = std::atoll(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: rig_soak [--seconds N | --long] [--no-localizer]\n");
      return 2;
    }
  }
  if (seconds < 60) {
    std::fprintf(stderr, "rig_soak: --seconds must be at least 60\n");
    return 2;
  }
  const SoakReport r = soak(mixed_sync_scenario(4), seconds, burst_frames, [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  });
  if (!r.failure.empty()) {
    std::fprintf(stderr, "rig_soak: %s\n", r.failure.c_str());
    return 1;
  }
  // The heap bound holds for the rig alone (--no-localizer); with the localizer its growth
  // is printed (docs/reliability.md).
  bool ok = r.exposures == r.expected_exposures && r.localizer.frame_errors == 0 &&
            (burst_frames > 0 || r.heap_kib_end - r.heap_kib_after_warmup < 64);
  std::printf("%llu/%llu exposures, %llu CAN syncs, heap in use %ld KiB after 60 s, %ld KiB at the end (RSS %ld,"
              " %ld KiB); localizer %llu frames, %llu refused, %llu poses\n",
              static_cast<unsigned long long>(r.exposures), static_cast<unsigned long long>(r.expected_exposures),
              static_cast<unsigned long long>(r.can_syncs), r.heap_kib_after_warmup, r.heap_kib_end,
              r.rss_kib_after_warmup, r.rss_kib_end,
              static_cast<unsigned long long>(r.localizer.frames),
              static_cast<unsigned long long>(r.localizer.frame_errors),
              static_cast<unsigned long long>(r.localizer.poses));
  for (size_t i = 0; i < r.boards.size(); ++i) {
    const SoakBoard& b = r.boards[i];
    const long long bound = b.sync == tetrapulse::sim::BoardSync::kGpio ? 1'000 : 50'000;
    ok = ok && b.not_locked == 0 && b.status_failures == 0 && b.max_abs_error_ns < bound;
    std::printf("board %zu: max |clock error| %.3f us, %llu reads not locked, %llu LED changes, %llu status failures\n",
                i, b.max_abs_error_ns / 1e3, static_cast<unsigned long long>(b.not_locked),
                static_cast<unsigned long long>(b.led_changes), static_cast<unsigned long long>(b.status_failures));
  }
  std::printf("%s\n", ok ? "soak passed" : "soak FAILED");
  return ok ? 0 : 1;
}

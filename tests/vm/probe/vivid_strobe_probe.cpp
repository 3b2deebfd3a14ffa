// vivid_strobe_probe: a strobe output for vivid's webcam, on a gpio-sim line, so
// that `tetrapulse record --sync-strobe` can be checked against the edges.
//
//   vivid_strobe_probe pulse --capture DEV --meta DEV --line-dir DIR --rate HZ
//                            --width-us W --lead-us L --seconds S --log FILE
//     Selects the webcam input at 640x480 GREY and HZ frames per second, streams
//     vivid's metadata capture node (filled in the same tick as the video frame,
//     stamped start of frame + 0.9 periods), and for every frame period after the
//     last one seen raises the gpio-sim line DIR (its sysfs `pull`) W µs long,
//     ending L µs before the earliest time the frame's tick can come: vivid's ticks
//     fall on a grid from the start of streaming, late by the jiffy they wait for
//     and by scheduling, never early, so the lower envelope of tick - n * period
//     is the grid. Logs each pulse: the period number and, for each edge, the
//     CLOCK_MONOTONIC before and after the sysfs write (the kernel stamps the edge
//     in between). Runs S seconds at most; SIGTERM or SIGINT ends it.
//   vivid_strobe_probe check --log FILE --edges FILE --recording DIR --tolerance-us T
//     Every frame of the recording must be stamped by one pulse: exposure start
//     inside (within T µs of) that pulse's rising-edge write, exposure length the
//     pulse's width within the same; pulses of successive frames strictly in
//     order. And against an independent clock: --edges lists the kernel's own
//     times of the line's interrupts (the irq_handler_entry trace event on
//     CLOCK_MONOTONIC, seconds); both ends of every exposure but the first must
//     lie within T µs of one of them. Under QEMU's TCG the first edge after the
//     recorder requests the line is, in most runs, stamped 200-300 µs after its
//     interrupt is entered, and no later edge is (12-23 µs): the emulator
//     translating the handler afresh once the recorder's start-up has filled its
//     code cache, not the kernel's stamp. That frame is held to its pulse's write
//     and its offset printed.
#include <fcntl.h>
#include <poll.h>
#include <csignal>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "tetrapulse/datasets/rig_dataset.hpp"
#include "v4l2_probe_util.hpp"

namespace {

using probe::die;
using probe::must;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

std::string need(const std::map<std::string, std::string>& a, const std::string& key) { return probe::need(a, key, "vivid_strobe_probe"); }

struct Pulse {
  int64_t period = 0;
  int64_t rise_before = 0, rise_after = 0, fall_before = 0, fall_after = 0;
};

int64_t write_pull(int fd, const char* value, int64_t* after) {
  const int64_t before = probe::monotonic_ns();
  if (pwrite(fd, value, std::strlen(value), 0) < 0) die(std::string("vivid_strobe_probe: writing pull: ") + std::strerror(errno));
  *after = probe::monotonic_ns();
  return before;
}

int pulse(const std::map<std::string, std::string>& a) {
  const std::string cap_dev = need(a, "capture"), meta_dev = need(a, "meta");
  const double rate = std::stod(need(a, "rate"));
  const int64_t width_ns = std::stoll(need(a, "width-us")) * 1000, lead_ns = std::stoll(need(a, "lead-us")) * 1000;
  const int64_t deadline = probe::monotonic_ns() + static_cast<int64_t>(std::stod(need(a, "seconds")) * 1e9);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);

  const int cap = open(cap_dev.c_str(), O_RDWR | O_CLOEXEC);
  if (cap < 0) die(cap_dev + ": " + std::strerror(errno));
  probe::select_input(cap, cap_dev, "Webcam");
  v4l2_format f{};
  f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  must(cap, VIDIOC_G_FMT, &f, cap_dev, "VIDIOC_G_FMT");
  f.fmt.pix.width = 640;
  f.fmt.pix.height = 480;
  f.fmt.pix.pixelformat = V4L2_PIX_FMT_GREY;
  must(cap, VIDIOC_S_FMT, &f, cap_dev, "VIDIOC_S_FMT");
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  parm.parm.capture.timeperframe.numerator = 1000;
  parm.parm.capture.timeperframe.denominator = static_cast<uint32_t>(std::lround(rate * 1000));
  must(cap, VIDIOC_S_PARM, &parm, cap_dev, "VIDIOC_S_PARM");
  const v4l2_fract tpf = parm.parm.capture.timeperframe;
  const double period_ns = 1e9 * tpf.numerator / tpf.denominator;
  // vivid stamps metadata at the tick plus 9/10 of the period (its cap_frame_eof_offset).
  const int64_t eof_ns = static_cast<int64_t>(period_ns) * 9 / 10;
  close(cap);

  const std::string pull_path = need(a, "line-dir") + "/pull";
  const int pull = open(pull_path.c_str(), O_WRONLY | O_CLOEXEC);
  if (pull < 0) die(pull_path + ": " + std::strerror(errno));
  int64_t ignored = 0;
  write_pull(pull, "pull-down", &ignored);

  const int meta = open(meta_dev.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (meta < 0) die(meta_dev + ": " + std::strerror(errno));
  v4l2_requestbuffers req{};
  req.count = 4;
  req.type = V4L2_BUF_TYPE_META_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  must(meta, VIDIOC_REQBUFS, &req, meta_dev, "VIDIOC_REQBUFS");
  for (uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_META_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = i;
    must(meta, VIDIOC_QBUF, &b, meta_dev, "VIDIOC_QBUF");
  }
  v4l2_buf_type type = V4L2_BUF_TYPE_META_CAPTURE;
  must(meta, VIDIOC_STREAMON, &type, meta_dev, "VIDIOC_STREAMON");

  std::ofstream log(need(a, "log"));
  if (!log) die("vivid_strobe_probe: cannot write " + need(a, "log"));
  std::optional<double> grid;  // lower envelope of tick - sequence * period (ns)
  int64_t last_pulsed = -1;
  uint64_t ticks = 0, pulses = 0, skipped = 0;
  while (!g_stop && probe::monotonic_ns() < deadline) {
    pollfd p{meta, POLLIN, 0};
    if (poll(&p, 1, 2000) == 0) die(meta_dev + ": no metadata buffer within 2 s");
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_META_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    if (probe::xioctl(meta, VIDIOC_DQBUF, &b) < 0) {
      if (errno == EAGAIN || errno == EINTR) continue;
      die(meta_dev + ": VIDIOC_DQBUF: " + std::strerror(errno));
    }
    const int64_t tick = static_cast<int64_t>(b.timestamp.tv_sec) * 1'000'000'000 + b.timestamp.tv_usec * 1000 - eof_ns;
    const int64_t seq = b.sequence;
    must(meta, VIDIOC_QBUF, &b, meta_dev, "VIDIOC_QBUF");
    ++ticks;
    const double phase = static_cast<double>(tick) - static_cast<double>(seq) * period_ns;
    grid = grid ? std::min(*grid, phase) : phase;
    // The next period whose pulse can still be given whole.
    int64_t k = std::max(seq + 1, last_pulsed + 1);
    const int64_t now = probe::monotonic_ns();
    auto fall_of = [&](int64_t n) { return static_cast<int64_t>(*grid + static_cast<double>(n) * period_ns) - lead_ns; };
    while (fall_of(k) - width_ns < now + 200'000) {
      ++k;
      ++skipped;
    }
    Pulse pl;
    pl.period = k;
    probe::sleep_until_ns(fall_of(k) - width_ns);
    pl.rise_before = write_pull(pull, "pull-up", &pl.rise_after);
    probe::sleep_until_ns(fall_of(k));
    pl.fall_before = write_pull(pull, "pull-down", &pl.fall_after);
    last_pulsed = k;
    ++pulses;
    log << pl.period << ' ' << pl.rise_before << ' ' << pl.rise_after << ' ' << pl.fall_before << ' ' << pl.fall_after << '\n';
    log.flush();
    if (pulses == 1) {
      std::printf("vivid_strobe_probe: pulsing, %.3f ms period, %lld µs wide, ending %lld µs before the tick\n", period_ns / 1e6,
                  static_cast<long long>(width_ns / 1000), static_cast<long long>(lead_ns / 1000));
      std::fflush(stdout);
    }
  }
  must(meta, VIDIOC_STREAMOFF, &type, meta_dev, "VIDIOC_STREAMOFF");
  std::printf("vivid_strobe_probe: %llu ticks seen, %llu pulses, %llu periods passed over (woken too late)\n",
              static_cast<unsigned long long>(ticks), static_cast<unsigned long long>(pulses),
              static_cast<unsigned long long>(skipped));
  return 0;
}

int check(const std::map<std::string, std::string>& a) {
  const int64_t tol = std::stoll(need(a, "tolerance-us")) * 1000;
  std::ifstream in(need(a, "log"));
  if (!in) die("vivid_strobe_probe: cannot read " + need(a, "log"));
  std::vector<Pulse> pulses;
  Pulse p;
  while (in >> p.period >> p.rise_before >> p.rise_after >> p.fall_before >> p.fall_after) pulses.push_back(p);
  if (pulses.empty()) die("vivid_strobe_probe: the log has no pulse");
  std::ifstream edges_in(need(a, "edges"));
  std::vector<int64_t> edges;
  for (double s = 0; edges_in >> s;) edges.push_back(std::llround(s * 1e9));
  if (edges.empty()) die("vivid_strobe_probe: " + need(a, "edges") + " lists no interrupt");
  std::sort(edges.begin(), edges.end());
  auto rec = tetrapulse::RigDataset::open(need(a, "recording"));
  if (!rec) die("vivid_strobe_probe: " + rec.error().what());
  const auto& frames = rec->frames();
  if (frames.empty()) die("vivid_strobe_probe: the recording has no frame");
  auto to_edge = [&](int64_t t) {
    int64_t best = INT64_MAX;
    for (int64_t e : edges) best = std::min<int64_t>(best, std::llabs(e - t));
    return best;
  };
  // The interrupt traced for an edge written from `written` on: the first at or after it.
  auto traced_from = [&](int64_t written) {
    const auto it = std::lower_bound(edges.begin(), edges.end(), written);
    return it == edges.end() ? INT64_MAX : *it;
  };
  int64_t worst_edge = 0, first_edge_off = 0;
  size_t late_traces = 0;
  // How far t lies outside [lo, hi] (0 inside).
  auto outside = [](int64_t t, int64_t lo, int64_t hi) { return std::max<int64_t>({0, lo - t, t - hi}); };
  int64_t worst = 0, worst_width = 0;
  std::vector<int64_t> brackets;
  size_t previous = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const int64_t start = frames[i].timestamp_ns;
    size_t best = 0;
    for (size_t j = 1; j < pulses.size(); ++j) {
      if (outside(start, pulses[j].rise_before, pulses[j].rise_after) < outside(start, pulses[best].rise_before, pulses[best].rise_after)) best = j;
    }
    const Pulse& q = pulses[best];
    const int64_t off = outside(start, q.rise_before, q.rise_after);
    const int64_t width_off = outside(frames[i].exposure_ns, q.fall_before - q.rise_after, q.fall_after - q.rise_before);
    if (off > tol || width_off > tol) {
      die(cv::format("strobe: frame %lld (exposure start %lld ns, %lld ns long) matches no pulse: nearest rising edge written "
                     "%lld..%lld ns, falling %lld..%lld ns",
                     static_cast<long long>(frames[i].frame), static_cast<long long>(start),
                     static_cast<long long>(frames[i].exposure_ns), static_cast<long long>(q.rise_before),
                     static_cast<long long>(q.rise_after), static_cast<long long>(q.fall_before), static_cast<long long>(q.fall_after)));
    }
    if (i > 0 && best <= previous) {
      die(cv::format("strobe: frame %lld is stamped by a pulse no later than the frame before it", static_cast<long long>(frames[i].frame)));
    }
    const int64_t edge_off = std::max(to_edge(start), to_edge(start + frames[i].exposure_ns));
    if (i == 0) first_edge_off = edge_off;
    // The tracer is a clock only where its entry followed the edge's write promptly: in a
    // loaded TCG guest the handler thread it traces once ran 1.7 ms after the write had
    // returned, while the stamp lay inside the write. Such a frame is held to its write
    // alone (above), and counted.
    const bool trace_late = traced_from(q.rise_before) - q.rise_after > tol || traced_from(q.fall_before) - q.fall_after > tol;
    late_traces += i > 0 && trace_late;
    if (i > 0 && !trace_late && edge_off > tol) {
      die(cv::format("strobe: frame %lld: its exposure starts %.1f µs and ends %.1f µs from the nearest interrupt the "
                     "kernel traced (start %lld ns, %lld ns long)",
                     static_cast<long long>(frames[i].frame), static_cast<double>(to_edge(start)) / 1e3,
                     static_cast<double>(to_edge(start + frames[i].exposure_ns)) / 1e3, static_cast<long long>(start),
                     static_cast<long long>(frames[i].exposure_ns)));
    }
    if (i > 0 && !trace_late) worst_edge = std::max(worst_edge, edge_off);
    previous = best;
    worst = std::max(worst, off);
    worst_width = std::max(worst_width, width_off);
    brackets.push_back(q.rise_after - q.rise_before);
  }
  if (3 * late_traces > frames.size()) {
    die(cv::format("strobe: for %zu of %zu frames the kernel traced the strobe's interrupt over %lld µs after its write: "
                   "no independent clock left", late_traces, frames.size(), static_cast<long long>(tol / 1000)));
  }
  std::sort(brackets.begin(), brackets.end());
  std::printf("strobe: %zu frames, each stamped by its own pulse: both exposure ends within %.1f µs of the kernel's traced "
              "interrupts (%zu traced; the first frame %.1f µs; %zu frames whose interrupts were traced late held to "
              "their writes alone); start at most %.1f µs outside the rising-edge write (writes took p50 %.1f µs, max "
              "%.1f µs), length at most %.1f µs off; tolerance %lld µs; %zu pulses given\n",
              frames.size(), static_cast<double>(worst_edge) / 1e3, edges.size(), static_cast<double>(first_edge_off) / 1e3,
              late_traces,
              static_cast<double>(worst) / 1e3,
              static_cast<double>(brackets[brackets.size() / 2]) / 1e3, static_cast<double>(brackets.back()) / 1e3,
              static_cast<double>(worst_width) / 1e3, static_cast<long long>(tol / 1000), pulses.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) die("usage: vivid_strobe_probe pulse|check --option value...");
  const std::string verb = argv[1];
  const auto a = probe::parse_options(argc, argv, 2, "vivid_strobe_probe");
  if (verb == "pulse") return pulse(a);
  if (verb == "check") return check(a);
  die("vivid_strobe_probe: unknown command " + verb);
}

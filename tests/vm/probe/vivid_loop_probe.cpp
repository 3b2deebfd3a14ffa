// vivid_loop_probe: frames out through vivid's video output, back through its
// video capture (drivers/media/test-drivers/vivid, "Video Looping" in its
// documentation), so a V4L2 recorder can be checked against what was sent.
//
//   vivid_loop_probe connect --capture DEV
//     Selects HDMI input 000-0 and connects it to HDMI output 000-0 at 640x480p60,
//     GREY, without OSD text (the loop's conditions on the capture side; done
//     before the recorder streams, as vivid refuses them while it does).
//   vivid_loop_probe send --output DEV --dataset DIR --count N --hold K --lead L
//                         --trail T --sent OUT [--await REC]
//     Sets HDMI output 000-0 to the same, then streams frame 0 for L output frames,
//     frames 1..N for K output frames each and frame N+1 for T: the first N+2
//     images of the rig dataset DIR, 640 columns cut from their middle, each with
//     its number as a barcode in row 0. Writes what it sent as OUT/sent-NNN.png.
//     With --await, a frame is not followed by the next (nor the last ended) until
//     the recording REC being written holds it: vivid shows the last buffer queued
//     for as long as it takes. (Without it, a recorder slowed by the emulated
//     machine for longer than K output frames lost a frame now and then, and the
//     test with it, though the recorder only drops what it cannot keep up with.)
//   vivid_loop_probe check --sent OUT --count N --recording DIR
//     Every frame of the recording between the first and the last looped one must
//     be one of the sent frames, byte for byte; the frames seen, once repeats are
//     folded, must be 0, 1, ..., N+1 (nothing lost, nothing out of order); the
//     exposure stamps strictly increasing. Frames before the loop engaged and
//     after it ended are vivid's test pattern and are only counted.
//
// The trailer's last buffer stays queued when streaming stops (vivid hands one
// back only when another is pending). A buffer the output hands back is rewritten only after three more came back:
// the capture side copies from the output queue's head without a lock, so a
// buffer just returned may still be read.
#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tetrapulse/datasets/rig_dataset.hpp"
#include "v4l2_probe_util.hpp"

namespace {

using probe::die;
using probe::must;

constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr int kBarBits = 16;
constexpr int kBarPixels = 4;  // per bit

std::string need(const std::map<std::string, std::string>& a, const std::string& key) { return probe::need(a, key, "vivid_loop_probe"); }

int need_int(const std::map<std::string, std::string>& a, const std::string& key) { return std::stoi(need(a, key)); }

std::string sent_path(const std::string& dir, int index) { return cv::format("%s/sent-%03d.png", dir.c_str(), index); }

void put_barcode(cv::Mat& image, int index) {
  for (int b = 0; b < kBarBits; ++b) {
    const uchar v = (index >> b) & 1 ? 255 : 0;
    for (int x = 0; x < kBarPixels; ++x) image.at<uchar>(0, b * kBarPixels + x) = v;
  }
}

// -1 when row 0 holds no clean barcode.
int read_barcode(const cv::Mat& image) {
  int index = 0;
  for (int b = 0; b < kBarBits; ++b) {
    const uchar v = image.at<uchar>(0, b * kBarPixels);
    for (int x = 1; x < kBarPixels; ++x) {
      if (image.at<uchar>(0, b * kBarPixels + x) != v) return -1;
    }
    if (v == 255) index |= 1 << b;
    else if (v != 0) return -1;
  }
  return index;
}

v4l2_dv_timings timings_640x480p60(int fd, const std::string& device) {
  for (uint32_t i = 0;; ++i) {
    v4l2_enum_dv_timings e{};
    e.index = i;
    if (probe::xioctl(fd, VIDIOC_ENUM_DV_TIMINGS, &e) < 0) break;
    const v4l2_bt_timings& bt = e.timings.bt;
    if (bt.width == kWidth && bt.height == kHeight && !bt.interlaced && bt.pixelclock < 26'000'000) return e.timings;
  }
  die(device + ": VIDIOC_ENUM_DV_TIMINGS offers no 640x480p60");
}

void set_grey_format(int fd, const std::string& device, v4l2_buf_type type) {
  v4l2_format f{};
  f.type = type;
  must(fd, VIDIOC_G_FMT, &f, device, "VIDIOC_G_FMT");
  f.fmt.pix.width = kWidth;
  f.fmt.pix.height = kHeight;
  f.fmt.pix.pixelformat = V4L2_PIX_FMT_GREY;
  f.fmt.pix.field = V4L2_FIELD_NONE;
  must(fd, VIDIOC_S_FMT, &f, device, "VIDIOC_S_FMT");
  if (f.fmt.pix.width != kWidth || f.fmt.pix.height != kHeight || f.fmt.pix.pixelformat != V4L2_PIX_FMT_GREY) {
    die(device + ": asked GREY 640x480, got " + probe::fourcc_text(f.fmt.pix.pixelformat) + " " +
        std::to_string(f.fmt.pix.width) + "x" + std::to_string(f.fmt.pix.height));
  }
}

// The frames (by barcode) that a recorder has written so far to REC/frames/*.png. A
// file it is still writing (no IEND chunk at its end yet) is read again at the next look.
class RecordingWatch {
 public:
  explicit RecordingWatch(std::string dir) : frames_(std::move(dir) + "/frames") {}

  bool holds(int index) {
    if (seen_.count(index)) return true;
    std::error_code ec;
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(frames_, ec))
      if (e.path().extension() == ".png" && !read_.count(e.path().string())) names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) {
      std::ifstream in(name, std::ios::binary);
      const std::vector<uchar> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      static constexpr uchar kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
      if (bytes.size() < sizeof kIend || !std::equal(std::begin(kIend), std::end(kIend), bytes.end() - sizeof kIend)) continue;
      const cv::Mat image = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
      if (image.empty() || image.cols < kBarBits * kBarPixels) continue;
      read_.insert(name);
      seen_.insert(read_barcode(image));
    }
    return seen_.count(index) > 0;
  }

 private:
  std::string frames_;
  std::set<std::string> read_;
  std::set<int> seen_;
};

struct OutBuffer {
  uint8_t* data = nullptr;
  size_t length = 0;
};

int connect(const std::map<std::string, std::string>& a) {
  const std::string cap_dev = need(a, "capture");
  const int cap = open(cap_dev.c_str(), O_RDWR | O_CLOEXEC);
  if (cap < 0) die(cap_dev + ": " + std::strerror(errno));
  probe::select_input(cap, cap_dev, "HDMI");
  v4l2_dv_timings t = timings_640x480p60(cap, cap_dev);
  must(cap, VIDIOC_S_DV_TIMINGS, &t, cap_dev, "VIDIOC_S_DV_TIMINGS");
  probe::set_menu(cap, cap_dev, "HDMI 000-0 Is Connected To", "Output HDMI 000-0");
  probe::set_menu(cap, cap_dev, "OSD Text Mode", "None");
  set_grey_format(cap, cap_dev, V4L2_BUF_TYPE_VIDEO_CAPTURE);
  close(cap);
  std::printf("vivid_loop_probe: %s: HDMI input connected to HDMI output 000-0, 640x480p60 GREY\n", cap_dev.c_str());
  return 0;
}

int send(const std::map<std::string, std::string>& a) {
  const std::string out_dev = need(a, "output"), sent_dir = need(a, "sent");
  const int count = need_int(a, "count"), hold = need_int(a, "hold"), lead = need_int(a, "lead"), trail = need_int(a, "trail");
  auto dataset = tetrapulse::RigDataset::open(need(a, "dataset"));
  if (!dataset) die("vivid_loop_probe: " + dataset.error().what());
  if (static_cast<int>(dataset->frames().size()) < count + 2) die("vivid_loop_probe: the dataset has too few frames");
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count + 2; ++i) {
    auto image = dataset->load_image(static_cast<size_t>(i), tetrapulse::RigDataset::ImageMode::kGrey);
    if (!image) die("vivid_loop_probe: " + image.error().what());
    if (image->type() != CV_8UC1 || image->cols < kWidth || image->rows != kHeight) die("vivid_loop_probe: need 8-bit frames 480 rows high");
    cv::Mat f = (*image)(cv::Rect((image->cols - kWidth) / 2, 0, kWidth, kHeight)).clone();
    put_barcode(f, i);
    if (!cv::imwrite(sent_path(sent_dir, i), f)) die("vivid_loop_probe: cannot write " + sent_path(sent_dir, i));
    frames.push_back(f);
  }

  const int out = open(out_dev.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (out < 0) die(out_dev + ": " + std::strerror(errno));
  probe::select_output(out, out_dev, "HDMI");
  v4l2_dv_timings t = timings_640x480p60(out, out_dev);
  must(out, VIDIOC_S_DV_TIMINGS, &t, out_dev, "VIDIOC_S_DV_TIMINGS");
  set_grey_format(out, out_dev, V4L2_BUF_TYPE_VIDEO_OUTPUT);
  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
  must(out, VIDIOC_G_FMT, &fmt, out_dev, "VIDIOC_G_FMT");
  const size_t stride = fmt.fmt.pix.bytesperline;

  v4l2_requestbuffers req{};
  req.count = 8;
  req.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
  req.memory = V4L2_MEMORY_MMAP;
  must(out, VIDIOC_REQBUFS, &req, out_dev, "VIDIOC_REQBUFS");
  if (req.count < 5) die(out_dev + ": only " + std::to_string(req.count) + " output buffers");
  std::vector<OutBuffer> buffers(req.count);
  for (uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = i;
    must(out, VIDIOC_QUERYBUF, &b, out_dev, "VIDIOC_QUERYBUF");
    void* p = mmap(nullptr, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, out, b.m.offset);
    if (p == MAP_FAILED) die(out_dev + ": mmap: " + std::strerror(errno));
    buffers[i] = {static_cast<uint8_t*>(p), b.length};
  }

  std::vector<int> schedule(static_cast<size_t>(lead), 0);
  for (int i = 1; i <= count; ++i) schedule.insert(schedule.end(), static_cast<size_t>(hold), i);
  schedule.insert(schedule.end(), static_cast<size_t>(trail), count + 1);

  size_t next = 0;
  auto queue = [&](uint32_t index) {
    const cv::Mat& f = frames[static_cast<size_t>(schedule[next++])];
    for (int y = 0; y < kHeight; ++y) std::memcpy(buffers[index].data + y * stride, f.ptr(y), kWidth);
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = index;
    b.bytesused = fmt.fmt.pix.sizeimage;
    b.field = V4L2_FIELD_NONE;
    must(out, VIDIOC_QBUF, &b, out_dev, "VIDIOC_QBUF");
  };
  constexpr size_t kSpare = 3;
  std::deque<uint32_t> returned;
  int queued = 0;
  for (uint32_t i = 0; i < req.count; ++i) {
    if (i + kSpare < req.count && next < schedule.size()) {
      queue(i);
      ++queued;
    } else {
      returned.push_back(i);
    }
  }
  v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
  must(out, VIDIOC_STREAMON, &type, out_dev, "VIDIOC_STREAMON");
  const int64_t start = probe::monotonic_ns();
  uint64_t shown = 0;
  std::optional<RecordingWatch> watch;
  if (a.count("await")) watch.emplace(a.at("await"));
  constexpr int64_t kAwaitNs = 60'000'000'000;
  int64_t awaiting_since = 0;
  // Waits (with the frame on show) until the recording holds frame `index`; false
  // while it does not yet.
  auto recorded = [&](int index) {
    if (!watch || watch->holds(index)) {
      awaiting_since = 0;
      return true;
    }
    const int64_t now = probe::monotonic_ns();
    if (awaiting_since == 0) awaiting_since = now;
    if (now - awaiting_since > kAwaitNs) die(cv::format("vivid_loop_probe: the recording holds no frame %d after 60 s", index));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return false;
  };
  // Whether the next buffer starts another frame: it may go only once the recording
  // holds this one (meanwhile the buffers queued drain to the last, which vivid keeps
  // showing).
  auto starts_a_frame = [&] { return next > 0 && next < schedule.size() && schedule[next] != schedule[next - 1]; };
  // vivid's output keeps its last buffer (it hands one back only when another is
  // pending, for the loop's sake): done when only the trailer's last one is left.
  while (next < schedule.size() || queued > 1) {
    if (queued <= 1 && starts_a_frame()) {
      if (!recorded(schedule[next - 1])) continue;
      queue(returned.front());
      returned.pop_front();
      ++queued;
      continue;
    }
    pollfd p{out, POLLOUT, 0};
    if (poll(&p, 1, 5000) <= 0) die(out_dev + ": no output buffer came back within 5 s");
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_OUTPUT;
    b.memory = V4L2_MEMORY_MMAP;
    if (probe::xioctl(out, VIDIOC_DQBUF, &b) < 0) {
      if (errno == EAGAIN) continue;
      die(out_dev + ": VIDIOC_DQBUF: " + std::strerror(errno));
    }
    --queued;
    ++shown;
    returned.push_back(b.index);
    if (returned.size() > kSpare && next < schedule.size() && (!starts_a_frame() || recorded(schedule[next - 1]))) {
      queue(returned.front());
      returned.pop_front();
      ++queued;
    }
  }
  while (!recorded(count + 1)) continue;  // the trailer too, before the output stops
  must(out, VIDIOC_STREAMOFF, &type, out_dev, "VIDIOC_STREAMOFF");
  std::printf("vivid_loop_probe: %llu output frames in %.2f s (frames 0..%d, %d each, %d lead, %d trail)\n",
              static_cast<unsigned long long>(shown), static_cast<double>(probe::monotonic_ns() - start) / 1e9, count + 1,
              hold, lead, trail);
  close(out);
  return 0;
}

int check(const std::map<std::string, std::string>& a) {
  const std::string sent_dir = need(a, "sent");
  const int count = need_int(a, "count");
  std::vector<cv::Mat> sent;
  for (int i = 0; i < count + 2; ++i) {
    cv::Mat f = cv::imread(sent_path(sent_dir, i), cv::IMREAD_GRAYSCALE);
    if (f.empty()) die("vivid_loop_probe: cannot read " + sent_path(sent_dir, i));
    sent.push_back(f);
  }
  auto rec = tetrapulse::RigDataset::open(need(a, "recording"));
  if (!rec) die("vivid_loop_probe: " + rec.error().what());
  const auto& frames = rec->frames();
  std::vector<int> seen(frames.size(), -1);
  for (size_t i = 0; i < frames.size(); ++i) {
    auto image = rec->load_image(i, tetrapulse::RigDataset::ImageMode::kGrey);
    if (!image) die("vivid_loop_probe: " + image.error().what());
    if (image->type() != CV_8UC1 || image->size() != sent[0].size()) continue;
    const int index = read_barcode(*image);
    if (index >= 0 && index < count + 2 && cv::norm(*image, sent[static_cast<size_t>(index)], cv::NORM_INF) == 0) {
      seen[i] = index;
    }
    if (i > 0 && frames[i].timestamp_ns <= frames[i - 1].timestamp_ns) {
      die(cv::format("vivid loop: frame %lld is stamped no later than the frame before it", static_cast<long long>(frames[i].frame)));
    }
  }
  size_t first = 0, last = frames.size();
  while (first < frames.size() && seen[first] < 0) ++first;
  while (last > first && seen[last - 1] < 0) --last;
  if (first == last) die(cv::format("vivid loop: none of the %zu frames recorded is a frame sent", frames.size()));
  std::vector<int> folded;
  std::vector<int> repeats(static_cast<size_t>(count + 2), 0);
  for (size_t i = first; i < last; ++i) {
    if (seen[i] < 0) {
      die(cv::format("vivid loop: recorded frame %lld (row %zu), inside the loop, matches no frame sent",
                     static_cast<long long>(frames[i].frame), i + 1));
    }
    if (folded.empty() || folded.back() != seen[i]) folded.push_back(seen[i]);
    ++repeats[static_cast<size_t>(seen[i])];
  }
  std::string order;
  for (int v : folded) order += (order.empty() ? "" : " ") + std::to_string(v);
  bool in_order = static_cast<int>(folded.size()) == count + 2;
  for (size_t i = 0; in_order && i < folded.size(); ++i) in_order = folded[i] == static_cast<int>(i);
  if (!in_order) die("vivid loop: frames came back as " + order + ", sent 0.." + std::to_string(count + 1));
  int least = 1 << 30, most = 0;
  for (int i = 1; i <= count; ++i) {
    least = std::min(least, repeats[static_cast<size_t>(i)]);
    most = std::max(most, repeats[static_cast<size_t>(i)]);
  }
  std::printf("vivid loop: %zu frames recorded (%zu test pattern before the loop, %zu after); all %d frames sent came back "
              "byte for byte, in order, none lost; frames 1..%d recorded %d to %d times each; stamps strictly increasing\n",
              frames.size(), first, frames.size() - last, count + 2, count, least, most);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) die("usage: vivid_loop_probe connect|send|check --option value...");
  const std::string verb = argv[1];
  const auto a = probe::parse_options(argc, argv, 2, "vivid_loop_probe");
  if (verb == "connect") return connect(a);
  if (verb == "send") return send(a);
  if (verb == "check") return check(a);
  die("vivid_loop_probe: unknown command " + verb);
}

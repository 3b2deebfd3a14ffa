// Camera through V4L2: mmap streaming, the kernel's buffer timestamps.
//
// V4L2 has no GenICam features: exposure, gain and frame rate map onto the
// standard controls (V4L2_CID_EXPOSURE_ABSOLUTE in 100 µs units, V4L2_CID_GAIN in
// the driver's units, VIDIOC_S_PARM); hardware trigger and strobe lines have no
// standard control, so asking for them is one line naming what is missing.
#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include <opencv2/imgproc.hpp>

#include "tetrapulse/host/camera.hpp"
#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {
namespace {

int xioctl(int fd, unsigned long request, void* arg) {
  int r = 0;
  do r = ioctl(fd, request, arg);
  while (r < 0 && errno == EINTR);
  return r;
}

std::string errno_text() { return std::strerror(errno); }

class V4l2Camera final : public Camera {
 public:
  V4l2Camera(std::string name, int fd) : Camera(std::move(name)), fd_(fd) {}
  ~V4l2Camera() override {
    do_stop();
    for (const Mapping& m : buffers_) munmap(m.start, m.length);
    close(fd_);
  }

 private:
  struct Mapping {
    void* start = nullptr;
    size_t length = 0;
  };

  bool set_control(uint32_t id, int32_t value) {
    v4l2_control c{};
    c.id = id;
    c.value = value;
    return xioctl(fd_, VIDIOC_S_CTRL, &c) == 0;
  }

  HostResult<std::vector<std::string>> do_configure(const CameraSettings& s) override {
    std::vector<std::string> notes;
    v4l2_format fmt{};
    fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd_, VIDIOC_G_FMT, &fmt) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_G_FMT: " + errno_text());
    if (s.width) fmt.fmt.pix.width = static_cast<uint32_t>(*s.width);
    if (s.height) fmt.fmt.pix.height = static_cast<uint32_t>(*s.height);
    if (s.pixel_format == "Mono8") fmt.fmt.pix.pixelformat = V4L2_PIX_FMT_GREY;
    else if (s.pixel_format == "Mono16") fmt.fmt.pix.pixelformat = V4L2_PIX_FMT_Y16;
    else if (s.pixel_format == "YUYV" || s.pixel_format == "colour") fmt.fmt.pix.pixelformat = V4L2_PIX_FMT_YUYV;
    else if (!s.pixel_format.empty()) notes.push_back(name() + ": pixel format " + s.pixel_format + " has no V4L2 mapping (Mono8, Mono16, YUYV)");
    const uint32_t asked = fmt.fmt.pix.pixelformat;
    if (xioctl(fd_, VIDIOC_S_FMT, &fmt) < 0) return host_error(HostErrorKind::kBadInput, name(), "VIDIOC_S_FMT: " + errno_text());
    if (fmt.fmt.pix.pixelformat != asked && !s.pixel_format.empty()) {
      notes.push_back(name() + ": device does not offer pixel format " + s.pixel_format);
    }
    if (s.exposure_us) {
      set_control(V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL);
      if (!set_control(V4L2_CID_EXPOSURE_ABSOLUTE, static_cast<int32_t>(std::lround(*s.exposure_us / 100.0)))) {
        notes.push_back(name() + ": device has no control exposure_time_absolute");
      }
    }
    if (s.gain_db && !set_control(V4L2_CID_GAIN, static_cast<int32_t>(std::lround(*s.gain_db)))) {
      notes.push_back(name() + ": device has no control gain");
    }
    if (s.frame_rate_hz) {
      v4l2_streamparm parm{};
      parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      parm.parm.capture.timeperframe.numerator = 1000;
      parm.parm.capture.timeperframe.denominator = static_cast<uint32_t>(std::lround(*s.frame_rate_hz * 1000));
      if (xioctl(fd_, VIDIOC_S_PARM, &parm) < 0) notes.push_back(name() + ": device does not set its frame rate");
    }
    if (s.packet_size) notes.push_back(name() + ": V4L2 has no feature GevSCPSPacketSize");
    if (s.trigger_source && s.trigger_required) {
      return host_error(HostErrorKind::kBadInput, name(),
                        "V4L2 has no hardware trigger (TriggerSource): the host cannot trigger this camera; wire its strobe "
                        "to --sync-strobe, or run without sync");
    }
    if (s.trigger_source) notes.push_back(name() + ": V4L2 has no feature TriggerSource (free-running)");
    if (s.strobe_line) notes.push_back(name() + ": V4L2 has no feature LineSource (no strobe output)");
    format_ = fmt.fmt.pix;
    return notes;
  }

  HostResult<void> do_start() override {
    if (format_.width == 0) {
      v4l2_format fmt{};
      fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      if (xioctl(fd_, VIDIOC_G_FMT, &fmt) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_G_FMT: " + errno_text());
      format_ = fmt.fmt.pix;
    }
    v4l2_requestbuffers req{};
    req.count = 4;
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (xioctl(fd_, VIDIOC_REQBUFS, &req) < 0 || req.count < 2) {
      return host_error(HostErrorKind::kOpenFailed, name(), "VIDIOC_REQBUFS (mmap streaming): " + errno_text());
    }
    for (uint32_t i = 0; i < req.count; ++i) {
      v4l2_buffer b{};
      b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      b.memory = V4L2_MEMORY_MMAP;
      b.index = i;
      if (xioctl(fd_, VIDIOC_QUERYBUF, &b) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_QUERYBUF: " + errno_text());
      void* start = mmap(nullptr, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, b.m.offset);
      if (start == MAP_FAILED) return host_error(HostErrorKind::kIo, name(), "mmap: " + errno_text());
      buffers_.push_back({start, b.length});
      if (xioctl(fd_, VIDIOC_QBUF, &b) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_QBUF: " + errno_text());
    }
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(fd_, VIDIOC_STREAMON, &type) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_STREAMON: " + errno_text());
    streaming_ = true;
    return {};
  }

  std::optional<cv::Mat> image_of(const uint8_t* data, size_t used, std::string* why) const {
    const int w = static_cast<int>(format_.width), h = static_cast<int>(format_.height);
    const size_t stride = format_.bytesperline;
    const size_t need = stride * static_cast<size_t>(h);
    if (used < need) {
      *why = "buffer of " + std::to_string(used) + " bytes, " + std::to_string(need) + " expected";
      return std::nullopt;
    }
    uint8_t* p = const_cast<uint8_t*>(data);
    switch (format_.pixelformat) {
      case V4L2_PIX_FMT_GREY: return cv::Mat(h, w, CV_8UC1, p, stride).clone();
      case V4L2_PIX_FMT_Y16: return cv::Mat(h, w, CV_16UC1, p, stride).clone();
      case V4L2_PIX_FMT_YUYV: {
        cv::Mat bgr;
        cv::cvtColor(cv::Mat(h, w, CV_8UC2, p, stride), bgr, cv::COLOR_YUV2BGR_YUYV);
        return bgr;
      }
      case V4L2_PIX_FMT_RGB24: {
        cv::Mat bgr;
        cv::cvtColor(cv::Mat(h, w, CV_8UC3, p, stride), bgr, cv::COLOR_RGB2BGR);
        return bgr;
      }
      default:
        *why = cv::format("pixel format %.4s is not read (GREY, Y16, YUYV, RGB3)", reinterpret_cast<const char*>(&format_.pixelformat));
        return std::nullopt;
    }
  }

  HostResult<std::optional<CameraFrame>> do_grab(int timeout_ms) override {
    if (!streaming_) return host_error(HostErrorKind::kIo, name(), "grab before start");
    pollfd pfd{fd_, POLLIN, 0};
    const int ready = poll(&pfd, 1, timeout_ms);
    if (ready < 0 && errno != EINTR) return host_error(HostErrorKind::kIo, name(), "poll: " + errno_text());
    if (ready <= 0) return std::optional<CameraFrame>{};
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    if (xioctl(fd_, VIDIOC_DQBUF, &b) < 0) {
      if (errno == EAGAIN) return std::optional<CameraFrame>{};
      return host_error(HostErrorKind::kIo, name(), "VIDIOC_DQBUF: " + errno_text());
    }
    CameraFrame f;
    f.sequence = b.sequence;
    // Drivers stamp on CLOCK_MONOTONIC (V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC), at the
    // start of exposure or at the end of frame per V4L2_BUF_FLAG_TSTAMP_SRC_*.
    f.camera_ns = static_cast<int64_t>(b.timestamp.tv_sec) * 1'000'000'000 + static_cast<int64_t>(b.timestamp.tv_usec) * 1000;
    f.arrived_ns = monotonic_now_ns();
    if (b.flags & V4L2_BUF_FLAG_ERROR) {
      f.bad = name() + ": frame " + std::to_string(b.sequence) + ": driver flagged the buffer as corrupt";
    } else if (b.index < buffers_.size()) {
      std::string why;
      auto image = image_of(static_cast<const uint8_t*>(buffers_[b.index].start), b.bytesused, &why);
      if (image) f.image = std::move(*image);
      else f.bad = name() + ": frame " + std::to_string(b.sequence) + ": " + why;
    }
    if (xioctl(fd_, VIDIOC_QBUF, &b) < 0) return host_error(HostErrorKind::kIo, name(), "VIDIOC_QBUF: " + errno_text());
    return std::optional<CameraFrame>(std::move(f));
  }

  void do_stop() override {
    if (!streaming_) return;
    streaming_ = false;
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(fd_, VIDIOC_STREAMOFF, &type);
  }

  int fd_;
  v4l2_pix_format format_{};
  std::vector<Mapping> buffers_;
  bool streaming_ = false;
};

}  // namespace

HostResult<std::unique_ptr<Camera>> open_v4l2_camera(const std::string& device) {
  const std::string name = "v4l2:" + device;
  const int fd = open(device.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return host_error(errno == ENOENT ? HostErrorKind::kNotFound : HostErrorKind::kOpenFailed, name, errno_text());
  }
  v4l2_capability cap{};
  if (xioctl(fd, VIDIOC_QUERYCAP, &cap) < 0 || !(cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities) ||
      !((cap.capabilities & V4L2_CAP_DEVICE_CAPS ? cap.device_caps : cap.capabilities) & V4L2_CAP_STREAMING)) {
    close(fd);
    return host_error(HostErrorKind::kOpenFailed, name, "not a V4L2 capture device with streaming I/O");
  }
  return std::unique_ptr<Camera>(new V4l2Camera(name, fd));
}

}  // namespace tetrapulse::host

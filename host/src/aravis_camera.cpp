// Camera through Aravis 0.8 (GenICam: GigE Vision and USB3 Vision).
//
// An IPv4 address is opened directly (arv_gv_device_new), never through Aravis'
// device list: building that list broadcasts GigE Vision discovery on every
// interface. Only a non-address device id goes through arv_camera_new, which has to
// look the id up.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <arv.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "tetrapulse/host/camera.hpp"
#include "tetrapulse/host/rig_clock.hpp"

namespace tetrapulse::host {
namespace {

std::string take_message(GError* e) {
  std::string m = e ? e->message : "unknown error";
  if (e) g_error_free(e);
  return m;
}

// The local address the kernel would send to `camera` from: a connected UDP socket
// routes without sending anything. The camera streams to this address.
std::optional<std::string> local_address_towards(const std::string& camera) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(3956);  // GVCP
  if (inet_pton(AF_INET, camera.c_str(), &to.sin_addr) != 1) return std::nullopt;
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return std::nullopt;
  sockaddr_in from{};
  socklen_t len = sizeof from;
  std::optional<std::string> out;
  if (connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&from), &len) == 0) {
    char text[INET_ADDRSTRLEN] = {};
    if (inet_ntop(AF_INET, &from.sin_addr, text, sizeof text)) out = text;
  }
  close(fd);
  return out;
}

bool is_ipv4(const std::string& s) {
  in_addr a{};
  return inet_pton(AF_INET, s.c_str(), &a) == 1;
}

// The buffer as an image (nullopt: a format this code does not read).
std::optional<cv::Mat> image_of(ArvBuffer* buffer, std::string* why) {
  size_t size = 0;
  const void* data = arv_buffer_get_data(buffer, &size);
  const int w = arv_buffer_get_image_width(buffer);
  const int h = arv_buffer_get_image_height(buffer);
  const ArvPixelFormat format = arv_buffer_get_image_pixel_format(buffer);
  const size_t bits = ARV_PIXEL_FORMAT_BIT_PER_PIXEL(format);
  const size_t expected = static_cast<size_t>(w) * static_cast<size_t>(h) * bits / 8;
  if (w <= 0 || h <= 0 || data == nullptr || size < expected) {
    *why = "buffer of " + std::to_string(size) + " bytes for a " + std::to_string(w) + "x" + std::to_string(h) + " image";
    return std::nullopt;
  }
  void* pixels = const_cast<void*>(data);
  switch (format) {
    case ARV_PIXEL_FORMAT_MONO_8:
      return cv::Mat(h, w, CV_8UC1, pixels).clone();
    case ARV_PIXEL_FORMAT_MONO_10:
    case ARV_PIXEL_FORMAT_MONO_12:
    case ARV_PIXEL_FORMAT_MONO_14:
    case ARV_PIXEL_FORMAT_MONO_16:
      return cv::Mat(h, w, CV_16UC1, pixels).clone();
    case ARV_PIXEL_FORMAT_RGB_8_PACKED: {
      cv::Mat bgr;
      cv::cvtColor(cv::Mat(h, w, CV_8UC3, pixels), bgr, cv::COLOR_RGB2BGR);
      return bgr;
    }
    case ARV_PIXEL_FORMAT_BGR_8_PACKED:
      return cv::Mat(h, w, CV_8UC3, pixels).clone();
    case ARV_PIXEL_FORMAT_BAYER_RG_8:
    case ARV_PIXEL_FORMAT_BAYER_GR_8:
    case ARV_PIXEL_FORMAT_BAYER_GB_8:
    case ARV_PIXEL_FORMAT_BAYER_BG_8: {
      // GenICam names the first two pixels of the first row; OpenCV names the
      // second and third of the second row, hence the crossed codes.
      const int code = format == ARV_PIXEL_FORMAT_BAYER_RG_8   ? cv::COLOR_BayerBG2BGR
                       : format == ARV_PIXEL_FORMAT_BAYER_GR_8 ? cv::COLOR_BayerGB2BGR
                       : format == ARV_PIXEL_FORMAT_BAYER_GB_8 ? cv::COLOR_BayerGR2BGR
                                                               : cv::COLOR_BayerRG2BGR;
      cv::Mat bgr;
      cv::cvtColor(cv::Mat(h, w, CV_8UC1, pixels), bgr, code);
      return bgr;
    }
    default:
      *why = cv::format("pixel format 0x%08x is not read (use Mono8, Mono16, RGB8 or Bayer*8)", static_cast<unsigned>(format));
      return std::nullopt;
  }
}

std::string status_text(ArvBufferStatus status) {
  switch (status) {
    case ARV_BUFFER_STATUS_TIMEOUT: return "packets still missing when the frame was given up (timeout)";
    case ARV_BUFFER_STATUS_MISSING_PACKETS: return "missing packets";
    case ARV_BUFFER_STATUS_WRONG_PACKET_ID: return "packet with a wrong id";
    case ARV_BUFFER_STATUS_SIZE_MISMATCH: return "image larger than the buffer";
    case ARV_BUFFER_STATUS_ABORTED: return "filling aborted";
    default: return "buffer status " + std::to_string(static_cast<int>(status));
  }
}

class AravisCamera final : public Camera {
 public:
  AravisCamera(std::string name, ArvCamera* camera) : Camera(std::move(name)), camera_(camera) {}
  ~AravisCamera() override {
    do_stop();
    if (stream_) g_object_unref(stream_);
    g_object_unref(camera_);
  }

 private:
  bool has(const char* feature_name) {
    GError* e = nullptr;
    const gboolean available = arv_camera_is_feature_available(camera_, feature_name, &e);
    if (e) g_error_free(e);
    return available && !e;
  }

  // Sets one feature when the camera has it (or its older SFNC name `alternative`,
  // which Aravis' setters fall back to); otherwise a line naming it.
  template <typename Set>
  void feature(const char* feature_name, std::vector<std::string>* notes, HostResult<void>* failed, Set set,
               const char* alternative = nullptr) {
    if (!has(feature_name) && !(alternative && has(alternative))) {
      notes->push_back(name() + ": camera has no feature " + feature_name + " (left as it is)");
      return;
    }
    GError* e = nullptr;
    set(&e);
    if (e && *failed) *failed = host_error(HostErrorKind::kBadInput, name(), std::string(feature_name) + ": " + take_message(e));
  }

  HostResult<std::vector<std::string>> do_configure(const CameraSettings& s) override {
    std::vector<std::string> notes;
    frame_rate_hz_ = s.frame_rate_hz;
    HostResult<void> failed{};
    if (!s.pixel_format.empty()) {
      feature("PixelFormat", &notes, &failed,
              [&](GError** e) { arv_camera_set_pixel_format_from_string(camera_, s.pixel_format.c_str(), e); });
    }
    if (s.width) feature("Width", &notes, &failed, [&](GError** e) { arv_camera_set_integer(camera_, "Width", *s.width, e); });
    if (s.height) feature("Height", &notes, &failed, [&](GError** e) { arv_camera_set_integer(camera_, "Height", *s.height, e); });
    if (s.exposure_us) {
      feature(
          "ExposureTime", &notes, &failed, [&](GError** e) { arv_camera_set_exposure_time(camera_, *s.exposure_us, e); },
          "ExposureTimeAbs");
    }
    if (s.gain_db) feature(
          "Gain", &notes, &failed, [&](GError** e) { arv_camera_set_gain(camera_, *s.gain_db, e); }, "GainRaw");
    if (s.frame_rate_hz) {
      feature("AcquisitionFrameRate", &notes, &failed,
              [&](GError** e) { arv_camera_set_frame_rate(camera_, *s.frame_rate_hz, e); }, "AcquisitionFrameRateAbs");
    }
    if (s.trigger_source && s.trigger_required && (!has("TriggerMode") || !has("TriggerSource"))) {
      return host_error(HostErrorKind::kBadInput, name(),
                        "camera has no feature TriggerMode/TriggerSource: it cannot be triggered by the host");
    }
    if (s.trigger_source) {
      feature("TriggerMode", &notes, &failed, [&](GError** e) { arv_camera_set_string(camera_, "TriggerMode", "On", e); });
      feature("TriggerSource", &notes, &failed,
              [&](GError** e) { arv_camera_set_string(camera_, "TriggerSource", s.trigger_source->c_str(), e); });
    }
    if (s.strobe_line) {
      feature("LineSelector", &notes, &failed,
              [&](GError** e) { arv_camera_set_string(camera_, "LineSelector", s.strobe_line->c_str(), e); });
      feature("LineSource", &notes, &failed,
              [&](GError** e) { arv_camera_set_string(camera_, "LineSource", "ExposureActive", e); });
    }
    if (!failed) return tl::unexpected(failed.error());
    return notes;
  }

  HostResult<void> do_start() override {
    GError* e = nullptr;
    if (!stream_) {
      stream_ = arv_camera_create_stream(camera_, nullptr, nullptr, &e);
      if (!stream_) return host_error(HostErrorKind::kOpenFailed, name(), "create stream: " + take_message(e));
      configure_resend();
    }
    const guint payload = arv_camera_get_payload(camera_, &e);
    if (e) return host_error(HostErrorKind::kIo, name(), "payload size: " + take_message(e));
    for (int i = 0; i < buffer_count(); ++i) arv_stream_push_buffer(stream_, arv_buffer_new(payload, nullptr));
    arv_camera_start_acquisition(camera_, &e);
    if (e) return host_error(HostErrorKind::kIo, name(), "start acquisition: " + take_message(e));
    running_ = true;
    return {};
  }

  // GigE Vision: a lost packet is asked for again (PACKETRESEND_CMD) instead of
  // costing its frame. Aravis turns resend off itself for a camera that does not
  // announce it; the summary says so. A gap is asked for 2 ms after it is seen (a
  // packet only out of order has come by then), again every 5 ms while the answer is
  // lost too -- also the wait before a frame whose last packets are missing is asked
  // for, so it bounds the latency a loss adds (Aravis' default, 20 ms, made a frame
  // with a lost packet ~20 ms late; 3 ms made spurious requests on a loaded host, and
  // frames given up at Aravis' request limit) -- and a frame is given up 100 ms after
  // its last packet (then it is one bad buffer).
  void configure_resend() {
    if (!ARV_IS_GV_STREAM(stream_)) return;
    gv_stream_ = true;
    ArvGvStreamPacketResend resend = ARV_GV_STREAM_PACKET_RESEND_NEVER;
    g_object_get(stream_, "packet-resend", &resend, nullptr);
    if (resend == ARV_GV_STREAM_PACKET_RESEND_NEVER) return;  // the camera does not offer it
    g_object_set(stream_, "packet-resend", ARV_GV_STREAM_PACKET_RESEND_ALWAYS, "initial-packet-timeout", 2000u,
                 "packet-timeout", 5000u, "frame-retention", 100000u, nullptr);
  }

  // Frames held while one waits for resent packets (Aravis hands frames out in
  // order): the frame retention's worth at the frame rate, and a margin.
  int buffer_count() const {
    if (!gv_stream_) return 8;
    if (!frame_rate_hz_ || *frame_rate_hz_ <= 0) return 16;
    return std::clamp(static_cast<int>(std::ceil(*frame_rate_hz_ * 0.15)) + 4, 8, 64);
  }

  std::string do_transport_summary() override {
    if (!gv_stream_) return "";
    ArvGvStreamPacketResend resend = ARV_GV_STREAM_PACKET_RESEND_NEVER;
    g_object_get(stream_, "packet-resend", &resend, nullptr);
    const auto info = [&](const char* key) { return static_cast<unsigned long long>(arv_stream_get_info_uint64_by_name(stream_, key)); };
    if (resend == ARV_GV_STREAM_PACKET_RESEND_NEVER) {
      return "packet resend off (the camera does not offer it): each lost packet costs its frame";
    }
    return cv::format("packet resend: %llu packets asked for again, %llu came back, %llu frames given up",
                      info("n_resend_requests"), info("n_resent_packets"), info("n_timeouts"));
  }

  HostResult<std::optional<CameraFrame>> do_grab(int timeout_ms) override {
    if (!stream_) return host_error(HostErrorKind::kIo, name(), "grab before start");
    ArvBuffer* buffer = arv_stream_timeout_pop_buffer(stream_, static_cast<guint64>(timeout_ms) * 1000);
    if (!buffer) return std::optional<CameraFrame>{};
    CameraFrame f;
    f.camera_ns = static_cast<int64_t>(arv_buffer_get_timestamp(buffer));
    const guint64 system_ns = arv_buffer_get_system_timestamp(buffer);  // CLOCK_REALTIME
    f.arrived_ns = system_ns ? monotonic_from_realtime_ns(static_cast<int64_t>(system_ns)) : monotonic_now_ns();
    f.sequence = arv_buffer_get_frame_id(buffer);
    const ArvBufferStatus status = arv_buffer_get_status(buffer);
    if (status != ARV_BUFFER_STATUS_SUCCESS) {
      f.bad = name() + ": frame " + std::to_string(f.sequence) + ": " + status_text(status);
    } else {
      std::string why;
      auto image = image_of(buffer, &why);
      if (image) f.image = std::move(*image);
      else f.bad = name() + ": frame " + std::to_string(f.sequence) + ": " + why;
    }
    arv_stream_push_buffer(stream_, buffer);
    return std::optional<CameraFrame>(std::move(f));
  }

  void do_stop() override {
    if (!running_) return;
    running_ = false;
    GError* e = nullptr;
    arv_camera_stop_acquisition(camera_, &e);
    if (e) g_error_free(e);
  }

  ArvCamera* camera_;
  ArvStream* stream_ = nullptr;
  bool running_ = false;
  bool gv_stream_ = false;
  std::optional<double> frame_rate_hz_;
};

}  // namespace

HostResult<std::unique_ptr<Camera>> open_aravis_camera(const std::string& id) {
  const std::string name = "aravis:" + id;
  GError* e = nullptr;
  ArvCamera* camera = nullptr;
  if (is_ipv4(id)) {
    const auto local = local_address_towards(id);
    if (!local) return host_error(HostErrorKind::kNotFound, name, "no route to " + id);
    GInetAddress* interface_address = g_inet_address_new_from_string(local->c_str());
    GInetAddress* device_address = g_inet_address_new_from_string(id.c_str());
    ArvDevice* device = arv_gv_device_new(interface_address, device_address, &e);
    g_object_unref(interface_address);
    g_object_unref(device_address);
    if (!device) return host_error(HostErrorKind::kOpenFailed, name, "no GigE Vision camera answers: " + take_message(e));
    camera = arv_camera_new_with_device(device, &e);
    g_object_unref(device);

  } else {
    camera = arv_camera_new(id.c_str(), &e);
  }
  if (!camera) return host_error(HostErrorKind::kOpenFailed, name, take_message(e));
  return std::unique_ptr<Camera>(new AravisCamera(name, camera));
}

}  // namespace tetrapulse::host

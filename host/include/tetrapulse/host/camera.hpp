#pragma once
// A live camera behind a small NVI interface: GenICam cameras through Aravis
// (GigE Vision, USB3 Vision) and V4L2 devices (UVC webcams, capture cards),
// opened from one spec string: "aravis:ID" (ID: an IPv4 address, opened by address
// without discovery, or an Aravis device id) or "v4l2:/dev/videoN".
//
// A frame carries the camera's own timestamp (ns, the camera's clock: the GigE/U3V
// device clock, or the kernel's CLOCK_MONOTONIC buffer stamp for V4L2) and the host's
// CLOCK_MONOTONIC when the buffer reached the host. A bad buffer (incomplete, wrong
// size, missing packets) costs one frame: grab() returns it with `bad` set and the
// camera counts it; the run goes on.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "tetrapulse/host/host_error.hpp"

namespace tetrapulse::host {

struct CameraSettings {
  std::optional<double> exposure_us;       // ExposureTime (µs)
  std::optional<double> gain_db;           // Gain (dB)
  std::optional<double> frame_rate_hz;     // AcquisitionFrameRate (Hz)
  std::string pixel_format;                // "Mono8", "Mono16", "BayerRG8", ... ("": the camera's)
  std::optional<std::string> trigger_source;  // TriggerMode=On, TriggerSource=this ("Line0")
  // The host triggers every exposure (--sync-trigger): a camera that cannot take the
  // trigger is an error, not a note, since its frames would not be the host's pulses.
  bool trigger_required = false;
  std::optional<std::string> strobe_line;     // LineSelector=this, LineSource=ExposureActive ("Line1")
  std::optional<int> width, height;        // image size (pixels)
  std::optional<int> packet_size;          // GigE Vision: GevSCPSPacketSize (bytes; jumbo frames: fewer packets to lose)
};

struct CameraFrame {
  cv::Mat image;               // CV_8UC1, CV_16UC1 or CV_8UC3 (BGR)
  int64_t camera_ns = 0;       // the camera's timestamp (its clock), 0 when it has none
  int64_t arrived_ns = 0;      // host CLOCK_MONOTONIC when the buffer was handed over
  uint64_t sequence = 0;       // the camera's frame counter (gaps: frames it dropped)
  std::optional<std::string> bad;  // set: the buffer is unusable (why); `image` empty
};

struct CameraCounters {
  uint64_t frames = 0;       // buffers handed over, good or bad
  uint64_t bad_buffers = 0;  // of which unusable
};

class Camera {
 public:
  virtual ~Camera() = default;
  Camera(const Camera&) = delete;
  Camera& operator=(const Camera&) = delete;

  // "aravis:192.168.1.20", "v4l2:/dev/video0".
  const std::string& name() const { return name_; }
  // Applies the settings through the camera's own features. A feature the camera
  // lacks is not an error: it is one line in the result naming it.
  HostResult<std::vector<std::string>> configure(const CameraSettings& s) { return do_configure(s); }
  HostResult<void> start() { return do_start(); }
  // The next buffer within timeout_ms (nullopt: none came); a frame with `bad` set
  // is a buffer lost to the camera or transport (counted).
  HostResult<std::optional<CameraFrame>> grab(int timeout_ms);
  void stop() { do_stop(); }
  const CameraCounters& counters() const { return counters_; }
  // What the transport did about losses (GigE Vision: packets asked for again), one
  // line for the run's summary; "" where there is nothing to say.
  std::string transport_summary() { return do_transport_summary(); }

 protected:
  explicit Camera(std::string name) : name_(std::move(name)) {}

 private:
  virtual HostResult<std::vector<std::string>> do_configure(const CameraSettings& s) = 0;
  virtual HostResult<void> do_start() = 0;
  virtual HostResult<std::optional<CameraFrame>> do_grab(int timeout_ms) = 0;
  virtual void do_stop() = 0;
  virtual std::string do_transport_summary() { return ""; }

  std::string name_;
  CameraCounters counters_;
};

// What a spec names: backend "aravis" or "v4l2" and its address/device.
struct CameraSpec {
  std::string backend;
  std::string address;
};
// kBadInput naming the spec when it is neither "aravis:ID" nor "v4l2:PATH".
HostResult<CameraSpec> parse_camera_spec(const std::string& spec);

// Opens the camera `spec` names (kNotFound / kOpenFailed naming it).
HostResult<std::unique_ptr<Camera>> open_camera(const std::string& spec);

HostResult<std::unique_ptr<Camera>> open_aravis_camera(const std::string& id);
HostResult<std::unique_ptr<Camera>> open_v4l2_camera(const std::string& device);

}  // namespace tetrapulse::host

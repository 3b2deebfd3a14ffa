#pragma once
// Where the localizer's frames come from: a rig dataset's images, a recorded
// video with a timestamps file, or a live V4L2 camera (both through OpenCV's
// VideoCapture). Every frame carries its exposure in rig time (integer ns,
// [timestamp_ns, timestamp_ns + exposure_ns), spec/rig-dataset.md). Images
// come as 8- or 16-bit grey (colour is converted); a frame that is not
// camera-sized is an error that names its file.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "tetrapulse/datasets/dataset_io.hpp"
#include "tetrapulse/localizer/localizer.hpp"
#include "tetrapulse/datasets/rig_dataset.hpp"

namespace tetrapulse {

struct Frame {
  int64_t frame = 0;
  int64_t timestamp_ns = 0;  // exposure start, rig time
  int64_t exposure_ns = 0;
  cv::Mat image;
  std::string name;  // for messages: the image file, or "VIDEO frame N"
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame; nullopt at the end; an error names the file (and line) at fault.
  virtual DatasetResult<std::optional<Frame>> next() = 0;
  // How many frames there are, when known (for progress).
  virtual std::optional<size_t> count() const = 0;
};

// The frames of a rig dataset, in frames.csv order.
std::unique_ptr<FrameSource> dataset_frames(const RigDataset& dataset);

// A recorded video (any format OpenCV reads) whose frames, in order, have the
// rows of a timestamps file (read_timestamps_csv). More or fewer frames than
// rows is an error. `camera` gives the expected size.
DatasetResult<std::unique_ptr<FrameSource>> video_frames(const std::string& video, const std::string& timestamps,
                                                         const CameraInfo& camera);

// A live camera (e.g. "/dev/video0") through OpenCV's V4L2 backend. Each frame is
// stamped with the driver's buffer time when OpenCV reports one (CAP_PROP_POS_MSEC,
// the kernel's monotonic clock), else with the host's steady clock when it
// arrives; the exposure start is that stamp minus exposure_ns. Rig time is then the
// host's clock: boards must be synchronised to it (or free-running). Runs until the
// device stops delivering.
DatasetResult<std::unique_ptr<FrameSource>> camera_frames(const std::string& device, const CameraInfo& camera,
                                                          int64_t exposure_ns);

// Runs `localizer` over every frame of `source`, calling on_frame with each
// frame's poses (at mid-exposure) until the source ends or on_frame fails. A
// frame the localizer refuses is an error naming the frame.
using FrameCallback = std::function<DatasetResult<void>(const Frame&, const std::vector<TargetPose>&)>;
DatasetResult<size_t> localize_frames(FrameSource& source, Localizer& localizer, const FrameCallback& on_frame);

}  // namespace tetrapulse

#pragma once
// Where the localizer's frames come from: a rig dataset's images, a recorded
// video with a timestamps file, or a live V4L2 camera (both through OpenCV's
// VideoCapture). Every frame carries its exposure in rig time (integer ns,
// [timestamp_ns, timestamp_ns + exposure_ns), docs/rig-dataset.md). Images
// come as 8- or 16-bit grey (colour is converted), except a dataset's whose
// targets.yaml gives markers a colour: those stay 8-bit BGR. A frame whose image cannot
// be had (missing, empty, truncated or undecodable file, not camera-sized, a bad
// camera buffer) costs only itself: it comes with `unreadable` set and is skipped.
#include <atomic>
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
  // Set when the image could not be had: `image` is empty, the frame is to be
  // skipped, and the error names the file (or buffer) and what is wrong.
  std::optional<DatasetError> unreadable;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame (possibly unreadable, see Frame); nullopt at the end; an error
  // means the source itself failed and names the file (and line) at fault.
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

// What localize_frames did: frames localized, frames skipped (unreadable, or
// refused by the localizer), and whether `stop` ended it before the source did.
struct LocalizedFrames {
  size_t frames = 0;
  size_t skipped = 0;
  bool stopped = false;
};

using FrameCallback = std::function<DatasetResult<void>(const Frame&, const std::vector<TargetPose>&)>;
// A skipped frame and why (the error names its file or buffer).
using SkipCallback = std::function<void(const Frame&, const DatasetError&)>;

struct LocalizeHooks {
  SkipCallback on_skip;                     // may be empty
  const std::atomic<bool>* stop = nullptr;  // checked between frames (a signal handler's flag)
};

// Runs `localizer` over every frame of `source`, calling on_frame with each
// frame's poses (at mid-exposure) until the source ends, on_frame fails or
// *stop is set. A frame that is unreadable or that the localizer refuses is
// skipped (on_skip) and the loop goes on.
DatasetResult<LocalizedFrames> localize_frames(FrameSource& source, Localizer& localizer, const FrameCallback& on_frame,
                                               const LocalizeHooks& hooks = {});

}  // namespace tetrapulse

#include "tetrapulse/datasets/frame_source.hpp"

#include <chrono>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

namespace tetrapulse {

namespace {

class DatasetFrames : public FrameSource {
 public:
  explicit DatasetFrames(const RigDataset& dataset) : dataset_(dataset) {}

  DatasetResult<std::optional<Frame>> next() override {
    if (next_ >= dataset_.frames().size()) return std::optional<Frame>();
    const FrameRecord& row = dataset_.frames()[next_];
    auto image = dataset_.load_image(next_);
    ++next_;
    Frame f{row.frame, row.timestamp_ns, row.exposure_ns, {}, dataset_.path_of(row.file), std::nullopt};
    if (image) {
      f.image = std::move(*image);
    } else {
      f.unreadable = image.error();
    }
    return f;
  }
  std::optional<size_t> count() const override { return dataset_.frames().size(); }

 private:
  const RigDataset& dataset_;
  size_t next_ = 0;
};

// Grey 8- or 16-bit; colour to grey. An error message, or empty.
std::string to_grey(cv::Mat* image, const CameraInfo& camera) {
  if (image->channels() == 3) {
    cv::cvtColor(*image, *image, cv::COLOR_BGR2GRAY);
  } else if (image->channels() == 4) {
    cv::cvtColor(*image, *image, cv::COLOR_BGRA2GRAY);
  } else if (image->channels() != 1) {
    return fmt::format("{} channels are not supported", image->channels());
  }
  if (image->depth() != CV_8U && image->depth() != CV_16U) return "only 8- and 16-bit images are supported";
  if (image->cols != camera.width || image->rows != camera.height) {
    return fmt::format("frame is {}x{}, camera.yaml says {}x{}", image->cols, image->rows, camera.width, camera.height);
  }
  return {};
}

class VideoFrames : public FrameSource {
 public:
  VideoFrames(std::string video, std::string timestamps, std::vector<FrameRecord> rows, const CameraInfo& camera)
      : video_(std::move(video)), timestamps_(std::move(timestamps)), rows_(std::move(rows)), camera_(camera) {}

  bool open() { return capture_.open(video_); }

  DatasetResult<std::optional<Frame>> next() override {
    cv::Mat image;
    bool got = false;
    std::string undecodable;
    try {
      got = capture_.read(image) && !image.empty();
    } catch (const cv::Exception& e) {
      got = true;  // a frame was there; it is skipped
      undecodable = std::string("cannot decode: ") + e.what();
    }
    if (next_ >= rows_.size()) {
      if (got) {
        return dataset_error(timestamps_, 0,
                             fmt::format("has {} rows, but {} has more frames", rows_.size(), video_));
      }
      return std::optional<Frame>();
    }
    if (!got) {
      return dataset_error(timestamps_, 0,
                           fmt::format("has {} rows, but {} ends after {} frames", rows_.size(), video_, next_));
    }
    const FrameRecord& row = rows_[next_++];
    Frame f{row.frame, row.timestamp_ns, row.exposure_ns, {}, fmt::format("{} frame {}", video_, row.frame),
            std::nullopt};
    const std::string why = undecodable.empty() ? to_grey(&image, camera_) : undecodable;
    if (why.empty()) {
      f.image = std::move(image);
    } else {
      f.unreadable = DatasetError{video_, 0, fmt::format("frame {}: {}", row.frame, why)};
    }
    return f;
  }
  std::optional<size_t> count() const override { return rows_.size(); }

 private:
  std::string video_, timestamps_;
  std::vector<FrameRecord> rows_;
  CameraInfo camera_;
  cv::VideoCapture capture_;
  size_t next_ = 0;
};

class CameraFrames : public FrameSource {
 public:
  CameraFrames(std::string device, const CameraInfo& camera, int64_t exposure_ns)
      : device_(std::move(device)), camera_(camera), exposure_ns_(exposure_ns) {}

  bool open() {
    if (!capture_.open(device_, cv::CAP_V4L2)) return false;
    capture_.set(cv::CAP_PROP_FRAME_WIDTH, camera_.width);
    capture_.set(cv::CAP_PROP_FRAME_HEIGHT, camera_.height);
    return true;
  }

  DatasetResult<std::optional<Frame>> next() override {
    cv::Mat image;
    try {
      if (!capture_.read(image) || image.empty()) return std::optional<Frame>();
    } catch (const cv::Exception& e) {
      return dataset_error(device_, 0, std::string("cannot read a frame: ") + e.what());
    }
    const auto arrived = std::chrono::steady_clock::now().time_since_epoch();
    const double buffer_ms = capture_.get(cv::CAP_PROP_POS_MSEC);
    int64_t end_ns = buffer_ms > 0 ? int64_t(buffer_ms * 1e6)
                                   : std::chrono::duration_cast<std::chrono::nanoseconds>(arrived).count();
    int64_t start = end_ns - exposure_ns_;
    if (frame_ > 0 && start <= last_start_) start = last_start_ + 1;  // a driver that repeats a stamp
    last_start_ = start;
    Frame f{frame_, start, exposure_ns_, {}, fmt::format("{} frame {}", device_, frame_), std::nullopt};
    ++frame_;
    // A buffer that is not a frame of this camera (size, format) costs only itself.
    if (const std::string why = to_grey(&image, camera_); !why.empty()) {
      f.unreadable = DatasetError{device_, 0, fmt::format("frame {}: {}", f.frame, why)};
    } else {
      f.image = std::move(image);
    }
    return f;
  }
  std::optional<size_t> count() const override { return std::nullopt; }

 private:
  std::string device_;
  CameraInfo camera_;
  int64_t exposure_ns_;
  cv::VideoCapture capture_;
  int64_t frame_ = 0;
  int64_t last_start_ = 0;
};

}  // namespace

DatasetResult<LocalizedFrames> localize_frames(FrameSource& source, Localizer& localizer, const FrameCallback& on_frame,
                                               const LocalizeHooks& hooks) {
  LocalizedFrames out;
  const auto skip = [&](const Frame& f, const DatasetError& why) {
    ++out.skipped;
    if (hooks.on_skip) hooks.on_skip(f, why);
  };
  for (;;) {
    if (hooks.stop && hooks.stop->load()) {
      out.stopped = true;
      return out;
    }
    auto frame = source.next();
    if (!frame) return tl::unexpected(frame.error());
    if (!*frame) return out;
    const Frame& f = **frame;
    if (f.unreadable) {
      skip(f, *f.unreadable);
      continue;
    }
    auto poses = localizer.process(f.image, f.timestamp_ns, f.exposure_ns);
    if (!poses) {
      skip(f, DatasetError{f.name, 0, poses.error().message});
      continue;
    }
    if (auto r = on_frame(f, *poses); !r) return tl::unexpected(r.error());
    ++out.frames;
  }
}

std::unique_ptr<FrameSource> dataset_frames(const RigDataset& dataset) {
  return std::make_unique<DatasetFrames>(dataset);
}

DatasetResult<std::unique_ptr<FrameSource>> video_frames(const std::string& video, const std::string& timestamps,
                                                         const CameraInfo& camera) {
  auto rows = read_timestamps_csv(timestamps);
  if (!rows) return tl::unexpected(rows.error());
  auto source = std::make_unique<VideoFrames>(video, timestamps, std::move(*rows), camera);
  bool opened = false;
  try {
    opened = source->open();
  } catch (const cv::Exception& e) {
    return dataset_error(video, 0, std::string("cannot open video: ") + e.what());
  }
  if (!opened) return dataset_error(video, 0, "cannot open video (missing, or a format OpenCV cannot read)");
  return std::unique_ptr<FrameSource>(std::move(source));
}

DatasetResult<std::unique_ptr<FrameSource>> camera_frames(const std::string& device, const CameraInfo& camera,
                                                          int64_t exposure_ns) {
  auto source = std::make_unique<CameraFrames>(device, camera, exposure_ns);
  bool opened = false;
  try {
    opened = source->open();
  } catch (const cv::Exception& e) {
    return dataset_error(device, 0, std::string("cannot open camera: ") + e.what());
  }
  if (!opened) return dataset_error(device, 0, "cannot open camera (no such V4L2 device, or busy)");
  return std::unique_ptr<FrameSource>(std::move(source));
}

}  // namespace tetrapulse

#include "blob_working_image.hpp"

#include <cstdint>

#include <Eigen/Core>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace tetrapulse::blob_internal {
namespace {

// Chroma along the target's hue, for pixels near the line from grey to the
// target (ColourTarget). Y, Cr and Cb as OpenCV's cv::COLOR_BGR2YCrCb
// computes them for 8-bit images.
void colour_evidence(const cv::Mat& bgr, cv::Rect window, const ColourTarget& target, cv::Mat* out) {
  Eigen::Vector2d hue(target.cr - 128.0, target.cb - 128.0);
  const double length = hue.norm();
  hue = length > 0 ? Eigen::Vector2d(hue / length) : Eigen::Vector2d(0, 0);
  const double r2 = target.radius * target.radius;
  for (int y = window.y; y < window.y + window.height; ++y) {
    const uint8_t* p = bgr.ptr<uint8_t>(y) + 3 * window.x;
    uint8_t* q = out->ptr<uint8_t>(y) + window.x;
    for (int x = 0; x < window.width; ++x, p += 3) {
      const double b = p[0], g = p[1], r = p[2];
      const double luma = 0.299 * r + 0.587 * g + 0.114 * b;
      const Eigen::Vector2d chroma((r - luma) * 0.713, (b - luma) * 0.564);
      const double along = chroma.dot(hue);
      const double off = (chroma - along * hue).squaredNorm();
      const bool match = luma >= target.min_luma && along > 0 && off <= r2;
      q[x] = match ? cv::saturate_cast<uint8_t>(along) : 0;
    }
  }
}

}  // namespace

const cv::Mat& WorkingImage::prepare(const cv::Mat& image, cv::Rect window, MarkerPolarity polarity,
                                     const std::optional<ColourTarget>& colour) {
  const bool dark = polarity == MarkerPolarity::kDark;
  if (image.channels() == 1 && !dark) {
    view_ = image;
    return view_;
  }
  const int type = image.channels() == 3 ? CV_8UC1 : image.type();
  if (buffer_.size() != image.size() || buffer_.type() != type) buffer_.create(image.size(), type);
  cv::Mat dst = buffer_(window);
  if (image.channels() == 3 && colour) {
    colour_evidence(image, window, *colour, &buffer_);  // markers are bright in the evidence whatever the polarity
  } else if (image.channels() == 3) {
    cv::cvtColor(image(window), dst, cv::COLOR_BGR2GRAY);
    if (dark) cv::bitwise_not(dst, dst);
  } else {
    // A dark marker on a bright background becomes a bright one on a dark background.
    cv::bitwise_not(image(window), dst);
  }
  view_ = buffer_;
  return view_;
}

}  // namespace tetrapulse::blob_internal

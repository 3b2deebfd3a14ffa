#pragma once
// Internal to BlobExtractor: the single-channel image the pipeline reads, in
// which markers are always brighter than their background.
#include <optional>

#include <opencv2/core/mat.hpp>

#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse::blob_internal {

class WorkingImage {
 public:
  // Makes the marker evidence of `image` (CV_8UC1, CV_16UC1 or CV_8UC3 BGR)
  // valid over `window` (inside the image) and returns it: `image` itself for
  // light grey markers, else an internal buffer of the image's size holding the
  // complement (dark markers), the luma (BGR), or the luma of pixels of the
  // target colour and 0 elsewhere (colour target). Outside `window` the buffer
  // holds whatever earlier calls left there.
  const cv::Mat& prepare(const cv::Mat& image, cv::Rect window, MarkerPolarity polarity,
                         const std::optional<ColourTarget>& colour);

 private:
  cv::Mat buffer_;
  cv::Mat view_;
};

}  // namespace tetrapulse::blob_internal

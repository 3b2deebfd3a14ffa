#pragma once
// The demo's annotated frames: a camera image with each reported target's
// markers and axes projected from its measured pose (blue, with its id), the
// true marker positions (red crosses), and a frame strip that tiles several of
// them. Pixels as CameraModel; poses as pose.hpp.
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/pose.hpp"
#include "tetrapulse/localizer/targets.hpp"

namespace tetrapulse::cli {

struct OverlayPose {
  const Target* target = nullptr;
  Pose pose;
};

// A colour copy of `frame` (grey 8- or 16-bit, or 8-bit BGR; brightened when dark)
// with `measured` and `truth` drawn over it and `caption` in its top-left corner.
cv::Mat overlay_frame(const cv::Mat& frame, const CameraModel& camera, const std::vector<OverlayPose>& measured,
                      const std::vector<OverlayPose>& truth, const std::string& caption);

// Tiles (all the same size) in rows of `columns`, each scaled by `scale`.
cv::Mat frame_strip(const std::vector<cv::Mat>& tiles, int columns, double scale);

}  // namespace tetrapulse::cli

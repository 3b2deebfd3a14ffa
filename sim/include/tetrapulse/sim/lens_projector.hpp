#pragma once
// The virtual camera's lens: projects through OpenCV (cv::projectPoints for
// plumb_bob, cv::fisheye::projectPoints for equidistant), not through the
// localizer's CameraModel, so that a convention shared by the simulator and the
// localizer that OpenCV does not share shows up as an error instead of cancelling.
// Pixel coordinates as in OpenCV (integer coordinates are pixel centres); points
// in the OpenCV camera frame (x right, y down, z forward), metres.
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/localizer/camera_model.hpp"

namespace tetrapulse::sim {

class LensProjector {
 public:
  explicit LensProjector(const CameraInfo& info);

  const CameraInfo& info() const { return info_; }
  int width() const { return info_.width; }
  int height() const { return info_.height; }

  // Pixel of camera-frame point p_C. False when the point is not in front of the
  // lens (plumb_bob: z <= 0; equidistant: more than 90 degrees off axis) or lies
  // where the lens map stops growing with the angle off axis (a real lens shows
  // nothing there; the polynomial folds such points back into the image).
  bool project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px) const;
  // The same for many points at once (one OpenCV call): false when any fails.
  bool project(const std::vector<Eigen::Vector3d>& p_C, std::vector<Eigen::Vector2d>* px) const;

  // Unit bearing of pixel px (cv::undistortPoints / cv::fisheye::undistortPoints);
  // false where the distortion cannot be inverted.
  bool unproject(const Eigen::Vector2d& px, Eigen::Vector3d* bearing) const;

  // px within [-0.5, width - 0.5) x [-0.5, height - 0.5) shrunk by margin pixels.
  bool in_image(const Eigen::Vector2d& px, double margin = 0.0) const;

 private:
  bool in_range(const Eigen::Vector3d& p_C) const;
  CameraInfo info_;
  // Largest angle off axis (rad) below which the lens map grows: found here by
  // sampling OpenCV's own radial map, independently of CameraModel.
  double max_angle_rad_;
};

}  // namespace tetrapulse::sim

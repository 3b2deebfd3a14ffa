#pragma once
// Calibrated camera models with exactly OpenCV's conventions: pixel coordinates
// (u, v) have their origin at the centre of the top-left pixel (integer
// coordinates are pixel centres); points are in the OpenCV camera frame
// (x right, y down, z forward), metres.
//
//   plumb_bob   (cv::projectPoints):      x = X/Z, y = Y/Z, r^2 = x^2 + y^2,
//               x' = x(1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x y + p2 (r^2 + 2 x^2)
//               y' = y(1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2 y^2) + 2 p2 x y
//   equidistant (cv::fisheye::projectPoints): theta = atan(r),
//               theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8),
//               x' = (theta_d / r) x,  y' = (theta_d / r) y
//   then        u = fx x' + cx,  v = fy y' + cy.
#include <array>
#include <string>

#include <Eigen/Core>

namespace tetrapulse {

enum class DistortionModel { kPlumbBob, kEquidistant };

// Name as written in camera.yaml ("plumb_bob", "equidistant").
const char* distortion_model_name(DistortionModel model);

// The contents of a ROS camera_info YAML (camera.yaml), as the model needs them.
struct CameraInfo {
  std::string name;
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  DistortionModel model = DistortionModel::kPlumbBob;
  // plumb_bob: k1 k2 p1 p2 k3 (5 used); equidistant: k1 k2 k3 k4 (4 used).
  std::array<double, 5> distortion{};

  int distortion_count() const { return model == DistortionModel::kPlumbBob ? 5 : 4; }
};

class CameraModel {
 public:
  explicit CameraModel(const CameraInfo& info);

  const CameraInfo& info() const { return info_; }
  int width() const { return info_.width; }
  int height() const { return info_.height; }

  // Pixel of camera-frame point p_C. Returns false when p_C is not in front of
  // the camera (z <= 0) or beyond the model's valid range: where the radial map
  // stops growing (max_radius2(), max_theta()), a lens model folds far
  // off-axis points back into the image. With `J`, also writes
  // d(u, v) / d(p_C) (2x3, pixels per metre).
  bool project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px,
               Eigen::Matrix<double, 2, 3>* J = nullptr) const;

  // As project(), with the pixel's derivative along the camera-frame direction
  // dp_C: d(u, v)/d(p_C) dp_C (pixels per metre of dp_C), without forming the 2x3
  // Jacobian (a sphere's image rim is projected with its tangents, many per frame).
  bool project_along(const Eigen::Vector3d& p_C, const Eigen::Vector3d& dp_C, Eigen::Vector2d* px,
                     Eigen::Vector2d* dpx) const;

  // Unit bearing vector (camera frame) of pixel `px`: the inverse of project
  // up to scale. Returns false when the distortion cannot be inverted there.
  bool unproject(const Eigen::Vector2d& px, Eigen::Vector3d* bearing) const;

  // True when `px` lies on the sensor: [-0.5, width - 0.5) x [-0.5, height - 0.5),
  // shrunk by `margin` pixels on every side.
  bool in_image(const Eigen::Vector2d& px, double margin = 0.0) const;

  // plumb_bob: the largest r^2 = (X/Z)^2 + (Y/Z)^2 below which the radial map
  // r -> r (1 + k1 r^2 + k2 r^4 + k3 r^6) is increasing (infinity when it always
  // is); the tangential terms are left out (they are small and never fold).
  double max_radius2() const { return max_r2_; }
  // equidistant: the largest angle from the optical axis (rad) below which
  // theta -> theta_d is increasing, at most pi / 2.
  double max_theta() const { return max_theta_; }

 private:
  bool distort(const Eigen::Vector2d& xy, Eigen::Vector2d* out, Eigen::Matrix2d* J) const;
  CameraInfo info_;
  double max_r2_;     // computed once from the coefficients
  double max_theta_;
};

}  // namespace tetrapulse

#include "tetrapulse/sim/lens_projector.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

namespace tetrapulse::sim {

namespace {

cv::Matx33d camera_matrix(const CameraInfo& c) { return {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}; }

cv::Mat distortion(const CameraInfo& c) {
  cv::Mat d(1, c.distortion_count(), CV_64F);
  for (int i = 0; i < c.distortion_count(); ++i) d.at<double>(i) = c.distortion[static_cast<size_t>(i)];
  return d;
}

// OpenCV on cv::Point3d rows; the fisheye variant needs a 3-channel Mat.
void opencv_project(const CameraInfo& c, const std::vector<cv::Point3d>& in, std::vector<cv::Point2d>* out) {
  const cv::Vec3d zero(0, 0, 0);
  if (c.model == DistortionModel::kEquidistant) {
    cv::fisheye::projectPoints(in, *out, zero, zero, camera_matrix(c), distortion(c));
  } else {
    cv::projectPoints(in, zero, zero, camera_matrix(c), distortion(c), *out);
  }
}

}  // namespace

LensProjector::LensProjector(const CameraInfo& info) : info_(info), max_angle_rad_(M_PI / 2) {
  // Walk the angle off axis along the x axis in 0.05-degree steps (the
  // tangential terms are small and never fold): the map must grow
  // strictly, and the first step where it stops is the limit.
  constexpr int kSteps = 1800;
  std::vector<cv::Point3d> rays;
  for (int k = 1; k < kSteps; ++k) {
    const double a = M_PI / 2 * k / kSteps;
    rays.emplace_back(std::sin(a), 0.0, std::cos(a));
  }
  std::vector<cv::Point2d> px;
  opencv_project(info_, rays, &px);
  double last = info_.cx;
  for (size_t k = 0; k < px.size(); ++k) {
    if (!(px[k].x > last)) {
      max_angle_rad_ = M_PI / 2 * static_cast<double>(k) / kSteps;
      break;
    }
    last = px[k].x;
  }
}

bool LensProjector::in_range(const Eigen::Vector3d& p) const {
  const double n = p.norm();
  if (!(n > 0) || !(p.z() > 1e-12 * n)) return false;  // z = 0 has no projection in either model
  return std::atan2(p.head<2>().norm(), p.z()) < max_angle_rad_;
}

bool LensProjector::project(const Eigen::Vector3d& p_C, Eigen::Vector2d* px) const {
  if (!in_range(p_C)) return false;
  std::vector<cv::Point2d> out;
  opencv_project(info_, {cv::Point3d(p_C.x(), p_C.y(), p_C.z())}, &out);
  *px = Eigen::Vector2d(out[0].x, out[0].y);
  return std::isfinite(px->x()) && std::isfinite(px->y());
}

bool LensProjector::project(const std::vector<Eigen::Vector3d>& p_C, std::vector<Eigen::Vector2d>* px) const {
  std::vector<cv::Point3d> in;
  in.reserve(p_C.size());
  for (const Eigen::Vector3d& p : p_C) {
    if (!in_range(p)) return false;
    in.emplace_back(p.x(), p.y(), p.z());
  }
  std::vector<cv::Point2d> out;
  opencv_project(info_, in, &out);
  px->resize(out.size());
  for (size_t k = 0; k < out.size(); ++k) {
    if (!std::isfinite(out[k].x) || !std::isfinite(out[k].y)) return false;
    (*px)[k] = Eigen::Vector2d(out[k].x, out[k].y);
  }
  return true;
}

bool LensProjector::unproject(const Eigen::Vector2d& px, Eigen::Vector3d* bearing) const {
  const std::vector<cv::Point2d> in{cv::Point2d(px.x(), px.y())};
  std::vector<cv::Point2d> out;
  if (info_.model == DistortionModel::kEquidistant) {
    cv::fisheye::undistortPoints(in, out, camera_matrix(info_), distortion(info_));
  } else {
    // OpenCV's default is 5 fixed-point steps, too few for strong distortion.
    cv::undistortPoints(in, out, camera_matrix(info_), distortion(info_), cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14));
  }
  const Eigen::Vector3d b(out[0].x, out[0].y, 1.0);
  if (!b.allFinite()) return false;
  *bearing = b.normalized();
  return true;
}

bool LensProjector::in_image(const Eigen::Vector2d& px, double margin) const {
  return px.x() >= -0.5 + margin && px.y() >= -0.5 + margin && px.x() < width() - 0.5 - margin &&
         px.y() < height() - 0.5 - margin;
}

}  // namespace tetrapulse::sim

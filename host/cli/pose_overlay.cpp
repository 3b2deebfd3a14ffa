#include "pose_overlay.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace tetrapulse::cli {

namespace {

const cv::Scalar kTruth(40, 40, 230), kMeasured(255, 160, 30), kText(255, 255, 255);

bool pixel_of(const CameraModel& camera, const Eigen::Vector3d& p_C, cv::Point2d* out) {
  Eigen::Vector2d px;
  if (!camera.project(p_C, &px)) return false;
  *out = cv::Point2d(px.x(), px.y());
  return true;
}

cv::Point rounded(const cv::Point2d& p) { return cv::Point(cvRound(p.x), cvRound(p.y)); }

}  // namespace

cv::Mat overlay_frame(const cv::Mat& frame, const CameraModel& camera, const std::vector<OverlayPose>& measured,
                      const std::vector<OverlayPose>& truth, const std::string& caption) {
  cv::Mat eight, out;
  if (frame.depth() == CV_16U) {
    frame.convertTo(eight, CV_8U, 1.0 / 256);
  } else {
    eight = frame;
  }
  // A dark scene (LEDs in a dim room) is brightened so that it shows; a lit one
  // (painted markers on a floor) is not, or the floor would clip.
  cv::Mat lifted;
  const cv::Scalar mean = cv::mean(eight);
  const bool dark = (mean[0] + mean[1] + mean[2] + mean[3]) / eight.channels() < 64;
  eight.convertTo(lifted, CV_8U, dark ? 2.0 : 1.0, dark ? 10 : 0);
  if (lifted.channels() == 3) {
    out = lifted;
  } else {
    cv::cvtColor(lifted, out, cv::COLOR_GRAY2BGR);
  }
  for (const OverlayPose& t : truth) {
    for (const Marker& m : t.target->markers) {
      cv::Point2d px;
      if (pixel_of(camera, t.pose.apply(m.position_m), &px)) cv::drawMarker(out, rounded(px), kTruth, cv::MARKER_CROSS, 14, 1);
    }
  }
  for (const OverlayPose& t : measured) {
    double extent = 0;
    for (const Marker& m : t.target->markers) extent = std::max(extent, m.position_m.norm());
    cv::Point2d origin, top_left(1e9, 1e9);
    for (const Marker& m : t.target->markers) {
      cv::Point2d px;
      if (!pixel_of(camera, t.pose.apply(m.position_m), &px)) continue;
      cv::circle(out, rounded(px), 7, kMeasured, 1, cv::LINE_AA);
      top_left = cv::Point2d(std::min(top_left.x, px.x), std::min(top_left.y, px.y));
    }
    if (pixel_of(camera, t.pose.t, &origin)) {
      const cv::Scalar axis_colour[3] = {cv::Scalar(60, 60, 255), cv::Scalar(60, 220, 60), cv::Scalar(255, 120, 60)};
      for (int a = 0; a < 3; ++a) {
        cv::Point2d end;
        if (pixel_of(camera, t.pose.apply(0.6 * extent * Eigen::Vector3d::Unit(a)), &end)) {
          cv::line(out, rounded(origin), rounded(end), axis_colour[a], 1, cv::LINE_AA);
        }
      }
    }
    if (top_left.x < 1e9) {
      cv::putText(out, "id " + std::to_string(t.target->id), rounded(top_left) + cv::Point(-10, -12),
                  cv::FONT_HERSHEY_SIMPLEX, 0.5, kMeasured, 1, cv::LINE_AA);
    }
  }
  cv::putText(out, caption, cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.55, kText, 1, cv::LINE_AA);
  return out;
}

cv::Mat frame_strip(const std::vector<cv::Mat>& tiles, int columns, double scale) {
  if (tiles.empty() || columns < 1) return cv::Mat();
  const int w = cvRound(tiles[0].cols * scale), h = cvRound(tiles[0].rows * scale);
  const int rows = (int(tiles.size()) + columns - 1) / columns;
  const int cols = std::min(columns, int(tiles.size()));
  cv::Mat strip(rows * h + (rows - 1) * 4, cols * w + (cols - 1) * 4, CV_8UC3, cv::Scalar(255, 255, 255));
  for (size_t i = 0; i < tiles.size(); ++i) {
    cv::Mat small;
    cv::resize(tiles[i], small, cv::Size(w, h), 0, 0, cv::INTER_AREA);
    const int r = int(i) / columns, c = int(i) % columns;
    small.copyTo(strip(cv::Rect(c * (w + 4), r * (h + 4), w, h)));
  }
  return strip;
}

}  // namespace tetrapulse::cli

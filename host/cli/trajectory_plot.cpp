#include "trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

namespace tetrapulse::cli {

namespace {

const cv::Scalar kTruth(40, 40, 220), kMeasured(200, 90, 20), kInk(40, 40, 40), kGrid(225, 225, 225);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// A step of 1, 2 or 5 times a power of ten giving about `count` ticks over `range`.
double nice_step(double range, int count) {
  const double raw = range / std::max(count, 1);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

// A panel mapping data coordinates (a, b) into a pixel rectangle.
struct Panel {
  cv::Rect area;
  double a0 = 0, a1 = 1, b0 = 0, b1 = 1;

  cv::Point2d at(double a, double b) const {
    return {area.x + (a - a0) / (a1 - a0) * area.width, area.y + area.height - (b - b0) / (b1 - b0) * area.height};
  }
  cv::Point pixel(double a, double b) const {
    const cv::Point2d p = at(a, b);
    return {int(std::lround(p.x)), int(std::lround(p.y))};
  }

  // Bounds of the values with a margin; equal: same scale on both axes (centred).
  void fit(double amin, double amax, double bmin, double bmax, bool equal) {
    if (!(amax > amin)) amin -= 0.5, amax += 0.5;
    if (!(bmax > bmin)) bmin -= 0.5, bmax += 0.5;
    const double ma = 0.08 * (amax - amin), mb = 0.08 * (bmax - bmin);
    a0 = amin - ma, a1 = amax + ma, b0 = bmin - mb, b1 = bmax + mb;
    if (!equal) return;
    const double sa = (a1 - a0) / area.width, sb = (b1 - b0) / area.height, s = std::max(sa, sb);
    const double ca = (a0 + a1) / 2, cb = (b0 + b1) / 2;
    a0 = ca - s * area.width / 2, a1 = ca + s * area.width / 2;
    b0 = cb - s * area.height / 2, b1 = cb + s * area.height / 2;
  }

  void axes(cv::Mat* img, const std::string& a_label, const std::string& b_label, const std::string& title) const {
    const double sa = nice_step(a1 - a0, 6), sb = nice_step(b1 - b0, 5);
    for (double a = std::ceil(a0 / sa) * sa; a <= a1; a += sa) {
      cv::line(*img, pixel(a, b0), pixel(a, b1), kGrid, 1);
      const std::string text = fmt::format("{:g}", std::abs(a) < 1e-9 ? 0.0 : a);
      cv::putText(*img, text, pixel(a, b0) + cv::Point(-8, 18), kFont, 0.4, kInk, 1, cv::LINE_AA);
    }
    for (double b = std::ceil(b0 / sb) * sb; b <= b1; b += sb) {
      cv::line(*img, pixel(a0, b), pixel(a1, b), kGrid, 1);
      const std::string text = fmt::format("{:g}", std::abs(b) < 1e-9 ? 0.0 : b);
      cv::putText(*img, text, pixel(a0, b) + cv::Point(-42, 4), kFont, 0.4, kInk, 1, cv::LINE_AA);
    }
    cv::rectangle(*img, area, kInk, 1);
    cv::putText(*img, a_label, cv::Point(area.x + area.width / 2 - 30, area.y + area.height + 38), kFont, 0.5, kInk, 1,
                cv::LINE_AA);
    cv::putText(*img, b_label, cv::Point(area.x - 60, area.y - 8), kFont, 0.45, kInk, 1, cv::LINE_AA);
    int baseline = 0;
    const cv::Size size = cv::getTextSize(title, kFont, 0.55, 1, &baseline);
    cv::putText(*img, title, cv::Point(area.x + (area.width - size.width) / 2, area.y - 10), kFont, 0.55, kInk, 1,
                cv::LINE_AA);
  }
};

void polyline(cv::Mat* img, const Panel& panel, const std::vector<TrajectoryPoint>& points, int a, int b,
              const cv::Scalar& colour) {
  std::vector<cv::Point> line;
  for (const TrajectoryPoint& p : points) line.push_back(panel.pixel(100 * p.p[a], 100 * p.p[b]));
  if (line.size() >= 2) cv::polylines(*img, line, false, colour, 1, cv::LINE_AA);
}

void dots(cv::Mat* img, const Panel& panel, const std::vector<TrajectoryPoint>& points, int a, int b,
          const cv::Scalar& colour) {
  for (const TrajectoryPoint& p : points) cv::circle(*img, panel.pixel(100 * p.p[a], 100 * p.p[b]), 1, colour, -1);
}

}  // namespace

cv::Mat plot_trajectories(const std::vector<Trajectory>& trajectories, const std::string& title,
                          const std::string& frame) {
  cv::Mat img(580, 1560, CV_8UC3, cv::Scalar(255, 255, 255));
  Panel top{cv::Rect(80, 95, 440, 420)}, side{cv::Rect(600, 95, 440, 420)}, error{cv::Rect(1110, 95, 420, 420)};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = Eigen::Vector3d::Constant(-kInf);
  double t_max = 0, e_max = 0;
  for (const Trajectory& tr : trajectories) {
    for (const TrajectoryPoint& p : tr.truth) lo = lo.cwiseMin(100 * p.p), hi = hi.cwiseMax(100 * p.p), t_max = std::max(t_max, p.t_s);
    for (const TrajectoryPoint& p : tr.error) e_max = std::max(e_max, 100 * p.p.x());
  }
  if (!(lo.x() <= hi.x())) lo.setZero(), hi.setOnes();
  top.fit(lo.x(), hi.x(), lo.y(), hi.y(), true);
  side.fit(lo.x(), hi.x(), lo.z(), hi.z(), true);
  error.fit(0, std::max(t_max, 1e-3), 0, std::max(e_max, 0.1), false);
  error.b0 = 0;
  top.axes(&img, "x (cm)", "y (cm)", "top view");
  side.axes(&img, "x (cm)", "z (cm)", "side view");
  error.axes(&img, "time (s)", "error (cm)", "position error");
  for (const Trajectory& tr : trajectories) {
    polyline(&img, top, tr.truth, 0, 1, kTruth);
    polyline(&img, side, tr.truth, 0, 2, kTruth);
    dots(&img, top, tr.measured, 0, 1, kMeasured);
    dots(&img, side, tr.measured, 0, 2, kMeasured);
    std::vector<cv::Point> line;
    for (const TrajectoryPoint& p : tr.error) line.push_back(error.pixel(p.t_s, 100 * p.p.x()));
    for (const cv::Point& p : line) cv::circle(img, p, 1, kMeasured, -1);
    if (!tr.truth.empty() && !tr.label.empty()) {
      cv::putText(img, tr.label, top.pixel(100 * tr.truth.front().p.x(), 100 * tr.truth.front().p.y()) + cv::Point(4, -4),
                  kFont, 0.4, kInk, 1, cv::LINE_AA);
    }
  }
  cv::putText(img, title, cv::Point(80, 30), kFont, 0.65, kInk, 1, cv::LINE_AA);
  cv::putText(img, frame, cv::Point(80, 54), kFont, 0.45, kInk, 1, cv::LINE_AA);
  // Legend.
  cv::line(img, cv::Point(1110, 28), cv::Point(1140, 28), kTruth, 2);
  cv::putText(img, "ground truth", cv::Point(1148, 33), kFont, 0.45, kInk, 1, cv::LINE_AA);
  cv::circle(img, cv::Point(1275, 28), 3, kMeasured, -1);
  cv::putText(img, "measured", cv::Point(1285, 33), kFont, 0.45, kInk, 1, cv::LINE_AA);
  return img;
}

}  // namespace tetrapulse::cli

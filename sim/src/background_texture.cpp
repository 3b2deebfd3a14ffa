#include "tetrapulse/sim/background_texture.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {

namespace {

// Adds amplitude x value noise of lattice spacing `scale` to `out`.
void add_octave(cv::Mat& out, double scale, double amplitude, Random& rng) {
  const int gw = static_cast<int>(std::ceil(out.cols / scale)) + 2;
  const int gh = static_cast<int>(std::ceil(out.rows / scale)) + 2;
  std::vector<double> lattice(static_cast<size_t>(gw) * static_cast<size_t>(gh));
  for (double& v : lattice) v = rng.uniform(-1.0, 1.0);
  const auto smooth = [](double s) { return s * s * (3 - 2 * s); };
  for (int y = 0; y < out.rows; ++y) {
    const double fy = y / scale;
    const int gy = static_cast<int>(fy);
    const double sy = smooth(fy - gy);
    float* row = out.ptr<float>(y);
    for (int x = 0; x < out.cols; ++x) {
      const double fx = x / scale;
      const int gx = static_cast<int>(fx);
      const double sx = smooth(fx - gx);
      const auto at = [&](int i, int j) { return lattice[static_cast<size_t>(j) * static_cast<size_t>(gw) + static_cast<size_t>(i)]; };
      const double top = at(gx, gy) + sx * (at(gx + 1, gy) - at(gx, gy));
      const double bottom = at(gx, gy + 1) + sx * (at(gx + 1, gy + 1) - at(gx, gy + 1));
      row[x] += static_cast<float>(amplitude * (top + sy * (bottom - top)));
    }
  }
}

}  // namespace

cv::Mat smooth_texture(int width, int height, double scale_px, uint64_t seed) {
  cv::Mat out(height, width, CV_32F, cv::Scalar(0));
  if (width <= 0 || height <= 0) return out;
  Random rng(seed);
  const double scale = std::max(scale_px, 2.0);
  add_octave(out, scale, 1.0, rng);
  add_octave(out, std::max(scale / 2, 2.0), 0.5, rng);
  double lo = 0, hi = 0;
  cv::minMaxLoc(out, &lo, &hi);
  const double half = std::max(std::abs(lo), std::abs(hi));
  if (half > 0) out *= 1.0 / half;
  return out;
}

}  // namespace tetrapulse::sim

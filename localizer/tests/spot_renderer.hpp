#pragma once
// Test-only renderer of marker spots with known sub-pixel centres: each pixel
// gets the integral of the spot over its square (pixel (x, y) covers
// [x - 0.5, x + 0.5) x [y - 0.5, y + 0.5), OpenCV's convention). Images are
// built in double precision, then rounded and clipped to 8 or 16 bits.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace tetrapulse::test {

// A 2D Gaussian of standard deviation `sigma` (pixels) whose continuous peak
// is `peak` grey levels, integrated over each pixel (erf, separable).
inline void add_gaussian(cv::Mat1d* img, const Eigen::Vector2d& c, double sigma, double peak) {
  const double s = sigma * std::sqrt(2.0);
  const double volume = peak * 2.0 * M_PI * sigma * sigma;
  const int reach = static_cast<int>(std::ceil(7 * sigma)) + 1;
  const int x0 = std::max(0, int(c.x()) - reach), x1 = std::min(img->cols - 1, int(c.x()) + reach);
  const int y0 = std::max(0, int(c.y()) - reach), y1 = std::min(img->rows - 1, int(c.y()) + reach);
  for (int y = y0; y <= y1; ++y) {
    const double fy = 0.5 * (std::erf((y + 0.5 - c.y()) / s) - std::erf((y - 0.5 - c.y()) / s));
    for (int x = x0; x <= x1; ++x) {
      const double fx = 0.5 * (std::erf((x + 0.5 - c.x()) / s) - std::erf((x - 0.5 - c.x()) / s));
      (*img)(y, x) += volume * fx * fy;
    }
  }
}

// A uniform disc of `level` grey levels, integrated over each pixel by 64 x 64
// supersampling of the pixels its rim crosses. `keep(x, y)` (sub-pixel
// position) may cut parts away, e.g. a shadow.
template <typename Keep>
void add_disc(cv::Mat1d* img, const Eigen::Vector2d& c, double radius, double level, Keep keep) {
  constexpr int kSub = 64;
  const int x0 = std::max(0, int(std::floor(c.x() - radius)) - 1), x1 = std::min(img->cols - 1, int(c.x() + radius) + 1);
  const int y0 = std::max(0, int(std::floor(c.y() - radius)) - 1), y1 = std::min(img->rows - 1, int(c.y() + radius) + 1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      int inside = 0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const double px = x - 0.5 + (i + 0.5) / kSub, py = y - 0.5 + (j + 0.5) / kSub;
          const double dx = px - c.x(), dy = py - c.y();
          inside += dx * dx + dy * dy <= radius * radius && keep(px, py);
        }
      (*img)(y, x) += level * inside / double(kSub * kSub);
    }
}

inline void add_disc(cv::Mat1d* img, const Eigen::Vector2d& c, double radius, double level) {
  add_disc(img, c, radius, level, [](double, double) { return true; });
}

// Gaussian read noise of `sigma` grey levels, from a fixed seed.
inline void add_noise(cv::Mat1d* img, double sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, sigma);
  for (int y = 0; y < img->rows; ++y)
    for (int x = 0; x < img->cols; ++x) (*img)(y, x) += n(rng);
}

inline cv::Mat quantise(const cv::Mat1d& img, int depth) {
  cv::Mat out;
  img.convertTo(out, depth);  // rounds to nearest and saturates
  return out;
}

}  // namespace tetrapulse::test

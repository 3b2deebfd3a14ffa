#include "tetrapulse/sim/pixel_response.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tetrapulse::sim {

PixelResponse::PixelResponse(double sigma_px, int oversampling)
    : sigma_(sigma_px > 0 ? sigma_px : 0), s_(std::max(1, oversampling)) {
  radius_ = sigma_ > 0 ? static_cast<int>(std::ceil(4 * sigma_ + 0.5)) : 0;
  const int taps = 2 * radius_ + 1;
  weights_.assign(static_cast<size_t>(s_) * static_cast<size_t>(taps), 0.0);
  const auto cdf = [this](double x) { return 0.5 * std::erfc(-x / (sigma_ * M_SQRT2)); };
  for (int phase = 0; phase < s_; ++phase) {
    const double d = (phase + 0.5) / s_ - 0.5;  // cell centre relative to its pixel's centre
    double* w = weights_.data() + static_cast<size_t>(phase) * static_cast<size_t>(taps);
    if (sigma_ == 0) {
      w[0] = 1.0;
      continue;
    }
    double sum = 0;
    for (int k = -radius_; k <= radius_; ++k) {
      w[k + radius_] = cdf(k - d + 0.5) - cdf(k - d - 0.5);
      sum += w[k + radius_];
    }
    for (int k = 0; k < taps; ++k) w[k] /= sum;
  }
}

int PixelResponse::pixel_of(int f) const {
  const int q = f / s_;
  return (f % s_ != 0 && f < 0) ? q - 1 : q;
}

void PixelResponse::apply(const FineImage& in, PixelImage* out) const {
  const int R = radius_;
  out->x0 = pixel_of(in.x0) - R;
  out->y0 = pixel_of(in.y0) - R;
  out->width = pixel_of(in.x0 + in.width - 1) + R - out->x0 + 1;
  out->height = pixel_of(in.y0 + in.height - 1) + R - out->y0 + 1;
  const auto ow = static_cast<size_t>(out->width);
  // Along x: each fine row into pixel columns.
  rows_.assign(static_cast<size_t>(in.height) * ow, 0.0);
  for (int j = 0; j < in.height; ++j) {
    const double* src = in.data + static_cast<std::ptrdiff_t>(j) * in.stride;
    double* dst = rows_.data() + static_cast<size_t>(j) * ow;
    for (int i = 0; i < in.width; ++i) {
      const double v = src[i];
      if (v == 0) continue;
      const int f = in.x0 + i;
      const int p = pixel_of(f);
      const int phase = f - p * s_;
      double* d = dst + (p - R - out->x0);
      for (int k = -R; k <= R; ++k) d[k + R] += v * weight(phase, k);
    }
  }
  // Along y: fine rows into pixel rows.
  out->data.assign(static_cast<size_t>(out->height) * ow, 0.0);
  for (int j = 0; j < in.height; ++j) {
    const double* src = rows_.data() + static_cast<size_t>(j) * ow;
    const int f = in.y0 + j;
    const int p = pixel_of(f);
    const int phase = f - p * s_;
    for (int k = -R; k <= R; ++k) {
      const double w = weight(phase, k);
      double* dst = out->data.data() + static_cast<size_t>(p + k - out->y0) * ow;
      for (size_t i = 0; i < ow; ++i) dst[i] += w * src[i];
    }
  }
}

}  // namespace tetrapulse::sim

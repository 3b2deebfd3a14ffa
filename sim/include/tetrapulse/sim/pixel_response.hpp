#pragma once
// From light on the sensor to pixel values: the optics' point-spread function (an
// isotropic Gaussian, sigma_px) followed by each pixel's integration over its area.
// Light is given on a grid `oversampling` times finer than the pixels (fine cell f
// has its centre at pixel coordinate u_f = (f + 1/2) / s - 1/2); light in fine cell f
// reaches pixel p with weight
//     w(p - u_f) = Phi((p - u_f + 1/2) / sigma) - Phi((p - u_f - 1/2) / sigma)
// along each axis (normalised over |p - pixel(f)| <= radius). Sampling the light on
// the fine grid moves each bit of it by at most half a fine cell, a pattern of
// spatial frequency s per pixel that the Gaussian damps by exp(-2 pi^2 sigma^2 s^2)
// (1e-49 for sigma = 0.6, s = 4): centroids are those of the continuous image.
// With sigma = 0 the weights are the pixel boxes (exact area coverage).
#include <cstddef>
#include <vector>

namespace tetrapulse::sim {

struct FineImage {
  const double* data = nullptr;  // row-major
  int width = 0, height = 0, stride = 0;
  int x0 = 0, y0 = 0;  // fine-grid index of data[0]
};

struct PixelImage {
  std::vector<double> data;  // row-major, width x height
  int width = 0, height = 0;
  int x0 = 0, y0 = 0;  // pixel index of data[0]
};

class PixelResponse {
 public:
  PixelResponse(double sigma_px, int oversampling);

  double sigma_px() const { return sigma_; }
  int oversampling() const { return s_; }
  // How many pixels light can reach beyond the pixel it falls in.
  int radius() const { return radius_; }

  // Pixel grid of fine cell index f: floor(f / s).
  int pixel_of(int f) const;

  void apply(const FineImage& in, PixelImage* out) const;

 private:
  // Weight from a fine cell of phase `phase` (0..s-1) to the pixel `k` away from its own.
  double weight(int phase, int k) const {
    return weights_[static_cast<size_t>(phase) * static_cast<size_t>(2 * radius_ + 1) + static_cast<size_t>(k + radius_)];
  }

  double sigma_ = 0;
  int s_ = 1;
  int radius_ = 0;
  std::vector<double> weights_;  // s x (2 radius + 1)
  mutable std::vector<double> rows_;  // scratch: fine rows x pixel columns
};

}  // namespace tetrapulse::sim

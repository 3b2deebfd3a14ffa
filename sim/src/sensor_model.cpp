#include "tetrapulse/sim/sensor_model.hpp"

#include <algorithm>
#include <cmath>

#include "tetrapulse/sim/background_texture.hpp"
#include "tetrapulse/sim/noise_sampler.hpp"
#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {

namespace {
// Below this mean the shot noise is drawn exactly from the Poisson distribution.
constexpr double kExactPoissonBelow = 30.0;
}  // namespace

SensorModel::SensorModel(int width, int height, const SensorConfig& config, uint64_t seed) : config_(config) {
  const cv::Mat texture = smooth_texture(width, height, config.texture_scale_px, stream_seed(seed, kStreamBackground));
  gain_.create(height, width, CV_32F);
  background_.create(height, width, CV_32F);
  offset_.create(height, width, CV_32F);
  NoiseSampler fixed(stream_seed(seed, kStreamFixedPattern));
  for (int y = 0; y < height; ++y) {
    const float* t = texture.ptr<float>(y);
    float* g = gain_.ptr<float>(y);
    float* b = background_.ptr<float>(y);
    float* o = offset_.ptr<float>(y);
    for (int x = 0; x < width; ++x) {
      g[x] = static_cast<float>(std::max(0.0, 1.0 + config.prnu * fixed.normal()));
      b[x] = static_cast<float>(g[x] * config.background_e_per_ms * std::max(0.0, 1.0 + config.texture_contrast * t[x]));
      o[x] = static_cast<float>(config.dsnu_e * std::abs(fixed.normal()));
    }
  }
}

template <typename Pixel>
void SensorModel::expose_as(const cv::Mat& light_e, double exposure_ms, uint64_t noise_seed, cv::Mat* image) const {
  NoiseSampler noise(noise_seed);
  const double inv_gain = 1.0 / config_.gain_e_per_dn;
  const double read = config_.read_noise_e, read2 = read * read;
  const double full = config_.full_well_e, black = config_.black_level_dn;
  const double top = max_dn();
  for (int y = 0; y < light_e.rows; ++y) {
    const float* l = light_e.ptr<float>(y);
    const float* g = gain_.ptr<float>(y);
    const float* b = background_.ptr<float>(y);
    const float* o = offset_.ptr<float>(y);
    Pixel* out = image->ptr<Pixel>(y);
    for (int x = 0; x < light_e.cols; ++x) {
      const double mu = std::max(0.0, static_cast<double>(g[x]) * l[x] + b[x] * exposure_ms + o[x]);
      double s = mu;
      if (config_.noise) {
        if (mu < kExactPoissonBelow) {
          s = noise.poisson(mu) + read * noise.normal();
        } else {
          s = mu + std::sqrt(mu + read2) * noise.normal();  // shot and read noise in one draw
        }
      }
      const double dn = std::min(s, full) * inv_gain + black;
      out[x] = static_cast<Pixel>(std::clamp(std::floor(dn + 0.5), 0.0, top));
    }
  }
}

void SensorModel::expose(const cv::Mat& light_e, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image) const {
  const double exposure_ms = static_cast<double>(exposure_ns) * 1e-6;
  if (config_.bit_depth == 16) {
    image->create(light_e.rows, light_e.cols, CV_16U);
    expose_as<uint16_t>(light_e, exposure_ms, noise_seed, image);
  } else {
    image->create(light_e.rows, light_e.cols, CV_8U);
    expose_as<uint8_t>(light_e, exposure_ms, noise_seed, image);
  }
}

}  // namespace tetrapulse::sim

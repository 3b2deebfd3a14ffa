#include "tetrapulse/sim/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

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

double SensorModel::background_e_per_ms_at(int x, int y) const {
  x = std::clamp(x, 0, background_.cols - 1);
  y = std::clamp(y, 0, background_.rows - 1);
  const float g = gain_.at<float>(y, x);
  return g > 0 ? background_.at<float>(y, x) / g : config_.background_e_per_ms;
}

void SensorModel::prepare_dark_frame(int64_t exposure_ns) {
  if (exposure_ns == dark_exposure_ns_) return;
  dark_exposure_ns_ = exposure_ns;
  const double exposure_ms = static_cast<double>(exposure_ns) * 1e-6;
  const double read2 = config_.read_noise_e * config_.read_noise_e;
  dark_mean_.create(background_.size(), CV_32F);
  dark_sd_.create(background_.size(), CV_32F);
  for (int y = 0; y < background_.rows; ++y) {
    const float* b = background_.ptr<float>(y);
    const float* o = offset_.ptr<float>(y);
    float* m = dark_mean_.ptr<float>(y);
    float* sd = dark_sd_.ptr<float>(y);
    for (int x = 0; x < background_.cols; ++x) {
      const double mu = std::max(0.0, b[x] * exposure_ms + o[x]);
      m[x] = static_cast<float>(mu);
      sd[x] = mu < kExactPoissonBelow ? -1.0f : static_cast<float>(std::sqrt(mu + read2));
    }
  }
}

template <typename Pixel>
void SensorModel::expose_as(const cv::Mat& light_e, double exposure_ms, uint64_t noise_seed, cv::Mat* image) const {
  NoiseSampler noise(noise_seed);
  const double inv_gain = 1.0 / config_.gain_e_per_dn;
  const double read = config_.read_noise_e, read2 = read * read;
  const double full = config_.full_well_e, black = config_.black_level_dn;
  const double top = max_dn();  // truncating dn in [0, top] rounds it
  std::vector<float> z(static_cast<size_t>(light_e.cols));
  for (int y = 0; y < light_e.rows; ++y) {
    if (config_.noise) noise.fill_normal(z.data(), light_e.cols);
    const float* l = light_e.ptr<float>(y);
    const float* g = gain_.ptr<float>(y);
    const float* b = background_.ptr<float>(y);
    const float* o = offset_.ptr<float>(y);
    const float* dark_mean = dark_mean_.ptr<float>(y);
    const float* dark_sd = dark_sd_.ptr<float>(y);
    Pixel* out = image->ptr<Pixel>(y);
    for (int x = 0; x < light_e.cols; ++x) {
      if (l[x] == 0 && dark_sd[x] >= 0 && config_.noise) {  // the common case, precomputed
        const double dn = std::min(static_cast<double>(dark_mean[x] + dark_sd[x] * z[static_cast<size_t>(x)]), full) * inv_gain + black + 0.5;
        out[x] = static_cast<Pixel>(dn <= 0 ? 0.0 : (dn >= top ? top : dn));
        continue;
      }
      const double mu = std::max(0.0, static_cast<double>(g[x]) * l[x] + b[x] * exposure_ms + o[x]);
      double s = mu;
      if (config_.noise) {
        const double zx = z[static_cast<size_t>(x)];
        if (mu < kExactPoissonBelow) {
          s = noise.poisson(mu) + read * zx;
        } else {
          s = mu + std::sqrt(mu + read2) * zx;  // shot and read noise in one draw
        }
      }
      const double dn = std::min(s, full) * inv_gain + black + 0.5;  // + 0.5: round to nearest
      out[x] = static_cast<Pixel>(dn <= 0 ? 0.0 : (dn >= top ? top : dn));
    }
  }
}

void bloom_columns(double full_well_e, double fraction, cv::Mat* light_e) {
  const int h = light_e->rows, w = light_e->cols;
  std::vector<double> spill(static_cast<size_t>(h)), column(static_cast<size_t>(h));
  for (int x = 0; x < w; ++x) {
    bool any = false;
    for (int y = 0; y < h; ++y) {
      const double v = light_e->at<float>(y, x);
      const double s = fraction * std::max(0.0, v - full_well_e);
      spill[static_cast<size_t>(y)] = s;
      column[static_cast<size_t>(y)] = v - s;
      any = any || s > 0;
    }
    if (!any) continue;
    // Half of each pixel's spill runs down the column, half up; a full pixel passes it on.
    const auto run = [&](int from, int to, int step) {
      double carry = 0;
      for (int y = from; y != to; y += step) {
        double& v = column[static_cast<size_t>(y)];
        const double room = std::max(0.0, full_well_e - v);
        const double kept = std::min(room, carry);
        v += kept;
        carry = carry - kept + 0.5 * spill[static_cast<size_t>(y)];
      }
    };
    run(0, h, 1);
    run(h - 1, -1, -1);
    for (int y = 0; y < h; ++y) light_e->at<float>(y, x) = static_cast<float>(column[static_cast<size_t>(y)]);
  }
}

void SensorModel::expose(const cv::Mat& light_e, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image) {
  if (config_.blooming > 0) {
    bloomed_ = light_e.clone();
    bloom_columns(config_.full_well_e, config_.blooming, &bloomed_);
    expose_light(bloomed_, exposure_ns, noise_seed, image);
    return;
  }
  expose_light(light_e, exposure_ns, noise_seed, image);
}

void SensorModel::expose_light(const cv::Mat& light_e, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image) {
  prepare_dark_frame(exposure_ns);
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

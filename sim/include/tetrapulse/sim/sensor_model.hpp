#pragma once
// The image sensor: turns the light each pixel collected (electrons) into the
// digital numbers (DN) of an 8- or 16-bit grey image. Global shutter; every pixel
// integrates the same exposure window. Per pixel p, for an exposure of E ms:
//   mean   mu_p = g_p (light_p + background_e_per_ms (1 + contrast T_p) E) + o_p
//            g_p = 1 + prnu N_p       (fixed-pattern gain, "PRNU")
//            o_p = dsnu_e |N'_p|      (fixed-pattern dark offset, "DSNU", e-)
//            T_p  in [-1, 1]          (smooth background texture)
//   signal s_p = Poisson(mu_p) + read_noise_e N(0, 1)   (exact Poisson below 30 e-;
//            above, its normal approximation mu_p + sqrt(mu_p) N(0, 1))
//   DN     = clamp(round(min(s_p, full_well_e) / gain_e_per_dn + black_level_dn), 0, 2^bits - 1)
// The fixed patterns and the texture are drawn once from the seed; the noise of
// each frame comes from its own seed, so frames render in any order alike.
#include <cstdint>

#include <opencv2/core.hpp>

namespace tetrapulse::sim {

struct SensorConfig {
  int bit_depth = 8;                 // 8 or 16 (the PNG's depth)
  double gain_e_per_dn = 16;         // electrons per digital number
  double read_noise_e = 6;           // standard deviation, electrons
  double full_well_e = 12000;        // saturation, electrons
  double black_level_dn = 2;         // DN of a pixel that collected nothing
  double background_e_per_ms = 40;   // mean light from the dark scene, electrons per ms
  double texture_contrast = 0.6;     // relative amplitude of the background texture, [0, 1]
  double texture_scale_px = 120;     // size of the texture's features, pixels
  double prnu = 0.01;                // relative standard deviation of the pixel gains
  double dsnu_e = 3;                 // scale of the pixel dark offsets, electrons
  bool noise = true;                 // false: expected values (no shot or read noise)
  // Blooming: this fraction [0, 1] of the light charge above full_well_e spills
  // out of a pixel, half up and half down its column, filling the neighbours up
  // to full well and passing on beyond (0: clipped charge is lost).
  double blooming = 0;
  // A Bayer colour filter (RGGB) over the pixels; the frame renderer mosaics the
  // light by it and demosaics the 8-bit result into a BGR image.
  bool bayer = false;
};

// Blooming of light charge (CV_32F electrons per pixel), in place: `fraction` of
// what exceeds full_well_e leaves each pixel, half up and half down its column;
// it fills the pixels it reaches up to full_well_e and runs on past full ones.
// Charge is conserved except what runs off the image's top or bottom.
void bloom_columns(double full_well_e, double fraction, cv::Mat* light_e);

class SensorModel {
 public:
  SensorModel(int width, int height, const SensorConfig& config, uint64_t seed);

  const SensorConfig& config() const { return config_; }
  // The background's light at pixel (x, y) before the pixel's gain,
  // background_e_per_ms (1 + contrast T_p) (electrons per ms): what an opaque body
  // in front of the background takes away.
  double background_e_per_ms_at(int x, int y) const;
  int max_dn() const { return config_.bit_depth == 16 ? 65535 : 255; }

  // Digitizes one exposure of `exposure_ns`. light_e: CV_32F, electrons from the
  // lights per pixel. image: CV_8U or CV_16U (bit_depth). noise_seed: this frame's.
  // Not thread-safe: it keeps the dark frame's statistics for the last exposure time.
  void expose(const cv::Mat& light_e, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image);

 private:
  void expose_light(const cv::Mat& light_e, int64_t exposure_ns, uint64_t noise_seed, cv::Mat* image);
  template <typename Pixel>
  void expose_as(const cv::Mat& light_e, double exposure_ms, uint64_t noise_seed, cv::Mat* image) const;
  // Mean and noise of each pixel that no light reaches, for one exposure time (most pixels).
  void prepare_dark_frame(int64_t exposure_ns);

  SensorConfig config_;
  cv::Mat gain_;        // CV_32F, g_p
  cv::Mat background_;  // CV_32F, g_p background_e_per_ms (1 + contrast T_p): electrons per ms
  cv::Mat offset_;      // CV_32F, o_p electrons
  int64_t dark_exposure_ns_ = -1;
  cv::Mat dark_mean_;   // CV_32F, mu_p without light
  cv::Mat bloomed_;     // CV_32F, the light after blooming (blooming > 0)
  cv::Mat dark_sd_;     // CV_32F, sqrt(mu_p + read^2), or -1 where the Poisson draw must be exact
};

}  // namespace tetrapulse::sim

// The sensor model's statistics: noise as promised, saturation, reproducibility.
#include <gtest/gtest.h>

#include <cmath>

#include "tetrapulse/sim/noise_sampler.hpp"
#include "tetrapulse/sim/sensor_model.hpp"

namespace tetrapulse::sim {
namespace {

TEST(NoiseSampler, InverseNormalCdfMatchesKnownQuantiles) {
  EXPECT_NEAR(inverse_normal_cdf(0.5), 0.0, 1e-14);
  EXPECT_NEAR(inverse_normal_cdf(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(0.001), -3.090232306167814, 1e-12);
  EXPECT_NEAR(inverse_normal_cdf(1e-9), -5.997807015007686, 1e-9);
}

TEST(NoiseSampler, NormalDeviatesHaveTheNormalsMoments) {
  NoiseSampler s(42);
  const int n = 2'000'000;
  double m1 = 0, m2 = 0, m4 = 0;
  int beyond3 = 0;
  for (int i = 0; i < n; ++i) {
    const double z = s.normal();
    m1 += z;
    m2 += z * z;
    m4 += z * z * z * z;
    beyond3 += std::abs(z) > 3;
  }
  m1 /= n;
  m2 /= n;
  m4 /= n;
  EXPECT_NEAR(m1, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(m2, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m4, 3.0, 5 * std::sqrt(96.0 / n));
  // P(|z| > 3) = 0.0026998
  EXPECT_NEAR(beyond3 / static_cast<double>(n), 0.0026998, 5 * std::sqrt(0.0027 / n));
}

TEST(NoiseSampler, PoissonHasItsMeanAsVariance) {
  for (double lambda : {0.7, 3.5, 12.0, 29.0}) {
    NoiseSampler s(7);
    const int n = 400'000;
    double m1 = 0, m2 = 0;
    for (int i = 0; i < n; ++i) {
      const double k = s.poisson(lambda);
      m1 += k;
      m2 += k * k;
    }
    m1 /= n;
    const double var = m2 / n - m1 * m1;
    EXPECT_NEAR(m1, lambda, 5 * std::sqrt(lambda / n)) << lambda;
    EXPECT_NEAR(var, lambda, 5 * lambda * std::sqrt(2.0 / n) + 0.01) << lambda;
  }
}

SensorConfig flat_sensor() {
  SensorConfig c;
  c.bit_depth = 16;
  c.gain_e_per_dn = 10;
  c.read_noise_e = 6;
  c.full_well_e = 1e6;
  c.black_level_dn = 100;
  c.background_e_per_ms = 0;
  c.prnu = 0;
  c.dsnu_e = 0;
  return c;
}

void moments(const cv::Mat& img, double* mean, double* var) {
  cv::Scalar m, sd;
  cv::meanStdDev(img, m, sd);
  *mean = m[0];
  *var = sd[0] * sd[0];
}

TEST(SensorModel, ShotAndReadNoiseAddUpAsPromised) {
  SensorModel sensor(400, 300, flat_sensor(), 1);
  const int n = 400 * 300;
  for (double electrons : {5.0, 20.0, 1000.0, 50000.0}) {
    const cv::Mat light(300, 400, CV_32F, cv::Scalar(electrons));
    cv::Mat img;
    sensor.expose(light, 1'000'000, 99, &img);
    ASSERT_EQ(img.type(), CV_16UC1);
    double mean = 0, var = 0;
    moments(img, &mean, &var);
    // DN = (Poisson(mu) + read N) / gain + black, rounded: variance (mu + read^2) / gain^2 + 1/12.
    const double expected_var = (electrons + 36.0) / 100.0 + 1.0 / 12;
    EXPECT_NEAR(mean, electrons / 10 + 100, 5 * std::sqrt(expected_var / n) + 0.01) << electrons;
    EXPECT_NEAR(var, expected_var, 5 * expected_var * std::sqrt(2.0 / n) + 0.01) << electrons;
  }
}

TEST(SensorModel, SaturatesAtFullWellOrTheLargestCode) {
  SensorConfig c = flat_sensor();
  c.full_well_e = 20000;
  SensorModel deep(64, 48, c, 1);
  const cv::Mat bright(48, 64, CV_32F, cv::Scalar(1e7));
  cv::Mat img;
  deep.expose(bright, 1'000'000, 1, &img);
  double lo = 0, hi = 0;
  cv::minMaxLoc(img, &lo, &hi);
  EXPECT_EQ(lo, 20000 / 10 + 100);
  EXPECT_EQ(hi, 20000 / 10 + 100);
  c.bit_depth = 8;
  SensorModel shallow(64, 48, c, 1);
  shallow.expose(bright, 1'000'000, 1, &img);
  ASSERT_EQ(img.type(), CV_8UC1);
  cv::minMaxLoc(img, &lo, &hi);
  EXPECT_EQ(lo, 255);
}

TEST(SensorModel, BackgroundTextureStaysWithinItsContrast) {
  SensorConfig c = flat_sensor();
  c.read_noise_e = 0;
  c.noise = false;
  c.gain_e_per_dn = 1;
  c.black_level_dn = 0;
  c.background_e_per_ms = 1000;
  c.texture_contrast = 0.5;
  SensorModel sensor(320, 240, c, 5);
  const cv::Mat dark(240, 320, CV_32F, cv::Scalar(0));
  cv::Mat img;
  sensor.expose(dark, 2'000'000, 1, &img);
  double lo = 0, hi = 0;
  cv::minMaxLoc(img, &lo, &hi);
  EXPECT_GE(lo, 2000 * 0.5 - 1);
  EXPECT_LE(hi, 2000 * 1.5 + 1);
  EXPECT_GT(hi - lo, 2000 * 0.5);  // the texture spans most of its range
}

TEST(SensorModel, SameSeedSameImageOtherSeedOtherNoise) {
  SensorConfig c;
  SensorModel a(160, 120, c, 3), b(160, 120, c, 3);
  const cv::Mat light(120, 160, CV_32F, cv::Scalar(500));
  cv::Mat ia, ib, ic;
  a.expose(light, 2'000'000, 11, &ia);
  b.expose(light, 2'000'000, 11, &ib);
  a.expose(light, 2'000'000, 12, &ic);
  EXPECT_EQ(cv::norm(ia, ib, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(ia, ic, cv::NORM_L1), 0.0);
}

// Blooming: charge over full well runs up and down the column, fills the
// neighbours to full well, runs past full ones, and none is lost inside the image.
TEST(SensorModel, BloomingSpillsAlongTheColumnAndConservesCharge) {
  cv::Mat l(41, 5, CV_32F, cv::Scalar(0));
  l.at<float>(20, 2) = 20 * 1000.0f;  // 20x a 1000 e- full well
  cv::Mat bloomed = l.clone();
  bloom_columns(1000, 1.0, &bloomed);
  EXPECT_NEAR(cv::sum(bloomed)[0], 20000, 1e-2);
  EXPECT_FLOAT_EQ(bloomed.at<float>(20, 2), 1000);
  for (int d = 1; d <= 9; ++d) {  // 19 000 e- over: 9.5 pixels each way at full well
    EXPECT_FLOAT_EQ(bloomed.at<float>(20 + d, 2), 1000) << d;
    EXPECT_FLOAT_EQ(bloomed.at<float>(20 - d, 2), 1000) << d;
  }
  EXPECT_NEAR(bloomed.at<float>(30, 2), 500, 1e-3);
  EXPECT_NEAR(bloomed.at<float>(10, 2), 500, 1e-3);
  EXPECT_EQ(bloomed.at<float>(31, 2), 0);
  EXPECT_EQ(cv::countNonZero(bloomed.col(1)) + cv::countNonZero(bloomed.col(3)), 0);
  // Half the excess leaves: 9 500 e- stay over full well in the pixel (clipped by the sensor).
  cv::Mat half = l.clone();
  bloom_columns(1000, 0.5, &half);
  EXPECT_NEAR(half.at<float>(20, 2), 10500, 1e-2);
  EXPECT_NEAR(cv::sum(half)[0], 20000, 1e-2);
}

}  // namespace
}  // namespace tetrapulse::sim

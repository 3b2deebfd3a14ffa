// A large 8-bit window (65536 pixels or more) counts every other row into eight
// partial histograms, and the pixels within the 8 levels that hold most of its first
// row 16 at a time; a smaller one counts every row into four. Both must give the
// histogram of the pixels they read: a large window and the small image of just
// the rows it counts agree on every statistic, and every bin equals its count.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "../src/background_histogram.hpp"

namespace tetrapulse::blob_internal {
namespace {

// Otsu's threshold by its definition: the split t (values <= t darker) with the
// largest w0 w1 (mean0 - mean1)^2, the first of equals, in long double; the
// returned threshold lies between bin t and t + 1.
double otsu_by_definition(const cv::Mat& image) {
  std::vector<long double> count(256, 0);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) count[image.at<uint8_t>(y, x)] += 1;
  long double total = 0, sum_all = 0;
  for (int v = 0; v < 256; ++v) total += count[v], sum_all += count[v] * v;
  long double w0 = 0, sum0 = 0, best = -1;
  int best_t = -1;
  for (int t = 0; t < 255; ++t) {
    w0 += count[t], sum0 += count[t] * t;
    const long double w1 = total - w0;
    if (w0 <= 0 || count[t] == 0) continue;
    if (w1 <= 0) break;
    const long double d = sum0 / w0 - (sum_all - sum0) / w1;
    const long double between = w0 * w1 * d * d;
    if (between > best * (1 + 1e-15L)) best = between, best_t = t;
  }
  return best_t < 0 ? -1 : best_t + 0.5;
}

TEST(BackgroundHistogram, OtsuSplitsWhereTheBetweenClassVarianceIsLargest) {
  std::mt19937 rng(11);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int width = std::uniform_int_distribution<int>(4, 60)(rng);
    const int height = std::uniform_int_distribution<int>(4, 60)(rng);
    cv::Mat image(height, width, CV_8U);
    std::normal_distribution<double> background(std::uniform_real_distribution<double>(5, 120)(rng),
                                                std::uniform_real_distribution<double>(0.5, 12)(rng));
    std::uniform_int_distribution<int> spot(0, 99), bright(60, 255);
    const int share = std::uniform_int_distribution<int>(0, 40)(rng);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        image.at<uint8_t>(y, x) =
            uint8_t(spot(rng) < share ? bright(rng) : std::clamp(int(std::lround(background(rng))), 0, 255));
    BackgroundHistogram h;
    h.count(image, cv::Rect(0, 0, width, height));
    const double expected = otsu_by_definition(image);
    EXPECT_EQ(h.otsu(), expected) << "trial " << trial << ", " << width << " x " << height;
    checked += expected >= 0;
  }
  EXPECT_GT(checked, 390);
}

TEST(BackgroundHistogram, ALargeWindowCountsItsEveryOtherRowExactly) {
  std::mt19937 rng(5);
  for (const int width : {256, 301, 307, 333}) {  // whole blocks of 8, and 5, 3 and 5 left over
    cv::Mat image(380, width, CV_8U);
    std::normal_distribution<double> background(40, 3);
    std::uniform_int_distribution<int> spot(0, 99), bright(120, 255);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x)
        image.at<uint8_t>(y, x) =
            uint8_t(spot(rng) == 0 ? bright(rng) : std::clamp(int(std::lround(background(rng))), 0, 255));
    cv::Mat counted(image.rows / 2, width, CV_8U);  // rows 0, 2, 4, ...
    for (int r = 0; r < counted.rows; ++r) image.row(2 * r).copyTo(counted.row(r));
    ASSERT_GE(image.total(), 65536u);
    ASSERT_LT(counted.total(), 65536u);

    BackgroundHistogram large, small;
    large.count(image, cv::Rect(0, 0, image.cols, image.rows));
    small.count(counted, cv::Rect(0, 0, counted.cols, counted.rows));
    EXPECT_EQ(large.total(), small.total()) << width;
    EXPECT_EQ(large.otsu(), small.otsu()) << width;
    const BackgroundFit a = large.fit_background(255), b = small.fit_background(255);
    EXPECT_EQ(a.mean, b.mean) << width;
    EXPECT_EQ(a.sigma, b.sigma) << width;
    EXPECT_NEAR(a.mean, 40, 0.5);
    // Counted twice over, the histograms must not carry anything from the first call.
    large.count(image, cv::Rect(0, 0, image.cols, image.rows));
    EXPECT_EQ(large.otsu(), small.otsu()) << width;
    const BackgroundFit again = large.fit_background(255);
    EXPECT_EQ(again.sigma, b.sigma) << width;
  }
}

// Every bin of a large window against a count of its every other row, one pixel at a
// time: a narrow background (counted 16 pixels at a time) with values at random just
// outside the band and anywhere, runs of 255 (a saturated marker), widths that leave
// pixels beyond whole vectors, a row of more than 255 vectors (byte counters that
// must be emptied within it, also where a lane holds one level all along), a first
// row unlike the rest, and a wide background (too wide for the band: every pixel one
// by one).
TEST(BackgroundHistogram, ALargeWindowsEveryBinEqualsItsCount) {
  std::mt19937 rng(17);
  struct Case {
    int width, height;
    double mean, sigma;
    bool odd_first_row;
  };
  for (const Case c : {Case{752, 480, 7, 1.2, false}, Case{301, 440, 60, 1.0, false}, Case{4100, 40, 3, 0.8, false},
                       Case{4100, 40, 200, 1.5, false}, Case{520, 260, 30, 1.0, true}, Case{333, 400, 90, 14, false},
                       Case{17, 4000, 12, 1.0, false}, Case{4200, 32, 9, 0.01, false}}) {
    cv::Mat image(c.height, c.width, CV_8U);
    std::normal_distribution<double> background(c.mean, c.sigma);
    std::uniform_int_distribution<int> kind(0, 199), any(0, 255), edge(0, 1);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        int v = std::clamp(int(std::lround(background(rng))), 0, 255);
        const int k = kind(rng);
        if (k == 0) v = any(rng);
        if (k == 1) v = std::clamp(int(std::lround(c.mean)) + (edge(rng) ? 5 : -5), 0, 255);
        image.at<uint8_t>(y, x) = uint8_t(v);
      }
      if (y % 37 == 0) image.row(y).colRange(c.width / 3, c.width / 3 + std::min(c.width / 3, 40)).setTo(255);
    }
    if (c.odd_first_row) image.row(0).setTo(250);
    std::vector<uint32_t> expected(256, 0);
    for (int y = 0; y < image.rows; y += 2)
      for (int x = 0; x < image.cols; ++x) ++expected[image.at<uint8_t>(y, x)];
    ASSERT_GE(image.total(), 65536u);

    BackgroundHistogram h;
    for (int run = 0; run < 2; ++run) {  // nothing carried from the first run
      h.count(image, cv::Rect(0, 0, image.cols, image.rows));
      for (int b = 0; b < 256; ++b)
        ASSERT_EQ(h.bin_count(b), expected[size_t(b)]) << c.width << " x " << c.height << ", bin " << b;
    }
  }
}

}  // namespace
}  // namespace tetrapulse::blob_internal

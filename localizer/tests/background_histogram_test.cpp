// A large 8-bit window (65536 pixels or more) counts every other row into eight
// partial histograms; a smaller one counts every row into four. Both must give the
// histogram of the pixels they read: a large window and the small image of just
// the rows it counts agree on every statistic.
#include <gtest/gtest.h>

#include <random>

#include "../src/background_histogram.hpp"

namespace tetrapulse::blob_internal {
namespace {

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

}  // namespace
}  // namespace tetrapulse::blob_internal

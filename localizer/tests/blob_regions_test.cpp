// RegionGrower's fast paths give what its plain ones give: an 8-bit window 16-62
// pixels wide (an ROI window) is grown from rows of bits, and a region whose box
// and ring fit 64 columns is measured from rows of bits. Growing is checked
// against the same image as 16 bits (which takes the plain path), pixel for pixel
// and in the order reached (recovery's rim follows it); measuring against the
// sums written out from their definition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "../src/blob_regions.hpp"

namespace tetrapulse::blob_internal {
namespace {

// Noise around 20 and a few spots of random size and brightness, some touching
// (regions of odd shapes) and some cut by the windows.
cv::Mat spots_image(std::mt19937* rng, cv::Size size = {140, 90}, double max_radius = 7) {
  cv::Mat image(size, CV_8U);
  std::uniform_int_distribution<int> noise(8, 32);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) image.at<uint8_t>(y, x) = uint8_t(noise(*rng));
  std::uniform_real_distribution<double> cx(-5, image.cols + 5), cy(-5, image.rows + 5), radius(0.8, max_radius),
      peak(40, 400);
  for (int k = 0; k < 14; ++k) {
    const double x0 = cx(*rng), y0 = cy(*rng), r = radius(*rng), p = peak(*rng);
    for (int y = 0; y < image.rows; ++y)
      for (int x = 0; x < image.cols; ++x) {
        const double d2 = ((x - x0) * (x - x0) + (y - y0) * (y - y0)) / (r * r);
        uint8_t& v = image.at<uint8_t>(y, x);
        v = uint8_t(std::min(255.0, v + p * std::exp(-d2)));
      }
  }
  return image;
}

Levels levels_for(std::mt19937* rng) {
  Levels lv;
  lv.background = 20;
  lv.f2 = std::uniform_real_distribution<double>(30, 70)(*rng);
  lv.f1 = lv.f2 + std::uniform_real_distribution<double>(0, 90)(*rng);
  lv.saturation = 255;
  lv.flat_top_floor = 0.75 * 255;
  return lv;
}

cv::Rect window_for(std::mt19937* rng, const cv::Mat& image, int min_width, int max_width) {
  const int w = std::uniform_int_distribution<int>(min_width, max_width)(*rng);
  const int h = std::uniform_int_distribution<int>(8, 60)(*rng);
  const int x = std::uniform_int_distribution<int>(0, image.cols - w)(*rng);
  const int y = std::uniform_int_distribution<int>(0, image.rows - h)(*rng);
  return {x, y, w, h};
}

struct Grown {
  std::vector<Region> regions;
  std::vector<int32_t> pixels;
  std::vector<int32_t> labels;
};

// Two overlapping windows grown one after the other (the second meets the first's
// labels), as an extraction call does; then the labels of the whole image.
Grown grow_two(const cv::Mat& work, cv::Rect a, cv::Rect b, const Levels& levels) {
  RegionGrower grower;
  grower.reset(work.size());
  Grown g;
  grower.grow(work, a, levels, levels.f1, &g.regions);
  grower.grow(work, b, levels, levels.f1, &g.regions);
  g.pixels = grower.pixels();
  for (int i = 0; i < work.rows * work.cols; ++i) g.labels.push_back(grower.label(i));
  return g;
}

TEST(RegionGrower, NarrowWindowsGrowTheSamePixelsInTheSameOrderAsThePlainPath) {
  std::mt19937 rng(7);
  int regions = 0, narrow = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const cv::Mat image = spots_image(&rng);
    cv::Mat wide;
    image.convertTo(wide, CV_16U);
    const Levels lv = levels_for(&rng);
    // Mostly narrow (16-62), some at and past the bits' limit and below 16.
    const cv::Rect a = window_for(&rng, image, 10, 70), b = window_for(&rng, image, 10, 70);
    narrow += (a.width >= 16 && a.width <= 62) + (b.width >= 16 && b.width <= 62);
    const Grown bits = grow_two(image, a, b, lv), plain = grow_two(wide, a, b, lv);
    ASSERT_EQ(bits.regions.size(), plain.regions.size()) << "trial " << trial;
    for (size_t k = 0; k < bits.regions.size(); ++k) {
      EXPECT_EQ(bits.regions[k].label, plain.regions[k].label) << "trial " << trial;
      EXPECT_EQ(bits.regions[k].begin, plain.regions[k].begin) << "trial " << trial;
      EXPECT_EQ(bits.regions[k].end, plain.regions[k].end) << "trial " << trial;
      EXPECT_EQ(bits.regions[k].box, plain.regions[k].box) << "trial " << trial;
    }
    ASSERT_EQ(bits.pixels, plain.pixels) << "trial " << trial;
    ASSERT_EQ(bits.labels, plain.labels) << "trial " << trial;
    regions += int(bits.regions.size());
  }
  EXPECT_GT(regions, 500);  // 754 with this seed
  EXPECT_GT(narrow, 400);
}

// A whole-image window of a narrow image taller than 65535 rows (grow_bits packs
// row numbers in 16 bits) takes the plain path: spots below row 65535 too.
TEST(RegionGrower, ANarrowWindowOfMoreThan65535RowsGrowsAsThePlainPath) {
  cv::Mat image(70000, 20, CV_8U, cv::Scalar(10));
  for (const int y : {100, 65534, 65600, 69990})
    for (int dy = -2; dy <= 2; ++dy)
      for (int x = 8; x <= 11; ++x) image.at<uint8_t>(y + dy, x) = uint8_t(200 - 20 * std::abs(dy));
  cv::Mat wide;
  image.convertTo(wide, CV_16U);
  Levels lv;
  lv.background = 10, lv.f2 = 50, lv.f1 = 150, lv.saturation = 255;
  const cv::Rect all(0, 0, image.cols, image.rows);
  const cv::Rect none(0, 0, 0, 0);
  const Grown bits = grow_two(image, all, none, lv), plain = grow_two(wide, all, none, lv);
  ASSERT_EQ(bits.regions.size(), 4u);
  ASSERT_EQ(plain.regions.size(), 4u);
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(bits.regions[k].box, plain.regions[k].box);
  EXPECT_EQ(bits.pixels, plain.pixels);
}

// The measurement's sums from their definition: the region's pixels, and the
// unlabelled pixels of the window brighter than the background that touch one,
// in row order.
RegionSums sums_by_definition(const cv::Mat& work, cv::Rect window, const RegionGrower& grower,
                              const Region& region, double bg) {
  RegionSums s;
  const int width = work.cols;
  const auto label_at = [&](int x, int y) {
    return window.contains(cv::Point(x, y)) ? grower.label(y * width + x) : -1;
  };
  int top = -1;
  for (int y = window.y; y < window.br().y; ++y)
    for (int x = window.x; x < window.br().x; ++x) {
      const int value = work.at<uint8_t>(y, x);
      const double d = double(value) - bg;
      const int32_t l = label_at(x, y);
      bool touches = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) touches = touches || label_at(x + dx, y + dy) == region.label;
      if (l == region.label) {
        ++s.area;
        s.sx += x, s.sy += y, s.sxx += double(x) * x, s.sxy += double(x) * y, s.syy += double(y) * y;
        top = std::max(top, value);
      } else if (l != 0 || d <= 0 || !touches) {
        continue;
      }
      s.w += d;
      s.wx += d * x;
      s.wy += d * y;
    }
  s.peak = double(top) - bg;
  return s;
}

// Each region of two overlapping windows measured, against the definition; counts
// the regions, and those whose box and ring are wider than 64 pixels.
std::pair<int, int> measure_against_definition(std::mt19937* rng, cv::Size size, double max_radius, int min_width,
                               int max_width) {
  const cv::Mat image = spots_image(rng, size, max_radius);
  const Levels lv = levels_for(rng);
  const cv::Rect a = window_for(rng, image, min_width, max_width), b = window_for(rng, image, min_width, max_width);
  RegionGrower grower;
  grower.reset(image.size());
  std::vector<Region> regions;
  grower.grow(image, a, lv, lv.f1, &regions);
  const size_t first_of_b = regions.size();
  grower.grow(image, b, lv, lv.f1, &regions);
  int wide = 0;
  for (size_t k = 0; k < regions.size(); ++k) {
    const cv::Rect window = k < first_of_b ? a : b;
    Region r = regions[k];
    grower.measure(image, window, lv, &r);
    const RegionSums want = sums_by_definition(image, window, grower, r, lv.background);
    EXPECT_EQ(r.sums.area, want.area);
    EXPECT_EQ(r.sums.sx, want.sx);
    EXPECT_EQ(r.sums.sy, want.sy);
    EXPECT_EQ(r.sums.sxx, want.sxx);
    EXPECT_EQ(r.sums.sxy, want.sxy);
    EXPECT_EQ(r.sums.syy, want.syy);
    EXPECT_EQ(r.sums.w, want.w);  // the same terms in the same order
    EXPECT_EQ(r.sums.wx, want.wx);
    EXPECT_EQ(r.sums.wy, want.wy);
    EXPECT_EQ(r.sums.peak, want.peak);
    wide += r.box.width + 2 > 64;
  }
  return {int(regions.size()), wide};
}

TEST(RegionGrower, MeasuringFromRowsOfBitsGivesTheSumsOfTheDefinition) {
  std::mt19937 rng(11);
  int measured = 0;
  for (int trial = 0; trial < 200 && !HasFailure(); ++trial)
    measured += measure_against_definition(&rng, {140, 90}, 7, 16, 62).first;
  EXPECT_GT(measured, 350);  // 532 with this seed
}

// Regions wider than 62 pixels (a close marker in a whole-image window) take the
// plain sweep.
TEST(RegionGrower, MeasuringWideRegionsGivesTheSumsOfTheDefinition) {
  std::mt19937 rng(13);
  int wide = 0;
  for (int trial = 0; trial < 40 && !HasFailure(); ++trial)
    wide += measure_against_definition(&rng, {200, 160}, 45, 150, 200).second;
  EXPECT_GT(wide, 20);
}

// The hull of the pixel squares: a plus of five pixels is a 3 x 3 square less four
// corner triangles of half a pixel each.
TEST(RegionGrower, AHullIsThatOfThePixelSquares) {
  cv::Mat image(20, 30, CV_8U, cv::Scalar(10));
  for (const cv::Point p : {cv::Point(10, 9), cv::Point(9, 10), cv::Point(10, 10), cv::Point(11, 10),
                            cv::Point(10, 11)})
    image.at<uint8_t>(p) = 200;
  image.at<uint8_t>(5, 20) = 200;  // a single pixel: its own square
  Levels lv;
  lv.background = 10, lv.f2 = 50, lv.f1 = 100, lv.saturation = 255;
  RegionGrower grower;
  grower.reset(image.size());
  std::vector<Region> regions;
  const cv::Rect window(2, 2, 24, 16);
  grower.grow(image, window, lv, lv.f1, &regions);
  ASSERT_EQ(regions.size(), 2u);
  for (Region& r : regions) grower.measure(image, window, lv, &r);
  EXPECT_EQ(regions[0].sums.area, 1);
  EXPECT_EQ(regions[0].sums.hull_area, 1.0);
  EXPECT_EQ(regions[1].sums.area, 5);
  EXPECT_EQ(regions[1].sums.hull_area, 7.0);
  EXPECT_DOUBLE_EQ(regions[1].blob.convexity, 5.0 / 7.0);
}

}  // namespace
}  // namespace tetrapulse::blob_internal

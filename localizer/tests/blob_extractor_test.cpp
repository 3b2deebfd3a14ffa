#include "tetrapulse/localizer/blob_extractor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <opencv2/imgproc.hpp>

#include "spot_renderer.hpp"

namespace tetrapulse {
namespace {

using test::add_disc;
using test::add_gaussian;
using test::add_noise;
using test::quantise;

cv::Mat1d canvas(int w, int h, double background) { return cv::Mat1d(h, w, background); }

BlobExtraction extract(const cv::Mat& image, int expected, BlobExtractorConfig config = {}) {
  BlobExtractor extractor(config);
  BlobExtraction out;
  const auto ok = extractor.extract(image, expected, &out);
  EXPECT_TRUE(ok) << (ok ? "" : ok.error().message);
  return out;
}

// The blob nearest `p`, or nullptr.
const Blob* nearest(const std::vector<Blob>& blobs, const Eigen::Vector2d& p) {
  const Blob* best = nullptr;
  for (const Blob& b : blobs)
    if (!best || (b.centroid - p).norm() < (best->centroid - p).norm()) best = &b;
  return best;
}

bool has_reason(const BlobExtraction& out, RejectReason reason) {
  for (const RejectedBlob& r : out.rejected)
    if (r.reason == reason) return true;
  return false;
}

// Worst centroid error over a 5 x 5 grid of sub-pixel offsets of one spot
// that `draw(image, centre)` renders on a noiseless 8-bit background of 20.
template <typename Draw>
double worst_centroid_error(Draw draw) {
  double worst = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      auto img = canvas(64, 64, 20);
      const Eigen::Vector2d c(31.0 + 0.2 * i + 0.037, 30.0 + 0.2 * j + 0.081);
      draw(&img, c);
      const auto out = extract(quantise(img, CV_8U), 1);
      if (out.blobs.size() != 1) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, (out.blobs[0].centroid - c).norm());
    }
  return worst;
}

TEST(BlobExtractor, GaussianCentroidsWithin005PxWithoutNoise) {
  for (const double sigma : {0.7, 1.0, 1.5, 2.5, 4.0}) {
    EXPECT_LT(worst_centroid_error([&](cv::Mat1d* img, const Eigen::Vector2d& c) { add_gaussian(img, c, sigma, 200); }),
              0.05)
        << "sigma " << sigma;
  }
}

TEST(BlobExtractor, DiscCentroidsWithin005PxWithoutNoise) {
  for (const double radius : {1.5, 2.5, 4.0, 7.0}) {
    EXPECT_LT(worst_centroid_error([&](cv::Mat1d* img, const Eigen::Vector2d& c) { add_disc(img, c, radius, 180); }),
              0.05)
        << "radius " << radius;
  }
}

TEST(BlobExtractor, DiscIntensityIsItsIntegratedLight) {
  for (const double radius : {1.5, 2.5, 4.0, 7.0}) {
    auto img = canvas(48, 48, 12);
    add_disc(&img, {23.3, 24.6}, radius, 180);
    const auto out = extract(quantise(img, CV_8U), 1);
    ASSERT_EQ(out.blobs.size(), 1u);
    const double light = 180 * M_PI * radius * radius;
    EXPECT_NEAR(out.blobs[0].intensity, light, 0.02 * light) << "radius " << radius;
  }
}

TEST(BlobExtractor, ReportsIntensityPeakAreaAndBackground) {
  auto img = canvas(64, 64, 25);
  add_gaussian(&img, {30.4, 33.6}, 1.5, 150);
  const auto out = extract(quantise(img, CV_8U), 1);
  ASSERT_EQ(out.blobs.size(), 1u);
  const Blob& b = out.blobs[0];
  const double volume = 150 * 2 * M_PI * 1.5 * 1.5;
  EXPECT_NEAR(b.intensity, volume, 0.01 * volume);
  EXPECT_NEAR(b.background, 25, 0.5);
  EXPECT_GT(b.peak, 0.8 * 150);
  EXPECT_LE(b.peak, 150);
  EXPECT_GT(b.area, 20);
  EXPECT_FALSE(b.saturated);
  EXPECT_FALSE(b.clipped);
  EXPECT_EQ(b.origin, BlobOrigin::kThreshold);
  ASSERT_EQ(out.windows.size(), 1u);
  EXPECT_GT(out.windows[0].f1, out.windows[0].f2);
}

TEST(BlobExtractor, FlagsSaturatedBlobs) {
  auto img = canvas(64, 64, 25);
  add_disc(&img, {30.4, 33.6}, 4, 400);
  const auto out = extract(quantise(img, CV_8U), 1);
  ASSERT_EQ(out.blobs.size(), 1u);
  EXPECT_TRUE(out.blobs[0].saturated);
  EXPECT_NEAR(out.blobs[0].centroid.x(), 30.4, 0.05);
}

// A sensor that clips below the type's top code (here at 250): the flat top says
// saturated; a streak of such light drawn out along the columns (blooming) is
// one marker, centred on its spot.
TEST(BlobExtractor, FlagsFlatToppedAndBloomedBlobsBelowTheTopCode) {
  auto img = canvas(64, 96, 25);
  add_disc(&img, {30.4, 47.6}, 4, 400);
  cv::Mat clipped = quantise(img, CV_8U);
  cv::min(clipped, 250, clipped);
  auto out = extract(clipped, 1);
  ASSERT_EQ(out.blobs.size(), 1u);
  EXPECT_TRUE(out.blobs[0].saturated);
  EXPECT_FALSE(out.blobs[0].bloomed);
  // Spill 12 rows up and down the disc's columns.
  for (int x = 0; x < clipped.cols; ++x) {
    int top = -1, bottom = -1;
    for (int y = 0; y < clipped.rows; ++y)
      if (clipped.at<uint8_t>(y, x) == 250) bottom = y, top = top < 0 ? y : top;
    for (int d = 1; top >= 0 && d <= 12; ++d) clipped.at<uint8_t>(top - d, x) = clipped.at<uint8_t>(bottom + d, x) = 250;
  }
  out = extract(clipped, 1);
  ASSERT_EQ(out.blobs.size(), 1u) << "the streak is one marker, not rejected as eccentric";
  EXPECT_TRUE(out.blobs[0].bloomed);
  EXPECT_GT(out.blobs[0].eccentricity, 0.8);
  EXPECT_NEAR(out.blobs[0].centroid.x(), 30.4, 0.3);
  EXPECT_NEAR(out.blobs[0].centroid.y(), 47.6, 0.6);
}

// 16 spots on a VGA-sized frame with read noise: all found, nothing else.
TEST(BlobExtractor, FindsSixteenSpotsInNoiseWithoutFalsePositives) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ux(20, 732), uy(20, 460), us(1.0, 2.0);
  for (int trial = 0; trial < 5; ++trial) {
    auto img = canvas(752, 480, 30);
    std::vector<Eigen::Vector2d> truth;
    while (truth.size() < 16) {
      const Eigen::Vector2d c(ux(rng), uy(rng));
      bool apart = true;
      for (const auto& t : truth) apart = apart && (t - c).norm() > 25;
      if (!apart) continue;
      truth.push_back(c);
      add_gaussian(&img, c, us(rng), 120);
    }
    add_noise(&img, 4.0, 100 + trial);
    const auto out = extract(quantise(img, CV_8U), 16);
    ASSERT_EQ(out.blobs.size(), 16u) << "trial " << trial;
    for (const auto& c : truth) {
      const Blob* b = nearest(out.blobs, c);
      ASSERT_NE(b, nullptr);
      EXPECT_LT((b->centroid - c).norm(), 0.15) << "trial " << trial;
    }
    EXPECT_NEAR(out.windows[0].background, 30, 0.5);
    EXPECT_NEAR(out.windows[0].background_sigma, 4.0, 0.3);
  }
}

TEST(BlobExtractor, RejectsDistractorsBySizeAndShape) {
  auto img = canvas(200, 160, 20);
  const std::vector<Eigen::Vector2d> truth = {{30.3, 30.6}, {160.2, 25.4}, {40.7, 130.1}, {170.5, 140.8}};
  for (const auto& c : truth) add_disc(&img, c, 3.5, 170);
  img(cv::Rect(60, 20, 60, 70)) += 170.0;  // a lamp: too large
  img(cv::Rect(10, 100, 40, 2)) += 170.0;  // a cable: eccentric
  img(cv::Rect(80, 110, 20, 3)) += 170.0;  // a "U": non-convex
  img(cv::Rect(80, 110, 3, 20)) += 170.0;
  img(cv::Rect(97, 110, 3, 20)) += 170.0;
  img(140, 90) += 170.0;                   // a hot pixel: too small
  BlobExtractorConfig config;
  config.max_area = 1000;
  const auto out = extract(quantise(img, CV_8U), 0, config);
  ASSERT_EQ(out.blobs.size(), truth.size());
  for (const auto& c : truth) EXPECT_LT((nearest(out.blobs, c)->centroid - c).norm(), 0.05);
  EXPECT_TRUE(has_reason(out, RejectReason::kTooLarge));
  EXPECT_TRUE(has_reason(out, RejectReason::kEccentric));
  EXPECT_TRUE(has_reason(out, RejectReason::kNonConvex));
  EXPECT_TRUE(has_reason(out, RejectReason::kTooSmall));
}

TEST(BlobExtractor, PrunesTheIsolatedBlobWhenThereAreTooMany) {
  auto img = canvas(200, 160, 20);
  const std::vector<Eigen::Vector2d> target = {{80.2, 70.3}, {100.6, 72.1}, {90.4, 90.8}, {110.1, 95.5}};
  for (const auto& c : target) add_disc(&img, c, 3, 170);
  add_disc(&img, {185.3, 150.2}, 3, 170);  // a reflection far from the target
  const auto out = extract(quantise(img, CV_8U), 4);
  ASSERT_EQ(out.blobs.size(), 4u);
  for (const auto& c : target) EXPECT_LT((nearest(out.blobs, c)->centroid - c).norm(), 0.05);
  EXPECT_TRUE(has_reason(out, RejectReason::kIsolated));
}

TEST(BlobExtractor, MergesTheClosestPairWhenThereAreTooMany) {
  auto img = canvas(120, 120, 20);
  add_disc(&img, {30.2, 30.7}, 3, 170);
  add_disc(&img, {90.4, 40.1}, 3, 170);
  add_disc(&img, {60.6, 90.3}, 3, 170);
  const Eigen::Vector2d marker(60.3, 45.5), ghost(66.8, 45.1);  // a marker and its reflection
  add_disc(&img, marker, 3, 170);
  add_disc(&img, ghost, 1.5, 170);
  const auto out = extract(quantise(img, CV_8U), 4);
  ASSERT_EQ(out.blobs.size(), 4u);
  const Blob* merged = nearest(out.blobs, marker);
  EXPECT_EQ(merged->origin, BlobOrigin::kMerged);
  // One blob with both lights: the intensity-weighted mean of the two centres.
  const double wa = 9.0, wb = 1.5 * 1.5;
  EXPECT_LT((merged->centroid - (wa * marker + wb * ghost) / (wa + wb)).norm(), 0.05);
  EXPECT_NEAR(merged->intensity, 170 * M_PI * (wa + wb), 0.02 * 170 * M_PI * (wa + wb));
  EXPECT_TRUE(has_reason(out, RejectReason::kMerged));
}

TEST(BlobExtractor, SplitsTwoMergedMarkersByErosion) {
  for (const double gap : {7.0, 7.5, 8.2}) {
    auto img = canvas(100, 80, 15);
    const Eigen::Vector2d a(40.3, 40.2), b = a + Eigen::Vector2d(gap, 0.9);
    add_disc(&img, a, 4, 170);
    add_disc(&img, b, 4, 170);
    cv::min(img, 185.0, img);  // overlapping light clips like a sensor
    const auto out = extract(quantise(img, CV_8U), 2);
    ASSERT_EQ(out.blobs.size(), 2u) << "gap " << gap;
    for (const auto& c : {a, b}) {
      const Blob* blob = nearest(out.blobs, c);
      EXPECT_EQ(blob->origin, BlobOrigin::kErosionSplit);
      EXPECT_LT((blob->centroid - c).norm(), 0.3) << "gap " << gap;
    }
    ASSERT_FALSE(out.rejected.empty());
    EXPECT_TRUE(out.rejected[0].recovered);
  }
}

TEST(BlobExtractor, FindsTheCentreOfAHalfShadowedMarkerByCircleFit) {
  // The centroid of a half disc lies 4 r / (3 pi) (2.1 px at r = 5) off its centre.
  double worst = 0;
  for (const double radius : {5.0, 7.0, 12.0})
    for (const double cx : {50.0, 50.35, 50.7})
      for (const double cy : {40.2, 40.5, 40.9}) {
        auto img = canvas(100, 80, 15);
        const Eigen::Vector2d c(cx, cy);
        add_disc(&img, c, radius, 170, [&](double, double y) { return y < c.y(); });  // bottom half in shadow
        const auto out = extract(quantise(img, CV_8U), 1);
        ASSERT_EQ(out.blobs.size(), 1u);
        EXPECT_EQ(out.blobs[0].origin, BlobOrigin::kCircleFit);
        worst = std::max(worst, (out.blobs[0].centroid - c).norm());
        EXPECT_NEAR(out.blobs[0].radius, radius, 0.2);
      }
  EXPECT_LT(worst, 0.15);
}

TEST(BlobExtractor, FindsAMarkerCutByTheImageBorderByCircleFit) {
  auto img = canvas(100, 80, 15);
  const Eigen::Vector2d c(1.2, 40.4);  // more than half outside the left border
  add_disc(&img, c, 6, 170);
  const auto out = extract(quantise(img, CV_8U), 1);
  ASSERT_EQ(out.blobs.size(), 1u);
  EXPECT_TRUE(out.blobs[0].clipped);
  EXPECT_EQ(out.blobs[0].origin, BlobOrigin::kCircleFit);
  EXPECT_LT((out.blobs[0].centroid - c).norm(), 0.3);
}

TEST(BlobExtractor, ABlobWhoseLightReachesTheBorderUncentredIsCutByIt) {
  // A marker centred 1 px below the top edge loses its upper part: the centroid
  // of what is left sits lower; a circle fit centres it, and then it is whole.
  auto img = canvas(100, 80, 15);
  const Eigen::Vector2d c(50.3, 1.0);
  add_disc(&img, c, 6, 170);
  BlobExtractorConfig config;
  config.refit_clipped = false;
  const auto uncentred = extract(quantise(img, CV_8U), 1, config);
  ASSERT_EQ(uncentred.blobs.size(), 1u);
  EXPECT_GT(uncentred.blobs[0].centroid.y() - c.y(), 1.0);
  EXPECT_TRUE(cut_by_border(uncentred.blobs[0], 100, 80));
  Blob fitted = uncentred.blobs[0];
  fitted.origin = BlobOrigin::kCircleFit;
  EXPECT_FALSE(cut_by_border(fitted, 100, 80));
  // On the border's pixels: cut; one pixel inside (its ring on them), whole,
  // unless recovery grew it from what the border left; two pixels inside, whole.
  Blob near;
  for (const auto& [box, cut] : {std::pair{cv::Rect(0, 30, 8, 8), true}, std::pair{cv::Rect(1, 30, 8, 8), false},
                                 std::pair{cv::Rect(92, 30, 8, 8), true}, std::pair{cv::Rect(91, 30, 8, 8), false},
                                 std::pair{cv::Rect(40, 72, 8, 8), true}, std::pair{cv::Rect(40, 71, 8, 8), false},
                                 std::pair{cv::Rect(40, 0, 8, 8), true}, std::pair{cv::Rect(40, 1, 8, 8), false}}) {
    near.bbox = box;
    near.origin = BlobOrigin::kThreshold;
    EXPECT_EQ(cut_by_border(near, 100, 80), cut) << box;
    near.origin = BlobOrigin::kDimRecovery;
    const bool ring_on_border = box.x <= 1 || box.y <= 1 || box.br().x >= 99 || box.br().y >= 79;
    EXPECT_EQ(cut_by_border(near, 100, 80), ring_on_border) << box;
  }
  near.bbox = cv::Rect(2, 30, 8, 8);
  EXPECT_FALSE(cut_by_border(near, 100, 80));
}

TEST(BlobExtractor, RecoversADimMarkerBelowOtsu) {
  auto img = canvas(160, 120, 20);
  const Eigen::Vector2d bright1(40.2, 40.3), bright2(120.6, 40.1), dim(80.4, 90.7);
  add_gaussian(&img, bright1, 1.5, 220);
  add_gaussian(&img, bright2, 1.5, 220);
  add_gaussian(&img, dim, 1.5, 220 * 0.3);  // a two_level marker in a 0 bit
  add_noise(&img, 2.0, 5);
  BlobExtractorConfig config;
  config.f1_min_sigmas = 20;  // a strict F1, as in a bright scene
  const auto without = extract(quantise(img, CV_8U), 0, config);
  EXPECT_EQ(without.blobs.size(), 2u);
  const auto out = extract(quantise(img, CV_8U), 3, config);
  ASSERT_EQ(out.blobs.size(), 3u);
  const Blob* d = nearest(out.blobs, dim);
  EXPECT_EQ(d->origin, BlobOrigin::kDimRecovery);
  EXPECT_LT((d->centroid - dim).norm(), 0.15);
}

TEST(BlobExtractor, FindsDarkMarkersOnABrightBackground) {
  auto img = canvas(160, 120, 200);
  const std::vector<Eigen::Vector2d> truth = {{40.3, 30.2}, {110.7, 40.9}, {60.1, 90.4}, {130.5, 95.6}};
  for (const auto& c : truth) add_disc(&img, c, 4, -160);
  add_noise(&img, 3.0, 9);
  BlobExtractorConfig config;
  config.polarity = MarkerPolarity::kDark;
  const auto out = extract(quantise(img, CV_8U), 4, config);
  ASSERT_EQ(out.blobs.size(), 4u);
  for (const auto& c : truth) EXPECT_LT((nearest(out.blobs, c)->centroid - c).norm(), 0.1);
  EXPECT_NEAR(out.blobs[0].background, 200, 1.0);
  EXPECT_NEAR(out.blobs[0].peak, 160, 15);
  // The same image read for light markers finds none of them.
  EXPECT_EQ(extract(quantise(img, CV_8U), 0).blobs.size(), 0u);
}

TEST(BlobExtractor, Handles16BitImages) {
  auto img = canvas(320, 240, 3000);
  const std::vector<Eigen::Vector2d> truth = {{40.3, 30.2}, {110.7, 40.9}, {60.1, 90.4}};
  for (const auto& c : truth) add_gaussian(&img, c, 1.6, 30000);
  add_noise(&img, 40.0, 3);
  const auto out = extract(quantise(img, CV_16U), 3);
  ASSERT_EQ(out.blobs.size(), 3u);
  for (const auto& c : truth) EXPECT_LT((nearest(out.blobs, c)->centroid - c).norm(), 0.05);
  EXPECT_NEAR(out.windows[0].background, 3000, 10);
  EXPECT_NEAR(out.windows[0].background_sigma, 40, 4);
  const double volume = 30000 * 2 * M_PI * 1.6 * 1.6;
  EXPECT_NEAR(out.blobs[0].intensity, volume, 0.03 * volume);
}

TEST(BlobExtractor, Handles12BitDataShiftedInto16Bits) {
  // Small and large windows take different paths through the histogram.
  for (const cv::Size size : {cv::Size(160, 120), cv::Size(320, 240)}) {
    auto img = canvas(size.width, size.height, 200);
    const Eigen::Vector2d c(70.3, 50.8);
    add_gaussian(&img, c, 1.6, 3000);
    add_noise(&img, 3.0, 3);
    cv::Mat twelve = quantise(img, CV_16U);
    cv::Mat shifted = twelve * 16;  // sensor data in the top 12 bits
    const auto out = extract(shifted, 1);
    ASSERT_EQ(out.blobs.size(), 1u);
    EXPECT_LT((out.blobs[0].centroid - c).norm(), 0.05);
    EXPECT_NEAR(out.windows[0].background, 200 * 16, 16);
    EXPECT_NEAR(out.windows[0].background_sigma, 3 * 16, 8);
  }
}

cv::Mat3b colour_canvas(int w, int h, cv::Vec3b bgr) { return cv::Mat3b(h, w, bgr); }

void add_colour_disc(cv::Mat3b* img, const Eigen::Vector2d& c, double radius, cv::Vec3d bgr) {
  cv::Mat1d cover(img->rows, img->cols, 0.0);
  add_disc(&cover, c, radius, 1.0);
  for (int y = 0; y < img->rows; ++y)
    for (int x = 0; x < img->cols; ++x) {
      const double a = cover(y, x);
      if (a <= 0) continue;
      for (int k = 0; k < 3; ++k)
        (*img)(y, x)[k] = cv::saturate_cast<uint8_t>((1 - a) * (*img)(y, x)[k] + a * bgr[k]);
    }
}

TEST(BlobExtractor, FindsColouredMarkersByChroma) {
  auto img = colour_canvas(160, 120, {70, 80, 75});
  const Eigen::Vector2d red1(40.3, 40.6), red2(120.2, 80.3), green(80.5, 40.2), white(60.7, 90.1);
  add_colour_disc(&img, red1, 4, {40, 40, 220});
  add_colour_disc(&img, red2, 4, {40, 40, 220});
  add_colour_disc(&img, green, 4, {40, 220, 40});
  add_colour_disc(&img, white, 4, {230, 230, 230});
  cv::Mat noise(img.size(), CV_8SC3);
  cv::randn(noise, 0, 3);
  cv::Mat noisy;
  cv::add(img, noise, noisy, cv::noArray(), CV_8UC3);
  BlobExtractorConfig config;
  // Red's chroma: Y = 0.299 R + 0.587 G + 0.114 B, Cr = 0.713 (R - Y) + 128, Cb = 0.564 (B - Y) + 128.
  const double y = 0.299 * 220 + 0.587 * 40 + 0.114 * 40;
  config.colour = ColourTarget{0.713 * (220 - y) + 128, 0.564 * (40 - y) + 128, 25, 16};
  const auto out = extract(noisy, 2, config);
  ASSERT_EQ(out.blobs.size(), 2u);
  for (const auto& c : {red1, red2}) EXPECT_LT((nearest(out.blobs, c)->centroid - c).norm(), 0.1);
  // Read as grey, the red discs are too faint against the background (their
  // luma is about 94 on 77) and the green and white ones are found instead.
  const auto grey = extract(noisy, 0);
  ASSERT_EQ(grey.blobs.size(), 2u);
  EXPECT_LT((nearest(grey.blobs, green)->centroid - green).norm(), 0.1);
  EXPECT_LT((nearest(grey.blobs, white)->centroid - white).norm(), 0.1);
}

TEST(BlobExtractor, RejectsInputsItCannotReadWithAMessage) {
  BlobExtractor extractor;
  BlobExtraction out;
  auto r = extractor.extract(cv::Mat(), 4, &out);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().message, "image: empty");
  r = extractor.extract(cv::Mat(10, 10, CV_32FC1, cv::Scalar(0)), 4, &out);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("32FC1"), std::string::npos);
  BlobExtractorConfig colour;
  colour.colour = ColourTarget{};
  r = BlobExtractor(colour).extract(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), 4, &out);
  ASSERT_FALSE(r);
}

TEST(BlobExtractor, AllSaturatedImageGivesNoBlobs) {
  for (const int type : {CV_8UC1, CV_16UC1}) {
    const cv::Mat img(60, 80, type, cv::Scalar(type == CV_8UC1 ? 255 : 65535));
    const auto out = extract(img, 4);
    EXPECT_TRUE(out.blobs.empty());
  }
}

// ROI mode --------------------------------------------------------------------

BlobRoi roi(const Eigen::Vector2d& c, int64_t tag, double radius = 8, double aperture = 5) {
  BlobRoi r;
  r.center = c;
  r.radius = radius;
  r.aperture_radius = aperture;
  r.tag = tag;
  return r;
}

TEST(BlobExtractor, FindsMarkersOnABackgroundThatIsNotFlat) {
  // A lamp's gradient from 20 to 150 grey levels across the image, with noise: one
  // threshold over the whole image would sit above the markers in its dark half.
  // Flattened against its own background map, all eight spots are found, centred
  // within 0.15 px (0.11 at worst here, noise of 1.5 grey levels on a 80-level spot), and nothing else.
  cv::Mat1d img(240, 320);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x) img(y, x) = 20 + 130.0 * x / img.cols + 10 * std::sin(y / 40.0);
  std::vector<Eigen::Vector2d> spots;
  for (int k = 0; k < 8; ++k) {
    spots.emplace_back(30.3 + 36.1 * k, 60.7 + 17.9 * (k % 3));
    add_gaussian(&img, spots.back(), 1.5, 80);
  }
  add_noise(&img, 1.5, 7);
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), 0, &out));
  ASSERT_EQ(out.blobs.size(), spots.size());
  for (const Eigen::Vector2d& c : spots) {
    const Blob* b = nearest(out.blobs, c);
    ASSERT_NE(b, nullptr);
    EXPECT_LT((b->centroid - c).norm(), 0.15);
  }
}

TEST(BlobExtractor, RoiWindowFilledByAClippedDiscKeepsItsBackground) {
  // A marker at close range: a disc 15 px in radius clipped at 252 (an 8-bit
  // sensor's full well under the top code) fills 40 % of its ROI's 47 x 47 window,
  // more than any one grey level of the noisy background holds. The background
  // comes from below the clipped pile-up, not from it: the disc is detected,
  // centred, and its intensity is its light over a background of about 8.
  auto img = canvas(120, 120, 8);
  const Eigen::Vector2d c(60.3, 59.6);
  add_disc(&img, c, 15, 2500);
  add_noise(&img, 1.0, 5);
  cv::Mat clipped = quantise(img, CV_8U);
  cv::min(clipped, 252, clipped);
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(clipped, {roi(c + Eigen::Vector2d(2.0, -1.5), 3, 6, 17.5)}, &out));
  ASSERT_EQ(out.rois.size(), 1u);
  ASSERT_EQ(out.rois[0].status, RoiStatus::kDetected);
  EXPECT_TRUE(out.rois[0].blob.saturated);
  EXPECT_LT((out.rois[0].position - c).norm(), 0.1);
  ASSERT_EQ(out.windows.size(), 1u);
  EXPECT_NEAR(out.windows[0].background, 8, 1);
  const double disc = M_PI * 15 * 15 * (252 - 8);
  EXPECT_NEAR(out.rois[0].intensity, disc, 0.08 * disc);
}

TEST(BlobExtractor, RoiModeMeasuresPresentDimAndAbsentMarkers) {
  auto img = canvas(200, 160, 25);
  const Eigen::Vector2d on(50.3, 40.7), dim(140.6, 45.2), off(60.2, 120.4), far(150.1, 130.3);
  add_gaussian(&img, on, 1.5, 180);
  add_gaussian(&img, dim, 1.5, 180 * 0.3);  // two_level 0 bit
  add_gaussian(&img, far, 1.5, 180);
  // `off`: an on_off marker in a 0 bit, nothing drawn.
  const double noise = 3.0;
  add_noise(&img, noise, 21);
  const std::vector<BlobRoi> rois = {roi(on + Eigen::Vector2d(1.5, -1.0), 7), roi(dim + Eigen::Vector2d(-2, 0.5), 8),
                                     roi(off, 9), roi(far, 10)};
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), rois, &out));
  ASSERT_EQ(out.rois.size(), 4u);
  const double volume = 180 * 2 * M_PI * 1.5 * 1.5;
  EXPECT_EQ(out.rois[0].tag, 7);
  EXPECT_EQ(out.rois[0].status, RoiStatus::kDetected);
  EXPECT_LT((out.rois[0].position - on).norm(), 0.1);
  EXPECT_NEAR(out.rois[0].intensity, volume, 0.05 * volume);
  EXPECT_NEAR(out.rois[0].aperture_intensity, volume, 0.05 * volume);
  EXPECT_EQ(out.rois[1].status, RoiStatus::kDetected);
  EXPECT_NEAR(out.rois[1].aperture_intensity / out.rois[0].aperture_intensity, 0.3, 0.03);
  EXPECT_EQ(out.rois[2].tag, 9);
  EXPECT_EQ(out.rois[2].status, RoiStatus::kAbsent);
  EXPECT_EQ(out.rois[2].position, off);
  EXPECT_GT(out.rois[2].aperture_pixels, 70);
  // An empty aperture reads zero within its noise (4 sigma of a sum of pixels).
  EXPECT_LT(std::abs(out.rois[2].intensity), 4 * noise * std::sqrt(out.rois[2].aperture_pixels));
  EXPECT_EQ(out.rois[2].intensity, out.rois[2].aperture_intensity);
  EXPECT_NEAR(out.rois[2].background, 25, 1.0);
  EXPECT_EQ(out.rois[3].status, RoiStatus::kDetected);
  EXPECT_TRUE(out.blobs.empty());
}

TEST(BlobExtractor, RoiModeGivesEachOfTwoCloseMarkersItsOwnBlob) {
  auto img = canvas(120, 100, 20);
  const Eigen::Vector2d a(50.2, 50.3), b(58.6, 51.1);
  add_gaussian(&img, a, 1.2, 200);
  add_gaussian(&img, b, 1.2, 200);
  // Predictions both nearer to `b` than to `a`: only a joint assignment gets both right.
  const std::vector<BlobRoi> rois = {roi(a + Eigen::Vector2d(4.5, 0), 1, 6), roi(b + Eigen::Vector2d(-1.0, 0), 2, 6)};
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), rois, &out));
  ASSERT_EQ(out.windows.size(), 1u);  // one window for both
  ASSERT_TRUE(out.rois[0].detected());
  ASSERT_TRUE(out.rois[1].detected());
  EXPECT_LT((out.rois[0].position - a).norm(), 0.05);
  EXPECT_LT((out.rois[1].position - b).norm(), 0.05);
}

TEST(BlobExtractor, RoiModeSplitsMergedMarkersBetweenTheirPredictions) {
  // Two discs of 4 px radius 6 px apart merge into one blob; their targets'
  // poses predict them 1 px off. Split between the predictions, each part's
  // centroid lies far nearer its disc than the merged blob's centroid does, and
  // the parts are marked merged, one group.
  auto img = canvas(120, 100, 20);
  const Eigen::Vector2d a(50.3, 50.2), b(56.1, 51.4);
  add_disc(&img, a, 4.0, 160);
  add_disc(&img, b, 4.0, 120);
  const Eigen::Vector2d off(0.7, -0.6);
  std::vector<BlobRoi> rois = {roi(a + off, 1, 5), roi(b + off, 2, 5)};
  for (BlobRoi& r : rois) r.splits = true;
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), rois, &out));
  ASSERT_TRUE(out.rois[0].detected());
  ASSERT_TRUE(out.rois[1].detected());
  const Blob& pa = out.rois[0].blob;
  const Blob& pb = out.rois[1].blob;
  EXPECT_TRUE(pa.merged && pb.merged);
  EXPECT_EQ(pa.origin, BlobOrigin::kPredictionSplit);
  EXPECT_EQ(pa.merge_group, pb.merge_group);
  EXPECT_EQ(pa.merge_parts, 2);
  const Eigen::Vector2d whole = (pa.intensity * pa.centroid + pb.intensity * pb.centroid) / (pa.intensity + pb.intensity);
  EXPECT_LT((pa.centroid - a).norm(), 0.6);
  EXPECT_LT((pb.centroid - b).norm(), 0.6);
  EXPECT_GT((whole - a).norm(), 2.5);  // what one centroid of both would have said
  // The light's centroid is the flux-weighted mean of the two discs.
  const Eigen::Vector2d truth = (160 * a + 120 * b) / 280.0;
  EXPECT_LT((whole - truth).norm(), 0.05);
  // Without predictions of both, nothing is split.
  rois[1].splits = false;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), rois, &out));
  EXPECT_FALSE(out.rois[0].blob.merged);
}

TEST(BlobExtractor, RoiModeSplitsTouchingSpotsAtTheValleyBetweenThem) {
  // Two drones crossing (crowd): a sphere image 6.5 px in radius touches a dimmer
  // one 5.5 px in radius, 12.5 px apart, the light between them down to a
  // fifteenth of the dimmer's; one region at the growing threshold. Split at the
  // valley, each part holds its own light; the centres' bisector cut the larger
  // disc's rim off and gave it to the smaller one.
  auto img = canvas(120, 100, 20);
  const Eigen::Vector2d a(50.4, 40.3), b(53.1, 52.5);
  add_disc(&img, a, 6.5, 3000);
  add_disc(&img, b, 5.5, 1400);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.8);
  add_noise(&img, 4, 7);
  const Eigen::Vector2d off(0.4, -0.5);
  std::vector<BlobRoi> rois = {roi(a + off, 1, 9), roi(b + off, 2, 9)};
  for (BlobRoi& r : rois) r.splits = true;
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_16U), rois, &out));
  ASSERT_TRUE(out.rois[0].detected());
  ASSERT_TRUE(out.rois[1].detected());
  const Blob& pa = out.rois[0].blob;
  const Blob& pb = out.rois[1].blob;
  ASSERT_TRUE(pa.merged && pb.merged) << "the two spots did not merge: nothing split";
  EXPECT_LT((pa.centroid - a).norm(), 0.1);
  EXPECT_LT((pb.centroid - b).norm(), 0.1);
}

TEST(BlobExtractor, RoiModeAtAndBeyondTheImageBorder) {
  auto img = canvas(100, 80, 20);
  const Eigen::Vector2d edge(97.8, 40.3);
  add_gaussian(&img, edge, 1.2, 200);
  const std::vector<BlobRoi> rois = {roi(edge, 1), roi({-50, 40}, 2), roi({50, 1e9}, 3),
                                     roi({std::nan(""), 4}, 4)};
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), rois, &out));
  ASSERT_EQ(out.rois.size(), 4u);
  EXPECT_EQ(out.rois[0].status, RoiStatus::kDetected);
  EXPECT_TRUE(out.rois[0].blob.clipped);
  EXPECT_LT((out.rois[0].position - edge).norm(), 0.05);  // circle fit: the centroid is 0.2 px off
  for (int i = 1; i < 4; ++i) EXPECT_EQ(out.rois[size_t(i)].status, RoiStatus::kOutsideImage);
}

TEST(BlobExtractor, RoiModeOnDeepNoisyDataFindsNoMarkerInNoise) {
  // 16 bits at high gain: a 26 x 26 window of read noise for a marker whose
  // on_off code is dark in this exposure. Its values spread over more levels
  // than it has pixels, one or two each, and the tallest single level stands
  // alone by chance; fitted from it, the background's sigma was 0.55 for 58 and
  // noise 55 levels above the mean grew into a "dim marker" (swarm, seed 43: a
  // three-marker pose through it 66 mm off). Over 40 noise seeds at each sigma:
  // sigma within 20 %, and nothing found.
  for (const double sigma : {58.0, 150.0, 400.0}) {
    int found = 0;
    for (uint32_t seed = 1; seed <= 40; ++seed) {
      auto img = canvas(100, 80, 2000);
      add_noise(&img, sigma, seed);
      BlobExtractor extractor;
      BlobExtraction out;
      ASSERT_TRUE(extractor.extract(quantise(img, CV_16U), std::vector<BlobRoi>{roi({50, 40}, 1, 8, 5)}, &out));
      ASSERT_EQ(out.rois.size(), 1u);
      ASSERT_FALSE(out.windows.empty());
      EXPECT_NEAR(out.windows[0].background_sigma, sigma, 0.2 * sigma) << "sigma " << sigma << ", seed " << seed;
      EXPECT_NEAR(out.windows[0].background, 2000, 0.3 * sigma) << "sigma " << sigma << ", seed " << seed;
      found += out.rois[0].detected();
    }
    EXPECT_EQ(found, 0) << "sigma " << sigma;
  }
}

TEST(BlobExtractor, RoiModeReportsBlobsNoRoiTook) {
  auto img = canvas(100, 80, 20);
  add_gaussian(&img, {40.2, 40.3}, 1.2, 200);
  add_gaussian(&img, {47.1, 40.6}, 1.2, 200);  // a newcomer inside the same window
  BlobExtractor extractor;
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_8U), std::vector<BlobRoi>{roi({40, 40}, 1, 8, 3)}, &out));
  ASSERT_TRUE(out.rois[0].detected());
  EXPECT_LT((out.rois[0].position - Eigen::Vector2d(40.2, 40.3)).norm(), 0.05);
  ASSERT_EQ(out.blobs.size(), 1u);
  EXPECT_LT((out.blobs[0].centroid - Eigen::Vector2d(47.1, 40.6)).norm(), 0.05);
}

TEST(BlobExtractor, RoiModeFindsSeedsJustAtTheThresholdAnywhereInTheWindow) {
  // A noiseless background B and a 3 x 3 plateau at B + 9: sigma is floored at
  // 1, Otsu splits at B + 0.5, so F1 = B + 8 and the plateau's pixels are the
  // lowest value that seeds. The seed search reads the 29-pixel rows of the
  // window 16 pixels at a time, the last 16 overlapping the first (8 at a time
  // where SSE2 is missing): at every column offset, the plateau reaching the
  // window's second and second-last columns, and with seeds below and above 128,
  // the plateau is found by the thresholds, not by the dim-marker recovery.
  for (const int background : {20, 150})
    for (int offset = -12; offset <= 12; ++offset) {
      cv::Mat1b img(60, 80, uint8_t(background));
      img(cv::Rect(40 + offset - 1, 29, 3, 3)).setTo(background + 9);
      BlobExtractor extractor;
      BlobExtraction out;
      ASSERT_TRUE(extractor.extract(img, std::vector<BlobRoi>{roi({40, 30}, 1, 12, 2)}, &out));
      ASSERT_TRUE(out.rois[0].detected()) << "background " << background << ", offset " << offset;
      EXPECT_EQ(out.windows[0].f1, background + 8.0);
      EXPECT_EQ(out.rois[0].blob.origin, BlobOrigin::kThreshold) << "background " << background << ", offset " << offset;
      EXPECT_LT((out.rois[0].position - Eigen::Vector2d(40 + offset, 30)).norm(), 1e-9);
    }
}

TEST(BlobExtractor, FindsSeedsJustAtTheThresholdAtEveryColumnOfAWholeImage) {
  // The whole-image seed search skips background 64 pixels at a time, then 8: a
  // plateau one grey level above F1 at every column, in rows of 150 (two full
  // 64-pixel steps and a tail), with seeds below and above 128, is found where it is.
  for (const int background : {20, 150})
    for (int x = 1; x <= 147; ++x) {
      cv::Mat1b img(20, 150, uint8_t(background));
      img(cv::Rect(x, 9, 2, 2)).setTo(background + 9);
      const auto out = extract(img, 1);
      ASSERT_EQ(out.blobs.size(), 1u) << "background " << background << ", column " << x;
      EXPECT_EQ(out.blobs[0].origin, BlobOrigin::kThreshold) << "background " << background << ", column " << x;
      EXPECT_LT((out.blobs[0].centroid - Eigen::Vector2d(x + 0.5, 9.5)).norm(), 1e-9)
          << "background " << background << ", column " << x;
    }
}

TEST(BlobExtractor, RoiModeWorksOnDarkAnd16BitImages) {
  auto img = canvas(100, 80, 40000);
  const Eigen::Vector2d c(30.4, 50.7);
  add_gaussian(&img, c, 1.5, -30000);
  add_noise(&img, 50, 4);
  BlobExtractorConfig config;
  config.polarity = MarkerPolarity::kDark;
  BlobExtractor extractor(config);
  BlobExtraction out;
  ASSERT_TRUE(extractor.extract(quantise(img, CV_16U), std::vector<BlobRoi>{roi(c, 1), roi({70, 30}, 2)}, &out));
  ASSERT_TRUE(out.rois[0].detected());
  EXPECT_LT((out.rois[0].position - c).norm(), 0.05);
  EXPECT_NEAR(out.rois[0].background, 40000, 20);
  EXPECT_EQ(out.rois[1].status, RoiStatus::kAbsent);
}

}  // namespace
}  // namespace tetrapulse

// Property tests: BlobExtractor answers every image and every ROI list,
// however odd, with a well-formed result and never crashes.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "spot_renderer.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse {
namespace {

enum class Content { kNoise, kConstant, kSaturated, kSpots, kStripes };

cv::Mat make_image(int width, int height, int type, Content content, uint32_t seed) {
  cv::Mat img(height, width, type, cv::Scalar::all(0));
  if (img.empty()) return img;
  const double top = CV_MAT_DEPTH(type) == CV_16U ? 65535.0 : 255.0;
  std::mt19937 rng(seed);
  switch (content) {
    case Content::kNoise:
      cv::randu(img, cv::Scalar::all(0), cv::Scalar::all(top + 1));
      break;
    case Content::kConstant:
      img.setTo(cv::Scalar::all(std::uniform_real_distribution<double>(0, top)(rng)));
      break;
    case Content::kSaturated:
      img.setTo(cv::Scalar::all(top));
      break;
    case Content::kSpots: {
      cv::Mat1d grey(height, width, std::uniform_real_distribution<double>(0, 0.3 * top)(rng));
      std::uniform_real_distribution<double> ux(-5, width + 5), uy(-5, height + 5), us(0.3, 6), ua(0, 1.5 * top);
      const int spots = std::uniform_int_distribution<int>(0, 12)(rng);
      for (int i = 0; i < spots; ++i) {
        if (i % 2) {
          test::add_gaussian(&grey, {ux(rng), uy(rng)}, us(rng), ua(rng));
        } else {
          test::add_disc(&grey, {ux(rng), uy(rng)}, us(rng), ua(rng));
        }
      }
      test::add_noise(&grey, 0.02 * top, seed);
      cv::Mat one = test::quantise(grey, CV_MAT_DEPTH(type));
      if (CV_MAT_CN(type) == 3) {
        cv::merge(std::vector<cv::Mat>{one, one * 0.5, one}, img);
      } else {
        img = one;
      }
      break;
    }
    case Content::kStripes:
      for (int y = 0; y < height; y += 2) img.row(y).setTo(cv::Scalar::all(top));
      break;
  }
  return img;
}

double odd_double(std::mt19937& rng, double lo, double hi) {
  const int pick = std::uniform_int_distribution<int>(0, 19)(rng);
  if (pick == 0) return std::numeric_limits<double>::quiet_NaN();
  if (pick == 1) return std::numeric_limits<double>::infinity();
  if (pick == 2) return -std::numeric_limits<double>::infinity();
  if (pick == 3) return 1e300;
  if (pick == 4) return -1e18;
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

BlobExtractorConfig make_config(std::mt19937& rng, bool colour_image) {
  BlobExtractorConfig config;
  config.polarity = rng() % 2 ? MarkerPolarity::kDark : MarkerPolarity::kLight;
  if (colour_image && rng() % 2) config.colour = ColourTarget{double(rng() % 256), double(rng() % 256), 5.0 + rng() % 60, 0};
  config.min_area = int(rng() % 6);
  config.max_area = int(rng() % 3000);
  config.min_shape_area = int(rng() % 20);
  config.f2_sigmas = 1 + rng() % 8;
  config.f1_min_sigmas = config.f2_sigmas + rng() % 8;
  config.max_erosions = int(rng() % 8);
  config.max_rejected_kept = int(rng() % 40);
  config.saturation_level = rng() % 3 ? 0.0 : double(rng() % 300);
  return config;
}

void check_blob(const Blob& b) {
  RC_ASSERT(b.centroid.allFinite());
  RC_ASSERT(std::isfinite(b.intensity));
  RC_ASSERT(std::isfinite(b.peak));
  RC_ASSERT(b.area > 0);
  RC_ASSERT(b.eccentricity >= 0.0);
  RC_ASSERT(b.eccentricity <= 1.0);
  RC_ASSERT(b.convexity > 0.0);
  RC_ASSERT(b.convexity <= 1.0);
}

// An image of any size (empty included), type and content, and the seed
// that drew it, from rapidcheck's generators.
struct Picture {
  cv::Mat image;
  uint32_t seed = 0;
  bool colour = false;
};

Picture any_picture() {
  const int width = *rc::gen::inRange(0, 64);
  const int height = *rc::gen::inRange(0, 64);
  const int type = *rc::gen::element(CV_8UC1, CV_16UC1, CV_8UC3);
  const auto content = *rc::gen::element(Content::kNoise, Content::kConstant, Content::kSaturated, Content::kSpots,
                                         Content::kStripes);
  const uint32_t seed = *rc::gen::arbitrary<uint32_t>();
  return Picture{make_image(width, height, type, content, seed), seed, type == CV_8UC3};
}

RC_GTEST_PROP(BlobExtractorProperty, WholeImageNeverFailsOnAnyPicture, ()) {
  const Picture picture = any_picture();
  const cv::Mat& img = picture.image;
  const int expected = *rc::gen::inRange(-2, 24);
  std::mt19937 rng(picture.seed);
  const BlobExtractorConfig config = make_config(rng, picture.colour);
  BlobExtractor extractor(config);
  BlobExtraction out;
  const auto ok = extractor.extract(img, expected, &out);
  if (img.empty()) {
    RC_ASSERT(!ok);
    return;
  }
  RC_ASSERT(bool(ok));
  RC_ASSERT(out.windows.size() == 1u);
  RC_ASSERT(out.rejected.size() <= size_t(std::max(config.max_rejected_kept, 0)));
  if (expected > 0) RC_ASSERT(out.blobs.size() <= size_t(expected));
  for (const Blob& b : out.blobs) check_blob(b);
  // The extractor keeps no state between calls that changes the answer.
  BlobExtraction again;
  RC_ASSERT(bool(extractor.extract(img, expected, &again)));
  RC_ASSERT(again.blobs.size() == out.blobs.size());
  for (size_t i = 0; i < out.blobs.size(); ++i) RC_ASSERT(again.blobs[i].centroid == out.blobs[i].centroid);
}

RC_GTEST_PROP(BlobExtractorProperty, RoiModeAnswersEveryRoiWhereverItLies, ()) {
  const Picture picture = any_picture();
  const cv::Mat& img = picture.image;
  const int width = img.cols, height = img.rows;
  const int count = *rc::gen::inRange(0, 20);
  std::mt19937 rng(picture.seed);
  std::vector<BlobRoi> rois(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    BlobRoi& r = rois[size_t(i)];
    r.center = {odd_double(rng, -30, width + 30), odd_double(rng, -30, height + 30)};
    r.radius = odd_double(rng, -3, 40);
    r.aperture_radius = odd_double(rng, -3, 12);
    r.tag = i;
  }
  BlobExtractor extractor(make_config(rng, picture.colour));
  BlobExtraction out;
  const auto ok = extractor.extract(img, rois, &out);
  if (img.empty()) {
    RC_ASSERT(!ok);
    return;
  }
  RC_ASSERT(bool(ok));
  RC_ASSERT(out.rois.size() == rois.size());
  for (size_t i = 0; i < rois.size(); ++i) {
    const RoiMeasurement& m = out.rois[i];
    RC_ASSERT(m.tag == int64_t(i));
    RC_ASSERT(std::isfinite(m.intensity) || m.status == RoiStatus::kOutsideImage);
    if (m.status == RoiStatus::kDetected) {
      check_blob(m.blob);
      // The blob is the ROI's: its centroid lies in the ROI's square.
      RC_ASSERT(std::abs(m.position.x() - rois[i].center.x()) <= rois[i].radius);
      RC_ASSERT(std::abs(m.position.y() - rois[i].center.y()) <= rois[i].radius);
      for (size_t j = 0; j < i; ++j)
        if (out.rois[j].status == RoiStatus::kDetected) RC_ASSERT(out.rois[j].position != m.position);
    }
    if (m.status == RoiStatus::kAbsent) RC_ASSERT(m.aperture_intensity == m.intensity);
  }
  for (const Blob& b : out.blobs) check_blob(b);
}

}  // namespace
}  // namespace tetrapulse

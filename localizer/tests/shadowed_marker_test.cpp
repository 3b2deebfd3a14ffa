// A passive marker half in shadow (issue 19; the paper: passive markers
// "sometimes affected by shadows on the bottom side"): a dark diffuse ball on a
// lit floor, lit from above the camera, whose lower half lies in a cast shadow.
// Its intensity centroid leans to the shadowed (darkest) half; the circle fit
// on its limb against the floor does not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "spot_renderer.hpp"
#include "tetrapulse/localizer/blob_extractor.hpp"

namespace tetrapulse {
namespace {

// A Lambertian sphere of image radius `radius` centred at `c` over a floor of
// `floor` grey levels: radiance albedo * max(0, n . l) + ambient, and only
// ambient where keep_lit(x, y) is false (a cast shadow). Orthographic view
// along +z; pixels integrated by 16 x 16 supersampling, then a Gaussian PSF.
cv::Mat1d shaded_ball(cv::Size size, const Eigen::Vector2d& c, double radius, double floor, double lit,
                      double ambient, const Eigen::Vector3d& to_light, bool shadow_lower_half, double psf_sigma) {
  cv::Mat1d img(size, floor);
  const Eigen::Vector3d l = to_light.normalized();
  constexpr int kSub = 16;
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      if (std::abs(x - c.x()) > radius + 1 || std::abs(y - c.y()) > radius + 1) continue;
      double sum = 0;
      for (int j = 0; j < kSub; ++j) {
        for (int i = 0; i < kSub; ++i) {
          const double px = x - 0.5 + (i + 0.5) / kSub, py = y - 0.5 + (j + 0.5) / kSub;
          const double dx = (px - c.x()) / radius, dy = (py - c.y()) / radius;
          const double rho2 = dx * dx + dy * dy;
          if (rho2 > 1) {
            sum += floor;
            continue;
          }
          const Eigen::Vector3d n(dx, dy, -std::sqrt(1 - rho2));  // facing the camera
          const bool shadowed = shadow_lower_half && py > c.y();
          sum += ambient + (shadowed ? 0.0 : lit * std::max(0.0, n.dot(l)));
        }
      }
      img(y, x) = sum / (kSub * kSub);
    }
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), psf_sigma);
  return img;
}

struct Centres {
  double centroid_error = 0;  // px: centroid without the circle fit
  double fitted_error = 0;    // px: with fit_every_circle
};

Centres measure(const cv::Mat1d& scene, const Eigen::Vector2d& truth, MarkerPolarity polarity, uint32_t seed) {
  cv::Mat1d noisy = scene.clone();
  test::add_noise(&noisy, 1.0, seed);
  const cv::Mat image = test::quantise(noisy, 8);
  Centres out;
  for (const bool fit : {false, true}) {
    BlobExtractorConfig config;
    config.polarity = polarity;
    config.fit_every_circle = fit;
    config.circle_rim_fraction = 0.25;  // what blobs_for_targets sets for painted markers
    BlobExtractor extractor(config);
    BlobExtraction blobs;
    EXPECT_TRUE(extractor.extract(image, 1, &blobs));
    EXPECT_EQ(blobs.blobs.size(), 1u);
    if (blobs.blobs.empty()) return {1e9, 1e9};
    const double e = (blobs.blobs[0].centroid - truth).norm();
    (fit ? out.fitted_error : out.centroid_error) = e;
    if (fit) {
      EXPECT_EQ(blobs.blobs[0].origin, BlobOrigin::kCircleFit);
    }
  }
  return out;
}

TEST(ShadowedMarker, DarkBallOnLitFloorHalfInShadowIsCentredOnItsLimb) {
  double worst_fit = 0, best_centroid = 1e9;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector2d truth(40.6 - 0.11 * k, 30.2 + 0.07 * k);
    // A black ball on a bright floor: its lit half shows a faint sheen, its shadowed half none.
    const cv::Mat1d scene =
        shaded_ball({80, 60}, truth, 7.5, 200, 60, 20, Eigen::Vector3d(0, -0.4, -1), true, 0.6);
    const Centres c = measure(scene, truth, MarkerPolarity::kDark, 200 + k);
    std::printf("dark ball %d: centroid off by %.3f px, circle fit off by %.3f px\n", k, c.centroid_error,
                c.fitted_error);
    worst_fit = std::max(worst_fit, c.fitted_error);
    best_centroid = std::min(best_centroid, c.centroid_error);
  }
  EXPECT_LT(worst_fit, 0.2);
  EXPECT_GT(best_centroid, 0.2);
}

}  // namespace
}  // namespace tetrapulse

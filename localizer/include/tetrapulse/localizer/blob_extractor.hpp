#pragma once
// Blob extraction (Breitenmoser, Kneip & Siegwart 2011, Sec. IV-B): markers as
// sub-pixel blob centroids, with what temporal decoding needs of each.
//
// Per window (the whole image, or a group of overlapping ROIs):
//   1. Histogram of the window. A Gaussian fitted around its mode (iterated
//      3-sigma clipping) gives the background mean mu and sigma;
//      F2 = mu + f2_sigmas * sigma and F1 = max(Otsu, mu + f1_min_sigmas * sigma).
//   2. F1 locates, F2 shapes: 8-connected regions of pixels above F2 grown from
//      every pixel above F1 (the F2-thresholded window around each F1 blob).
//   3. Rejection: too small, too large, non-convex, eccentric.
//   4. With `expected` markers (n * m): more blobs -> merge the closest pair
//      when they nearly touch, else drop the one farthest from its nearest
//      neighbour; fewer -> recovery cascade: F2 seeds (dim markers), erosion
//      (merged markers), robust circle fit (cut or shadowed markers).
//      Blobs cut by the image border are centred by the circle fit as well.
//   5. Centroid weighted by value - mu over the blob and a one-pixel ring.
// Dark markers invert the values; colour targets replace the grey values by
// each pixel's chroma along the target colour's hue (see ColourTarget).
//
// Images: CV_8UC1, CV_16UC1, or CV_8UC3 (BGR; converted to luma unless a
// colour target is set). The image is only read during a call; results go to
// a caller-owned BlobExtraction. Positions in pixels, OpenCV convention
// (integer = pixel centre); intensities in the input's grey levels (blob.hpp).
// The extractor owns reusable scratch memory: not thread-safe, one per thread.
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core/mat.hpp>
#include <tl/expected.hpp>

#include "tetrapulse/localizer/blob.hpp"

namespace tetrapulse {
namespace blob_internal {
class ExtractorScratch;
}

enum class MarkerPolarity : uint8_t {
  kLight,  // markers brighter than the background (LEDs)
  kDark,   // markers darker than the background (the paper's passive markers)
};

// Coloured markers, in OpenCV's 8-bit YCrCb (128 = no chroma). Blends of the
// marker with a grey background lie on the line from grey (128, 128) through
// the target (cr, cb): a pixel is evidence when its chroma lies within
// `radius` of that line, on the target's side, and its luma is at least
// min_luma. Its evidence is how far along the line it lies (chroma levels), so
// a pixel half covered by the marker weighs half and centroids stay unbiased;
// blob intensities are then in chroma levels x pixels. Saturated LED cores
// lose their chroma: expose so that they do not clip.
struct ColourTarget {
  double cr = 128;
  double cb = 128;
  double radius = 20;
  double min_luma = 16;
};

struct BlobExtractorConfig {
  MarkerPolarity polarity = MarkerPolarity::kLight;
  std::optional<ColourTarget> colour;  // set: the image must be 8-bit BGR; polarity is then unused

  double f2_sigmas = 4.0;             // F2 = mu + f2_sigmas * sigma
  double f1_min_sigmas = 8.0;         // F1 >= mu + f1_min_sigmas * sigma (guards Otsu on a near-empty image)
  double min_background_sigma = 1.0;  // grey levels; floor for sigma (a noiseless background has none)
  // Grey level at which the sensor clips, in the input's polarity; 0 = the
  // type's maximum (255 or 65535; for dark markers, 0 counts as clipped).
  double saturation_level = 0;

  int min_area = 3;         // pixels
  int max_area = 4000;      // pixels
  int min_shape_area = 9;   // smaller blobs skip the shape tests: too few pixels to judge
  double min_convexity = 0.8;
  double max_eccentricity = 0.8;  // axes up to 1.67 : 1

  // Over-count: the closest pair merges when their centroids are closer than
  // merge_factor * (r_a + r_b) (r = sqrt(area / pi)).
  double merge_factor = 1.5;

  bool recover_dim = true;
  bool recover_by_erosion = true;
  int max_erosions = 6;  // 4-neighbour erosions tried, one at a time
  bool recover_by_circle_fit = true;
  // Blobs touching the image border (or an ROI window's edge) get the circle
  // fit too, when their rim supports one: their centroid is biased.
  bool refit_clipped = true;
  // Every accepted blob is centred by the circle fit when its rim supports one:
  // passive markers lit from one side show a shadow-cut disc whose intensity
  // centroid leans to the lit side, while the limb (the lit boundary against
  // the background) still lies on the marker's circle.
  bool fit_every_circle = false;
  // The rim the circle fit follows: where the value crosses background +
  // this fraction of the blob's peak. Shaded balls dim towards the limb, so
  // passive markers want a lower level than LED spots (which are flat-topped).
  double circle_rim_fraction = 0.5;
  double circle_inlier_px = 0.35;  // rim points within this distance support a circle
  int circle_trials = 64;          // RANSAC triples (deterministic)

  int max_rejected_kept = 256;  // bound on BlobExtraction::rejected
};

class BlobExtractor {
 public:
  explicit BlobExtractor(BlobExtractorConfig config = {});
  ~BlobExtractor();
  BlobExtractor(BlobExtractor&&) noexcept;
  BlobExtractor& operator=(BlobExtractor&&) noexcept;

  const BlobExtractorConfig& config() const { return config_; }

  // Whole image, for (re)initialisation. `expected` = markers that should be
  // visible (n targets * m markers); 0 = unknown: no pruning, no recovery.
  // `prune` false: more blobs than expected are all kept (coded markers tell
  // clutter apart themselves); fewer still run the recovery cascade.
  // `measured`: ROIs measured in this frame (ROI mode); a blob centred in one of
  // their squares is not split to recover missing markers (that pass split what
  // merged there), which spares a tracked scene most of the recovery's cost.
  // Fills out->blobs (top to bottom), out->rejected, out->windows.
  tl::expected<void, BlobInputError> extract(const cv::Mat& image, int expected, BlobExtraction* out,
                                             bool prune = true, const std::vector<BlobRoi>& measured = {});

  // Regions of interest, while tracking. Fills out->rois (one per ROI, in
  // order), out->blobs (found but taken by no ROI), out->rejected and
  // out->windows. ROIs whose squares overlap are processed as one window and
  // share its blobs by a globally optimal assignment (least squared distance
  // from the ROI centres), so two ROIs never report the same blob. ROIs may lie
  // partly or wholly outside the image.
  tl::expected<void, BlobInputError> extract(const cv::Mat& image, const std::vector<BlobRoi>& rois,
                                             BlobExtraction* out);

 private:
  BlobExtractorConfig config_;
  std::unique_ptr<blob_internal::ExtractorScratch> scratch_;
};

}  // namespace tetrapulse

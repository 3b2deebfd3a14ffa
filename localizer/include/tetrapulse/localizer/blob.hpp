#pragma once
// What blob extraction reports (BlobExtractor) and blob tracking consumes
// (BlobTracker).
//
// Pixel coordinates follow OpenCV: x right, y down, origin at the centre of the
// top-left pixel, so integer coordinates are pixel centres (as CameraModel).
// Intensities are grey levels of the input image (0..255 or 0..65535; luma for
// colour targets) measured from the background towards the marker: a dark
// marker's intensity says how far below its background it is. "Integrated"
// intensities are sums over pixels (grey levels x pixels).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/types.hpp>

namespace tetrapulse {

// How a blob was found.
enum class BlobOrigin : uint8_t {
  kThreshold,     // grown from F1 seeds at level F2 and passed every test
  kDimRecovery,   // recovery: grown from F2 seeds (a marker dimmer than F1)
  kErosionSplit,  // recovery: one part of a merged blob split by erosion
  kCircleFit,     // recovery: centre of a circle fitted to a cut or shadowed blob's rim
  kMerged,        // two nearby blobs merged when there were more than expected
  kPredictionSplit,  // one part of a blob that held two or more predicted markers (BlobRoi::splits)
};
const char* blob_origin_name(BlobOrigin origin);

struct Blob {
  // Background-subtracted intensity-weighted centroid over the blob's pixels and
  // a one-pixel ring around them (the ring holds the spot's faint tail); for
  // kCircleFit the fitted circle's centre. Pixels.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double intensity = 0;     // sum of (value - background) over the same pixels, grey levels x pixels
  double peak = 0;          // largest (value - background) in the blob, grey levels
  double background = 0;    // background level of the blob's window, grey levels of the input image
  int area = 0;             // pixels above threshold F2
  double radius = 0;        // sqrt(area / pi), or the fitted circle's radius (kCircleFit); pixels
  double eccentricity = 0;  // sqrt(1 - lambda_min / lambda_max) of the pixels' second moments; 0 = round
  double convexity = 1;     // area / area of the convex hull of the pixel squares; 1 = convex
  cv::Rect bbox;            // pixels above F2
  bool saturated = false;   // some pixel reached the saturation level: intensity is a lower bound
  // Saturated and drawn out along the sensor's columns (major axis within 15
  // degrees of the image's y axis): a sensor's blooming, charge over the full well
  // spilling up and down the column. Such a streak is a marker (its eccentricity
  // is not held against it); its centroid stays on the spot's centre, the spill
  // being symmetric, and its length grows with the light.
  bool bloomed = false;
  bool clipped = false;     // touches the image border or the edge of the searched window
  // Its light was shared with another marker's (kPredictionSplit): the centroid
  // is biased towards the other and the intensity holds some of its light.
  bool merged = false;
  int merge_group = 0;  // merged: parts of one blob share this number (unique within a frame's extraction)
  int merge_parts = 0;  // merged: how many parts that blob was split into
  // Which of the rig's looks (RigLooks, target_appearance.hpp) found it: 0 unless
  // the rig mixes light, dark or coloured markers.
  int look = 0;
  BlobOrigin origin = BlobOrigin::kThreshold;
};

// Whether the blob's centroid is no measurement of its light's centre because the
// border of a width x height image cut it, and no circle fit centred it: its
// region lies on the border's pixels, or it is a part grown by recovery whose ring
// (the pixels around it its centroid sums) lies on them (a marker centred 7 px
// above the image imaged as a 2 x 5 px fragment on rows 1-5 whose centroid lay
// 9 px off; a pose through it was 357 mm off).
bool cut_by_border(const Blob& blob, int width, int height);

enum class RejectReason : uint8_t {
  kTooSmall,   // area < min_area
  kTooLarge,   // area > max_area
  kNonConvex,  // convexity < min_convexity
  kEccentric,  // eccentricity > max_eccentricity
  kIsolated,   // more blobs than expected: farthest from its nearest neighbour
  kMerged,     // more blobs than expected: merged into its nearest neighbour
  kFaint,      // far more blobs than expected: among the faintest, dropped before pruning
};
const char* reject_reason_name(RejectReason reason);

// A candidate that is not reported as a blob, kept for diagnostics.
struct RejectedBlob {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();  // pixels
  cv::Rect bbox;
  int area = 0;
  RejectReason reason = RejectReason::kTooSmall;
  double value = 0;        // the measure that failed: area, convexity, eccentricity or distance (px)
  bool recovered = false;  // a recovery step then reported it (split or circle fit)
};

// A region of interest for tracking: where a marker is predicted.
struct BlobRoi {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // predicted marker position, pixels
  // Half side of the square, centred on `center`, in which a blob's centroid
  // must lie to be this ROI's (the prediction's uncertainty), pixels.
  double radius = 8;
  // Radius of the disc whose intensity is measured (around the blob, or around
  // `center` when nothing is found), pixels: the marker's expected radius plus
  // a pixel or two. The window processed is the square of half side
  // radius + aperture_radius, so a blob at the square's edge is seen whole.
  double aperture_radius = 4;
  int64_t tag = -1;  // the caller's label (e.g. a track id), copied to the measurement
  // `center` is where a marker is predicted from its target's pose: a blob that
  // holds the centres of two or more such ROIs is two markers merged, and is
  // split between them (each pixel to the nearest centre, after the centres'
  // common offset from the blob is taken out); its parts are marked merged.
  bool splits = false;
};

enum class RoiStatus : uint8_t {
  kDetected,      // a blob was found: `blob` holds it
  kAbsent,        // no blob: intensity measured in the aperture around the ROI centre
  kOutsideImage,  // the ROI does not overlap the image: nothing measured
};
const char* roi_status_name(RoiStatus status);

// One ROI's answer. For temporal decoding a marker in a 0 bit is dark or dim:
// the measurement then still carries the light found where it should be.
struct RoiMeasurement {
  int64_t tag = -1;  // BlobRoi::tag
  RoiStatus status = RoiStatus::kOutsideImage;
  Blob blob;  // kDetected only
  // Blob centroid (kDetected) or the ROI centre (kAbsent, kOutsideImage); pixels.
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  // kDetected: blob.intensity. kAbsent: aperture_intensity. Grey levels x pixels.
  double intensity = 0;
  // Sum of (value - background) over the pixels whose centres lie within
  // aperture_radius of `position` (and inside the ROI's window). Unclipped, so
  // an empty aperture reads about 0 (noise may make it negative).
  double aperture_intensity = 0;
  int aperture_pixels = 0;
  double aperture_peak = 0;         // largest (value - background) in the aperture, grey levels
  bool aperture_saturated = false;  // some aperture pixel reached the saturation level
  double background = 0;            // grey levels of the input image
  double background_sigma = 0;      // grey levels

  bool detected() const { return status == RoiStatus::kDetected; }
};

// Thresholds found for one processed window (the whole image, or a group of
// overlapping ROIs), for diagnostics. Grey levels of the input image.
struct WindowThresholds {
  cv::Rect window;
  double background = 0;        // mean of the Gaussian fitted to the background histogram
  double background_sigma = 0;  // its standard deviation
  double f1 = 0;                // locating threshold (Otsu, at least background + f1_min_sigmas sigma)
  double f2 = 0;                // shape threshold (background + f2_sigmas sigma)
};

// Output of BlobExtractor. Caller-owned; each call overwrites it and reuses its
// capacity, so a caller that keeps one allocates nothing once warmed up.
struct BlobExtraction {
  // Whole image: the blobs found, top to bottom. ROI mode: blobs found in the
  // ROIs' windows that no ROI took (markers appearing, or clutter).
  std::vector<Blob> blobs;
  std::vector<RoiMeasurement> rois;  // ROI mode: one per ROI, in the ROIs' order
  std::vector<RejectedBlob> rejected;
  std::vector<WindowThresholds> windows;

  void clear() {
    blobs.clear();
    rois.clear();
    rejected.clear();
    windows.clear();
  }
};

// An input the extractor cannot work on: "image: 32-bit float images are not supported".
struct BlobInputError {
  std::string message;
};

}  // namespace tetrapulse

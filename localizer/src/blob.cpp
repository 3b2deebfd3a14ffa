#include "tetrapulse/localizer/blob.hpp"

namespace tetrapulse {

const char* blob_origin_name(BlobOrigin origin) {
  switch (origin) {
    case BlobOrigin::kThreshold: return "threshold";
    case BlobOrigin::kDimRecovery: return "dim_recovery";
    case BlobOrigin::kErosionSplit: return "erosion_split";
    case BlobOrigin::kCircleFit: return "circle_fit";
    case BlobOrigin::kMerged: return "merged";
    case BlobOrigin::kPredictionSplit: return "prediction_split";
  }
  return "?";
}

bool cut_by_border(const Blob& blob, int width, int height) {
  if (blob.origin == BlobOrigin::kCircleFit) return false;
  const cv::Rect& b = blob.bbox;
  const auto within = [&](int d) { return b.x <= d || b.y <= d || b.x + b.width >= width - d || b.y + b.height >= height - d; };
  // Its region on the border's pixels: the light beyond them is lost. A part
  // recovery grew (dim seeds, erosion) whose ring of pixels lies on them is what
  // the border left of a larger blob.
  const bool part = blob.origin == BlobOrigin::kDimRecovery || blob.origin == BlobOrigin::kErosionSplit;
  return within(0) || (part && within(1));
}

const char* reject_reason_name(RejectReason reason) {
  switch (reason) {
    case RejectReason::kTooSmall: return "too_small";
    case RejectReason::kTooLarge: return "too_large";
    case RejectReason::kNonConvex: return "non_convex";
    case RejectReason::kEccentric: return "eccentric";
    case RejectReason::kIsolated: return "isolated";
    case RejectReason::kMerged: return "merged";
    case RejectReason::kFaint: return "faint";
  }
  return "?";
}

const char* roi_status_name(RoiStatus status) {
  switch (status) {
    case RoiStatus::kDetected: return "detected";
    case RoiStatus::kAbsent: return "absent";
    case RoiStatus::kOutsideImage: return "outside_image";
  }
  return "?";
}

}  // namespace tetrapulse

#pragma once
// Four markers of one target seen as four bearings: the pose, with the markers'
// identities unknown (identification by geometry, Breitenmoser et al. 2011, Sec. IV-C)
// or known. Frames and units as in p3p.hpp: unit bearings in the OpenCV camera
// frame, target points in metres, p_C = R p_T + t.
#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "tetrapulse/localizer/camera_model.hpp"
#include "tetrapulse/localizer/p3p.hpp"

namespace tetrapulse {

using Bearing4 = std::array<Eigen::Vector3d, 4>;  // unit bearings, camera frame
using Point4 = std::array<Eigen::Vector3d, 4>;    // target points (marker centres), metres

enum class P4PRanking {
  // Each of the 24 assignments is solved as a known-order P4P (solve_p4p below) and
  // ranked by the RMS error of all four bearings. The default: at 0.3 px blob noise
  // on the paper's target at up to 4 m, a wrong best candidate never led the
  // runner-up by more than 0.62 px (p4p_test.cpp).
  kBestTriple,
  // The paper's: P3P on the three bearings furthest from coplanar for each of the 24
  // assignments; the fourth bearing's error ranks the (up to 96) poses. Noise on
  // the three is amplified in the fourth, so under noise a wrong candidate can lead
  // by many pixels.
  kCheckBearing,
};

struct P4POptions {
  P3PSolver solver = kDefaultP3PSolver;
  // When set and every bearing projects, errors are also measured in pixels (the
  // observed pixel of a bearing is its projection) and candidates are ranked by
  // them; otherwise by angle (P4PIdentification::in_pixels tells which).
  const CameraModel* camera = nullptr;
  P4PRanking ranking = P4PRanking::kBestTriple;
};

// One assignment of bearings to markers and a pose that explains it.
struct P4PHypothesis {
  Pose pose;
  std::array<int, 4> marker_of{};  // bearing i is the image of marker marker_of[i]
  // The ranking's error: RMS over the four bearings (kBestTriple) or the check
  // bearing's error (kCheckBearing); as an angle, and in pixels with a camera.
  double error_rad = 0;
  double error_px = std::numeric_limits<double>::quiet_NaN();

  double error(bool in_pixels) const { return in_pixels ? error_px : error_rad; }
};

struct P4PIdentification {
  std::vector<P4PHypothesis> candidates;  // best first
  bool in_pixels = false;                 // candidates ranked by error_px (else error_rad)

  // error(runner-up) - error(best), in the ranking's unit; infinity with fewer than
  // two candidates, NaN with none.
  double margin() const;
  // A caller accepts the best candidate only when its error is at most max_error and
  // no other candidate comes within min_margin of it.
  bool unambiguous(double max_error, double min_margin) const;
};

// Unknown correspondence: the four bearings of one target's markers in any order.
// Tries all 24 assignments (see P4PRanking); poses that put a marker behind the
// camera are dropped.
P4PIdentification identify_p4p(const Bearing4& x, const Point4& X, const P4POptions& options = {});

struct P4PSolution {
  Pose pose;
  double rms_error_rad = 0;  // over all four bearings
  double rms_error_px = std::numeric_limits<double>::quiet_NaN();  // with a camera
};

// Known correspondence (bearing i sees marker i): P3P on each of the four triples;
// the pose with the smallest RMS error over all four bearings (pixels with a camera,
// else angle). nullopt when no triple gives a pose with every marker in front, or
// none whose RMS error is within max_rms (pixels with a camera, else radians): a
// caller that rejects worse poses anyway says so and the solver skips them early.
std::optional<P4PSolution> solve_p4p(const Bearing4& x, const Point4& X, const P4POptions& options = {},
                                     double max_rms = std::numeric_limits<double>::infinity());

}  // namespace tetrapulse

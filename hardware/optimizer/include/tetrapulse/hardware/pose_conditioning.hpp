#pragma once
// How well one camera can measure a target's pose, worst case over viewing directions.
//
// A camera at distance r (m) from the markers' centroid looks at it from each direction
// v of a Fibonacci sphere (view_directions.hpp). J is the 8 x 6 Jacobian of the four
// markers' normalised image coordinates (x/z, y/z) with respect to the target's pose:
// a small rotation about its centroid (rad) and a translation in units of its RMS
// radius rho (so that both move the markers by comparable amounts). The conditioning
// of a view is kappa = sigma_max(J) / sigma_min(J): pose error per image error, worst
// direction over best. All four markers enter, as in the localizer's refinement; the
// minimal P3P triples each have a "danger cylinder" of singular camera positions that
// every sphere of views crosses, so their worst case is infinite for every target.
//
// Also reported: the share of views in which two markers' discs overlap (angular
// separation < sum of their angular radii: one hides the other, or their blobs merge),
// and the median over views of the smallest angle between two markers' lines of sight.
// The worst case of that angle says nothing: every pair of markers lines up seen from
// the two points where the line through them meets the sphere of viewpoints.
#include <vector>

#include <Eigen/Core>

#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {

struct ViewSphere {
  double distance = 1.0;  // camera to the markers' centroid (m); > 2 x the target's radius
  int views = 2000;       // directions over the whole sphere
};

struct PoseConditioning {
  double worst_kappa = 0;                                   // over all views
  Eigen::Vector3d worst_direction = Eigen::Vector3d::UnitZ();  // target frame, centroid -> camera
  double worst_kappa_above = 0;                             // over views from z >= 0 (above the support plane)
  double median_closest_rad = 0;                            // median over views of the closest pair's angle
  double overlap_fraction = 0;                              // views in which two marker discs overlap, [0, 1]
};

// kappa of one view: camera at `camera` (target frame) looking at the markers' centroid.
double view_conditioning(const Markers& markers, const Eigen::Vector3d& camera);

// Largest marker distance from the centroid (m): the view distance must exceed twice it.
double target_radius(const Markers& markers);

PoseConditioning pose_conditioning(const Markers& markers, double marker_diameter, const ViewSphere& sphere);

}  // namespace tetrapulse::hardware

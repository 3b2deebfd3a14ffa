#pragma once
// Nearly uniform unit directions on the sphere (the Fibonacci lattice: equal-area
// latitude bands, golden-angle longitudes), deterministic for a count.
#include <vector>

#include <Eigen/Core>

namespace tetrapulse::hardware {

// `count` directions over the whole sphere, or over the half z >= 0 when `upper_half`.
std::vector<Eigen::Vector3d> fibonacci_directions(int count, bool upper_half);

// Unit vector at polar angle theta from +z and azimuth phi from +x (radians).
Eigen::Vector3d direction_from_angles(double theta, double phi);

}  // namespace tetrapulse::hardware

#pragma once
// The demo's trajectory figure, after the paper's Fig. 5 (Breitenmoser et al.
// 2011): ground truth in red, measured in blue, drawn with OpenCV. Three panels:
// a top view (x, y), a side view (x, z), both with equal axes, and the position
// error over time. Positions in metres in, centimetres on the axes.
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace tetrapulse::cli {

struct TrajectoryPoint {
  double t_s = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // metres
};

struct Trajectory {
  std::string label;                   // drawn at its start (e.g. "target 3")
  std::vector<TrajectoryPoint> truth;  // in time order
  std::vector<TrajectoryPoint> measured;
  std::vector<TrajectoryPoint> error;  // p.x() = position error (m) at t_s
};

// `frame` names the frame the positions are in ("camera in target frame").
cv::Mat plot_trajectories(const std::vector<Trajectory>& trajectories, const std::string& title,
                          const std::string& frame);

}  // namespace tetrapulse::cli

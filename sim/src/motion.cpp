#include "tetrapulse/sim/motion.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "tetrapulse/sim/random.hpp"

namespace tetrapulse::sim {

Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

namespace {

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Pose interpolate(const Pose& a, const Pose& b, double s) {
  const Eigen::Quaterniond qa(a.R), qb(b.R);
  return Pose{qa.slerp(s, qb).toRotationMatrix(), (1 - s) * a.t + s * b.t};
}

Pose waypoint_pose(const WaypointMotion& m, double t) {
  const auto& p = m.points;
  if (p.size() == 1) return p.front().pose;
  const double first = p.front().t_s, last = p.back().t_s;
  if (m.loop && last > first) t = first + std::fmod(std::fmod(t - first, last - first) + (last - first), last - first);
  if (t <= first) return p.front().pose;
  if (t >= last) return p.back().pose;
  const auto it = std::upper_bound(p.begin(), p.end(), t, [](double x, const Waypoint& w) { return x < w.t_s; });
  const Waypoint& b = *it;
  const Waypoint& a = *(it - 1);
  return interpolate(a.pose, b.pose, (t - a.t_s) / (b.t_s - a.t_s));
}

Pose circle_pose(const CircleMotion& m, double t) {
  const Eigen::Vector3d n = m.axis.normalized();
  // u: any unit vector normal to n, chosen the same way every time.
  const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = (helper - n * n.dot(helper)).normalized();
  const Eigen::Vector3d v = n.cross(u);
  const double phi = m.phase_rad + 2 * M_PI * t / m.period_s;
  Pose pose;
  pose.t = m.center_m + m.radius_m * (std::cos(phi) * u + std::sin(phi) * v);
  pose.R = m.follow_tangent ? Eigen::AngleAxisd(phi, n).toRotationMatrix() * m.orientation : m.orientation;
  return pose;
}

}  // namespace

Trajectory::Trajectory(MotionSpec spec, uint64_t seed) : spec_(std::move(spec)) {
  if (const auto* m = std::get_if<SmoothRandomMotion>(&spec_)) {
    Random rng(seed);
    const double f_max = 1.0 / m->min_period_s;
    for (int c = 0; c < 6; ++c) {
      double sum = 0;
      const size_t first = harmonics_.size();
      for (int k = 0; k < kHarmonics; ++k) {
        Harmonic h{};
        h.weight = rng.uniform(0.5, 1.0);
        h.frequency_hz = rng.uniform(f_max / 8, f_max);
        h.phase_rad = rng.uniform(0, 2 * M_PI);
        sum += h.weight;
        harmonics_.push_back(h);
      }
      for (size_t k = first; k < harmonics_.size(); ++k) harmonics_[k].weight /= sum;
    }
  }
}

double Trajectory::channel(int c, double t) const {
  double s = 0;
  for (int k = 0; k < kHarmonics; ++k) {
    const Harmonic& h = harmonics_[static_cast<size_t>(c * kHarmonics + k)];
    s += h.weight * std::sin(2 * M_PI * h.frequency_hz * t + h.phase_rad);
  }
  return s;
}

Pose Trajectory::at(double t) const {
  if (const auto* m = std::get_if<StaticMotion>(&spec_)) return m->pose;
  if (const auto* m = std::get_if<WaypointMotion>(&spec_)) return waypoint_pose(*m, t);
  if (const auto* m = std::get_if<CircleMotion>(&spec_)) return circle_pose(*m, t);
  const auto& m = std::get<SmoothRandomMotion>(spec_);
  const Eigen::Vector3d s(channel(0, t), channel(1, t), channel(2, t));
  const Eigen::Vector3d r(channel(3, t), channel(4, t), channel(5, t));
  return Pose{m.centre.R * exp_so3(m.rotation_amplitude_rad.cwiseProduct(r)), m.centre.t + m.amplitude_m.cwiseProduct(s)};
}

}  // namespace tetrapulse::sim

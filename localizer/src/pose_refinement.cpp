#include "tetrapulse/localizer/pose_refinement.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <fmt/format.h>

#include "tetrapulse/localizer/sphere_image.hpp"

namespace tetrapulse {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

tl::unexpected<RefinementError> refinement_error(RefinementError::Kind kind, std::string message) {
  return tl::unexpected<RefinementError>(RefinementError{kind, std::move(message)});
}

// The measurement model and the loss, evaluated at a pose.
class ReprojectionProblem {
 public:
  ReprojectionProblem(const CameraModel& camera, const std::vector<MarkerObservation>& markers,
                      const RefinementOptions& options)
      : camera_(camera),
        markers_(markers),
        huber_(options.huber_px),
        radius_(options.sphere_centroid && options.marker_diameter_m > 0 ? options.marker_diameter_m / 2 : 0) {}

  // At `pose`: the robust cost and the plain squared error; with H and g the
  // Gauss-Newton system of the robust cost (H ~ Hessian / 2, g = gradient / 2); with
  // W the reweighted J^T W J of the covariance. Returns the index of the first marker
  // that does not project, or -1.
  int evaluate(const Pose& pose, double* cost, double* squared, Matrix6* H = nullptr, Vector6* g = nullptr,
               Matrix6* W = nullptr) const {
    *cost = *squared = 0;
    if (H) H->setZero(), g->setZero();
    if (W) W->setZero();
    for (size_t i = 0; i < markers_.size(); ++i) {
      const Eigen::Vector3d rotated = pose.R * markers_[i].position_m;
      const Eigen::Vector3d p = rotated + pose.t;
      Eigen::Vector2d h;
      Eigen::Matrix<double, 2, 3> Jp;
      if (!camera_.project(p, &h, H ? &Jp : nullptr)) return int(i);
      // The silhouette's centroid sits a fraction of a pixel from the centre's
      // projection; its change with the pose is left out of the Jacobian (1e-3 of it).
      if (radius_ > 0 && !sphere_image_centroid(camera_, p, radius_, &h)) return int(i);
      const Eigen::Vector2d r = h - markers_[i].pixel;
      const double s2 = r.squaredNorm();
      *squared += s2;
      const bool outlier = huber_ > 0 && s2 > huber_ * huber_;
      const double s = std::sqrt(s2);
      *cost += outlier ? 2 * huber_ * s - huber_ * huber_ : s2;
      if (H) {
        Eigen::Matrix<double, 2, 6> J;
        J.leftCols<3>() = -Jp * skew(rotated);  // d p / d w = -[R X]x
        J.rightCols<3>() = Jp;                  // d p / d v = I
        if (outlier) {
          // Huber's loss is linear in |r| here: gradient weight huber/|r|, and no
          // curvature along r (Triggs' correction), so only the part of J across r
          // enters H. Without it the iteration converges only linearly.
          const double w = huber_ / s;
          const Eigen::Vector2d across(-r.y() / s, r.x() / s);
          const Eigen::Matrix<double, 1, 6> Ja = across.transpose() * J;
          H->noalias() += w * Ja.transpose() * Ja;
          if (W) W->noalias() += w * J.transpose() * J;
          g->noalias() += w * J.transpose() * r;
        } else {
          H->noalias() += J.transpose() * J;
          if (W) W->noalias() += J.transpose() * J;
          g->noalias() += J.transpose() * r;
        }
      }
    }
    return -1;
  }

 private:
  const CameraModel& camera_;
  const std::vector<MarkerObservation>& markers_;
  double huber_;
  double radius_;
};

Pose step(const Pose& pose, const Vector6& delta) {
  return Pose{so3_exp(delta.head<3>()) * pose.R, pose.t + delta.tail<3>()};
}

}  // namespace

tl::expected<RefinedPose, RefinementError> refine_pose(const CameraModel& camera,
                                                       const std::vector<MarkerObservation>& markers,
                                                       const Pose& initial, const RefinementOptions& options) {
  using Kind = RefinementError::Kind;
  if (markers.size() < 3) {
    return refinement_error(Kind::kTooFewMarkers, fmt::format("{} markers given, at least 3 needed", markers.size()));
  }
  for (size_t i = 0; i < markers.size(); ++i) {
    if (!markers[i].position_m.allFinite() || !markers[i].pixel.allFinite()) {
      return refinement_error(Kind::kNotFinite, fmt::format("marker {}: position or pixel is not finite", i));
    }
  }
  if (!initial.R.allFinite() || !initial.t.allFinite()) {
    return refinement_error(Kind::kNotFinite, "initial pose is not finite");
  }

  const ReprojectionProblem problem(camera, markers, options);
  RefinedPose out;
  out.pose = initial;
  double cost, squared;
  Matrix6 H;
  Vector6 g;
  if (const int bad = problem.evaluate(out.pose, &cost, &squared, &H, &g); bad >= 0) {
    return refinement_error(Kind::kNotInView, fmt::format("marker {}: not in the camera's view at the initial pose", bad));
  }
  out.initial_rms_px = std::sqrt(squared / markers.size());

  // Levenberg-Marquardt with Marquardt's scaling (damping proportional to diag(H)).
  // Converged when the undamped Gauss-Newton step promises a negligible decrease
  // (g^T H^-1 g of the cost sum |r|^2) or the residuals are exactly zero.
  const double tiny_cost = 1e-20 * markers.size();  // (1e-10 px)^2 per marker
  auto at_minimum = [&] {
    const double decrease = g.dot(H.ldlt().solve(g));
    return cost <= tiny_cost || (std::isfinite(decrease) && decrease <= 1e-12 * cost);
  };
  double lambda = 1e-3;
  out.converged = at_minimum();
  while (!out.converged && out.iterations < options.max_iterations && lambda < 1e12) {
    ++out.iterations;
    Matrix6 A = H;
    A.diagonal() += lambda * H.diagonal().cwiseMax(1e-12 * H.diagonal().maxCoeff());
    const Vector6 delta = A.ldlt().solve(-g);
    if (!delta.allFinite()) return refinement_error(Kind::kDegenerate, "normal equations are singular");
    const Pose candidate = step(out.pose, delta);
    double new_cost, new_squared;
    if (problem.evaluate(candidate, &new_cost, &new_squared) < 0 && new_cost < cost) {
      out.pose = candidate;
      problem.evaluate(out.pose, &cost, &squared, &H, &g);
      lambda = std::max(lambda / 3, 1e-12);
      out.converged = at_minimum();
    } else {
      lambda *= 4;
    }
  }
  out.rms_px = std::sqrt(squared / markers.size());

  // Covariance sigma^2 H^-1; sigma given, or estimated with 2n - 6 degrees of freedom.
  const int dof = 2 * int(markers.size()) - 6;
  out.sigma_px = options.sigma_px > 0 ? options.sigma_px : (dof > 0 ? std::sqrt(squared / dof) : 0);
  Matrix6 W;
  problem.evaluate(out.pose, &cost, &squared, &H, &g, &W);
  const Eigen::LDLT<Matrix6> ldlt(W);
  if (out.sigma_px > 0 && ldlt.info() == Eigen::Success && ldlt.isPositive() &&
      ldlt.vectorD().minCoeff() > 1e-12 * ldlt.vectorD().maxCoeff()) {
    out.covariance = out.sigma_px * out.sigma_px * ldlt.solve(Matrix6::Identity());
    out.has_covariance = out.covariance.allFinite();
  }
  return out;
}

}  // namespace tetrapulse

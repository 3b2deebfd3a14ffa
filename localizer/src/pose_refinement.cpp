#include "tetrapulse/localizer/pose_refinement.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
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

// The measurement model and the loss, evaluated at a pose. With a known marker
// radius, h = projection of the centre + the offset of the sphere image's centroid
// from it; the offsets are held fixed while the pose is solved (they change by a
// small fraction of their 0.1-0.7 px with the pose), then recomputed until stable.
class ReprojectionProblem {
 public:
  ReprojectionProblem(const CameraModel& camera, const std::vector<MarkerObservation>& markers,
                      const RefinementOptions& options)
      : camera_(camera),
        markers_(markers),
        huber_(options.huber_px),
        radius_(options.sphere_centroid && options.marker_diameter_m > 0 ? options.marker_diameter_m / 2 : 0),
        offsets_(markers.size(), Eigen::Vector2d::Zero()),
        partner_offsets_(markers.size(), Eigen::Vector2d::Zero()) {}

  bool models_silhouettes() const { return radius_ > 0; }

  // Sets the silhouette offsets at `pose`; writes the largest change (pixels).
  // Returns the index of the first marker whose sphere does not project, or -1.
  int update_offsets(const Pose& pose, double* largest_change) {
    *largest_change = 0;
    for (size_t i = 0; i < markers_.size(); ++i) {
      if (!update_offset(pose.apply(markers_[i].position_m), &offsets_[i], largest_change)) return int(i);
      if (markers_[i].partner_share > 0 &&
          !update_offset(pose.apply(markers_[i].partner_m), &partner_offsets_[i], largest_change))
        return int(i);
    }
    return -1;
  }

  bool update_offset(const Eigen::Vector3d& p, Eigen::Vector2d* offset, double* largest_change) const {
    Eigen::Vector2d centre, centroid;
    if (!camera_.project(p, &centre) || !sphere_image_centroid(camera_, p, radius_, &centroid)) return false;
    *largest_change = std::max(*largest_change, (centroid - centre - *offset).norm());
    *offset = centroid - centre;
    return true;
  }

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
      const MarkerObservation& m = markers_[i];
      const Eigen::Vector3d rotated = pose.R * m.position_m;
      Eigen::Vector2d h;
      Eigen::Matrix<double, 2, 3> Jp;
      if (!camera_.project(rotated + pose.t, &h, H ? &Jp : nullptr)) return int(i);
      h += offsets_[i];
      Eigen::Matrix<double, 2, 6> J;
      if (H) {
        J.leftCols<3>() = -Jp * skew(rotated);  // d p / d w = -[R X]x
        J.rightCols<3>() = Jp;                  // d p / d v = I
      }
      if (m.partner_share > 0) {
        const double s = m.partner_share;
        const Eigen::Vector3d partner = pose.R * m.partner_m;
        Eigen::Vector2d h2;
        Eigen::Matrix<double, 2, 3> Jp2;
        if (!camera_.project(partner + pose.t, &h2, H ? &Jp2 : nullptr)) return int(i);
        h = (1 - s) * h + s * (h2 + partner_offsets_[i]);
        if (H) {
          Eigen::Matrix<double, 2, 6> J2;
          J2.leftCols<3>() = -Jp2 * skew(partner);
          J2.rightCols<3>() = Jp2;
          J = (1 - s) * J + s * J2;
        }
      }
      const Eigen::Vector2d r = h - m.pixel;
      const double s2 = r.squaredNorm();
      *squared += s2;
      // Loss rho(s^2): s^2, or Huber's in its smooth form 2 k^2 (sqrt(1 + s^2/k^2) - 1),
      // quadratic below k and linear above, whose curvature is continuous: with the
      // kinked form, Levenberg-Marquardt crawls when a residual sits at the kink.
      double weight = 1, radial = 0;  // rho'(s^2), and the curvature removed along r
      if (huber_ > 0) {
        const double q = 1 + s2 / (huber_ * huber_), root = std::sqrt(q);
        *cost += 2 * huber_ * huber_ * (root - 1);
        weight = 1 / root;
        radial = 1 - 1 / q;
      } else {
        *cost += s2;
      }
      if (!H) continue;
      const Matrix6 JtJ = J.transpose() * J;
      // Gauss-Newton for a robust loss (Triggs et al.): H += rho' J^T (I - radial r r^T/|r|^2) J.
      *H += weight * JtJ;
      if (radial > 0) {
        const Eigen::Matrix<double, 1, 6> Jr = r.transpose() * J;
        *H -= (weight * radial / s2) * Jr.transpose() * Jr;
      }
      *g += weight * J.transpose() * r;
      if (W) *W += weight * JtJ;
    }
    return -1;
  }

 private:
  const CameraModel& camera_;
  const std::vector<MarkerObservation>& markers_;
  double huber_;
  double radius_;
  std::vector<Eigen::Vector2d> offsets_;
  std::vector<Eigen::Vector2d> partner_offsets_;
};

// A 6 x 6 symmetric positive definite system by Cholesky, A = L L^T, in loops the
// compiler unrolls: Eigen's LLT of a fixed 6 x 6 runs its generic blocked-column
// code, and the normal equations are factored twice per Levenberg-Marquardt
// iteration (Eigen's pivoting LDLT, which the covariance took, cost as much again as
// the factorisations of a whole tracked refinement). ok() is false unless every
// pivot is positive (and finite).
class Cholesky6 {
 public:
  explicit Cholesky6(const Matrix6& A) {
    for (int j = 0; j < 6; ++j) {
      double d = A(j, j);
      for (int k = 0; k < j; ++k) d -= L_[j][k] * L_[j][k];
      if (!(d > 0) || !std::isfinite(d)) return;
      inv_diag_[j] = 1 / std::sqrt(d);
      for (int i = j + 1; i < 6; ++i) {
        double s = A(i, j);
        for (int k = 0; k < j; ++k) s -= L_[i][k] * L_[j][k];
        L_[i][j] = s * inv_diag_[j];
      }
    }
    ok_ = true;
  }
  bool ok() const { return ok_; }
  // The smallest pivot (the squared diagonal of L) over the largest: near zero, A is
  // nearly singular.
  double pivot_ratio() const {
    double least = 1 / (inv_diag_[0] * inv_diag_[0]), most = least;
    for (int j = 1; j < 6; ++j) {
      const double d = 1 / (inv_diag_[j] * inv_diag_[j]);
      least = std::min(least, d), most = std::max(most, d);
    }
    return least / most;
  }
  // A^-1 = L^-T L^-1, symmetric to the last bit (each entry and its mirror are one sum).
  Matrix6 inverse() const {
    double M[6][6] = {};  // L^-1, lower triangular, by forward substitution
    for (int c = 0; c < 6; ++c)
      for (int i = c; i < 6; ++i) {
        double s = i == c ? 1.0 : 0.0;
        for (int k = c; k < i; ++k) s -= L_[i][k] * M[k][c];
        M[i][c] = s * inv_diag_[i];
      }
    Matrix6 out;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j <= i; ++j) {
        double s = 0;
        for (int k = i; k < 6; ++k) s += M[k][i] * M[k][j];
        out(i, j) = out(j, i) = s;
      }
    return out;
  }
  // A^-1 b (forward, then back substitution).
  Vector6 solve(const Vector6& b) const {
    double y[6];
    for (int i = 0; i < 6; ++i) {
      double s = b(i);
      for (int k = 0; k < i; ++k) s -= L_[i][k] * y[k];
      y[i] = s * inv_diag_[i];
    }
    Vector6 x;
    for (int i = 5; i >= 0; --i) {
      double s = y[i];
      for (int k = i + 1; k < 6; ++k) s -= L_[k][i] * x(k);
      x(i) = s * inv_diag_[i];
    }
    return x;
  }

 private:
  double L_[6][6] = {};
  double inv_diag_[6] = {};
  bool ok_ = false;
};

Pose step(const Pose& pose, const Vector6& delta) {
  return Pose{so3_exp(delta.head<3>()) * pose.R, pose.t + delta.tail<3>()};
}

// Levenberg-Marquardt with Marquardt's scaling (damping proportional to diag(H)) from
// out->pose. Converged when the undamped Gauss-Newton step promises a negligible
// decrease (g^T H^-1 g of the cost sum |r|^2): 1e-9 of it (the step left then moves
// the residuals by 3e-5 of their norm, 3e-6 px for four markers at 0.05 px; 1e-12
// took a fifth more iterations for nothing), or below rounding; or when an accepted
// step no longer changes the cost.
// Returns false when the normal equations cannot be solved.
bool levenberg_marquardt(const ReprojectionProblem& problem, size_t markers, int max_iterations, RefinedPose* out) {
  double cost, squared;
  Matrix6 H;
  Vector6 g;
  problem.evaluate(out->pose, &cost, &squared, &H, &g);
  // Pixel coordinates carry ~1e-13 px of rounding: a decrease below (1e-10 px)^2 per
  // marker is no progress.
  const double negligible = 1e-20 * double(markers);
  auto at_minimum = [&] {
    if (cost <= negligible) return true;
    const Cholesky6 llt(H);
    if (!llt.ok()) return false;
    const double decrease = g.dot(llt.solve(g));
    return std::isfinite(decrease) && decrease <= std::max(1e-9 * cost, negligible);
  };
  double lambda = 1e-3;
  bool converged = at_minimum();
  for (int iteration = 0; !converged && iteration < max_iterations && lambda < 1e12; ++iteration) {
    ++out->iterations;
    Matrix6 A = H;
    A.diagonal() += lambda * H.diagonal().cwiseMax(1e-12 * H.diagonal().maxCoeff());
    const Cholesky6 llt(A);
    if (!llt.ok()) return false;
    const Vector6 delta = -llt.solve(g);
    if (!delta.allFinite()) return false;
    const Pose candidate = step(out->pose, delta);
    // H and g at the candidate come with its cost: most steps are taken, and a
    // taken step needs them next.
    double new_cost, new_squared;
    Matrix6 new_H;
    Vector6 new_g;
    if (problem.evaluate(candidate, &new_cost, &new_squared, &new_H, &new_g) < 0 && new_cost < cost) {
      // A step that changes the cost only in its tenth digit also ends the search:
      // near a singular H (three markers near the danger cylinder) or at a Huber
      // kink the Gauss-Newton prediction above is unreliable and steps only crawl.
      const bool stalled = cost - new_cost <= 1e-10 * cost;
      out->pose = candidate;
      cost = new_cost, squared = new_squared, H = new_H, g = new_g;
      lambda = std::max(lambda / 3, 1e-12);
      converged = stalled || at_minimum();
    } else {
      lambda *= 4;
    }
  }
  out->converged = converged;
  return true;
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

  ReprojectionProblem problem(camera, markers, options);
  RefinedPose out;
  out.pose = initial;
  double change = 0, cost, squared;
  int bad = problem.models_silhouettes() ? problem.update_offsets(out.pose, &change) : -1;
  if (bad >= 0 || (bad = problem.evaluate(out.pose, &cost, &squared)) >= 0) {
    return refinement_error(Kind::kNotInView, fmt::format("marker {}: not in the camera's view at the initial pose", bad));
  }
  out.initial_rms_px = std::sqrt(squared / markers.size());

  // Solve with the silhouette offsets fixed, recompute them at the solution, and
  // solve again while they move by more than 1e-4 px (twice from a P3P pose; a
  // change that small moves the pose by 1e-4 px of its reprojections, far below noise).
  for (int round = 0; round < 4; ++round) {
    if (!levenberg_marquardt(problem, markers.size(), options.max_iterations, &out)) {
      return refinement_error(Kind::kDegenerate, "normal equations are singular");
    }
    if (!problem.models_silhouettes()) break;
    if (problem.update_offsets(out.pose, &change) >= 0) {
      return refinement_error(Kind::kNotInView, "a marker's sphere left the camera's view during refinement");
    }
    if (change < 1e-4) break;
    out.converged = false;  // unless the next round settles
  }

  // Covariance sigma^2 (J^T W J)^-1; sigma given, or estimated with 2n - 6 degrees of freedom.
  Matrix6 H, W;
  Vector6 g;
  if (options.covariance) {
    problem.evaluate(out.pose, &cost, &squared, &H, &g, &W);
  } else {
    problem.evaluate(out.pose, &cost, &squared);
  }
  out.rms_px = std::sqrt(squared / markers.size());
  const int dof = 2 * int(markers.size()) - 6;
  out.sigma_px = options.sigma_px > 0 ? options.sigma_px : (dof > 0 ? std::sqrt(squared / dof) : 0);
  if (!options.covariance) return out;
  const Cholesky6 llt(W);
  if (out.sigma_px > 0 && llt.ok() && llt.pivot_ratio() > 1e-12) {
    out.covariance = out.sigma_px * out.sigma_px * llt.inverse();
    out.has_covariance = out.covariance.allFinite();
  }
  return out;
}

}  // namespace tetrapulse

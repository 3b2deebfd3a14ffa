#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "tetrapulse/hardware/pose_conditioning.hpp"
#include "tetrapulse/hardware/view_directions.hpp"

namespace tetrapulse::hardware {
namespace {

const Markers kPaperTarget{Eigen::Vector3d(0.0, -0.1651, 0.2366), Eigen::Vector3d(0.0, 0.1304, 0.1845),
                           Eigen::Vector3d(0.0626, -0.0221, 0.0539), Eigen::Vector3d(-0.0802, 0.0249, 0.0621)};

Markers regular(double edge) {
  const double a = edge / std::sqrt(8.0);
  return {Eigen::Vector3d(a, a, a), Eigen::Vector3d(a, -a, -a), Eigen::Vector3d(-a, a, -a),
          Eigen::Vector3d(-a, -a, a)};
}

// kappa from the definition in pose_conditioning.hpp, by central differences of the
// projections under small rotations about the centroid and translations of rho units.
double kappa_by_differences(const Markers& m, const Eigen::Vector3d& camera) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : m) c += p / 4;
  double rho2 = 0;
  for (const auto& p : m) rho2 += (p - c).squaredNorm() / 4;
  const Eigen::Vector3d z = (c - camera).normalized();
  const Eigen::Matrix3d r = Eigen::Quaterniond::FromTwoVectors(z, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto image = [&](const Eigen::Matrix<double, 6, 1>& d) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(d.head<3>().norm(), d.head<3>().normalized()).toRotationMatrix();
    Eigen::Matrix<double, 8, 1> out;
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector3d q = r * (m[i] - camera);
      const Eigen::Vector3d qc = r * (c - camera);
      q = qc + (d.head<3>().norm() > 0 ? turn : Eigen::Matrix3d::Identity()) * (q - qc) + std::sqrt(rho2) * d.tail<3>();
      out.segment<2>(2 * i) = q.head<2>() / q.z();
    }
    return out;
  };
  Eigen::Matrix<double, 8, 6> j;
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d[k] = h;
    j.col(k) = (image(d) - image(-d)) / (2 * h);
  }
  const auto s = Eigen::JacobiSVD<Eigen::Matrix<double, 8, 6>>(j).singularValues();
  return s[0] / s[5];
}

RC_GTEST_PROP(PoseConditioning, MatchesFiniteDifferencesOfTheProjection, ()) {
  const Eigen::Vector3d v =
      Eigen::Vector3d(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101));
  RC_PRE(v.norm() > 10.0);
  const double distance = *rc::gen::inRange(5, 31) * 0.1;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : kPaperTarget) c += p / 4;
  const Eigen::Vector3d camera = c + distance * v.normalized();
  const double expected = kappa_by_differences(kPaperTarget, camera);
  RC_ASSERT(std::abs(view_conditioning(kPaperTarget, camera) - expected) < 1e-4 * expected);
}

RC_GTEST_PROP(PoseConditioning, DoesNotDependOnWhereTheTargetIs, ()) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101),
                                                  *rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101));
  RC_PRE(q.norm() > 10.0);
  const Eigen::Isometry3d motion = Eigen::Translation3d(*rc::gen::inRange(-5, 6), 0.3, -2.0) * q.normalized();
  const Eigen::Vector3d camera(0.4, -0.7, 1.1);
  Markers moved;
  for (int i = 0; i < 4; ++i) moved[i] = motion * kPaperTarget[i];
  const double before = view_conditioning(kPaperTarget, camera);
  RC_ASSERT(std::abs(view_conditioning(moved, motion * camera) - before) < 1e-8 * before);
}

TEST(PoseConditioning, DegenerateTargetsAreWorseThanRegularOnes) {
  // Nearly flat: face-on, tilt and distance trade against each other.
  const Markers flat{Eigen::Vector3d(-0.1, -0.1, 0), Eigen::Vector3d(0.1, -0.1, 0), Eigen::Vector3d(0.1, 0.1, 0.001),
                     Eigen::Vector3d(-0.1, 0.1, 0)};
  // Nearly colinear: the roll about the line is all but invisible.
  const Markers colinear{Eigen::Vector3d(-0.1, 0, 0), Eigen::Vector3d(0.0, 0.0, 0), Eigen::Vector3d(0.1, 0.001, 0.0),
                         Eigen::Vector3d(0.2, 0, 0.001)};
  const ViewSphere sphere{1.0, 2000};
  const double round = pose_conditioning(regular(0.25), 0.01, sphere).worst_kappa;
  EXPECT_GT(pose_conditioning(flat, 0.01, sphere).worst_kappa, 1.3 * round);
  EXPECT_GT(pose_conditioning(colinear, 0.01, sphere).worst_kappa, 100 * round);
  // Farther away, the same image error means a larger pose error.
  EXPECT_GT(pose_conditioning(regular(0.25), 0.01, ViewSphere{3.0, 2000}).worst_kappa, 2 * round);
}

TEST(PoseConditioning, CountsOverlappingMarkerDiscs) {
  const ViewSphere sphere{1.0, 1000};
  double previous = -1;
  for (const double diameter : {0.0, 0.01, 0.03, 0.1, 0.3}) {
    const double fraction = pose_conditioning(kPaperTarget, diameter, sphere).overlap_fraction;
    EXPECT_GE(fraction, previous);  // bigger markers overlap in at least as many views
    previous = fraction;
  }
  EXPECT_EQ(pose_conditioning(kPaperTarget, 0.0, sphere).overlap_fraction, 0.0);
  EXPECT_EQ(pose_conditioning(kPaperTarget, 2.0, sphere).overlap_fraction, 1.0);  // discs wider than the target
}

TEST(PoseConditioning, ClosestPairShrinksWithDistance) {
  const double near = pose_conditioning(kPaperTarget, 0.03, ViewSphere{1.0, 2000}).median_closest_rad;
  const double far = pose_conditioning(kPaperTarget, 0.03, ViewSphere{2.0, 2000}).median_closest_rad;
  EXPECT_GT(near, 0.0);
  EXPECT_NEAR(far / near, 0.5, 0.05);  // small angles: separation ~ offset / distance
  const ViewSphere sphere{1.0, 2000};
  const PoseConditioning p = pose_conditioning(kPaperTarget, 0.03, sphere);
  EXPECT_LE(p.worst_kappa_above, p.worst_kappa);
}

TEST(ViewDirections, CoverTheSphereEvenly) {
  const auto all = fibonacci_directions(1000, false);
  const auto upper = fibonacci_directions(1000, true);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& v : all) {
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    mean += v / 1000;
  }
  EXPECT_LT(mean.norm(), 0.01);
  for (const auto& v : upper) EXPECT_GE(v.z(), 0.0);
  // Every direction has a lattice point within 0.1 rad (spacing ~ sqrt(4 pi / 1000) = 0.11).
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d probe = direction_from_angles(std::acos(1 - 2 * (i + 0.3) / 200), 2.4 * i);
    double best = M_PI;
    for (const auto& v : all) best = std::min(best, std::acos(std::clamp(v.dot(probe), -1.0, 1.0)));
    EXPECT_LT(best, 0.1);
  }
}

}  // namespace
}  // namespace tetrapulse::hardware

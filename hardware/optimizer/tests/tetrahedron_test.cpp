#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "tetrapulse/hardware/tetrahedron.hpp"

namespace tetrapulse::hardware {
namespace {

// The paper's large target (Breitenmoser et al. 2011, Sec. III-A), metres.
const Markers kPaperTarget{Eigen::Vector3d(0.0, -0.1651, 0.2366), Eigen::Vector3d(0.0, 0.1304, 0.1845),
                           Eigen::Vector3d(0.0626, -0.0221, 0.0539), Eigen::Vector3d(-0.0802, 0.0249, 0.0621)};

// Four markers with coordinates in [-0.3, 0.3] m on a 0.1 mm grid.
rc::Gen<Markers> gen_markers() {
  return rc::gen::map(rc::gen::container<std::vector<int>>(12, rc::gen::inRange(-3000, 3001)),
                      [](const std::vector<int>& c) {
                        Markers m;
                        for (int i = 0; i < 4; ++i) m[i] = Eigen::Vector3d(c[3 * i], c[3 * i + 1], c[3 * i + 2]) * 1e-4;
                        return m;
                      });
}

double point_to_plane(const Markers& m, int k) {
  std::array<int, 3> f{};
  for (int i = 0, j = 0; i < 4; ++i) {
    if (i != k) f[j++] = i;
  }
  const Eigen::Vector3d n = (m[f[1]] - m[f[0]]).cross(m[f[2]] - m[f[0]]).normalized();
  return std::abs(n.dot(m[k] - m[f[0]]));
}

double point_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (p - a).cross(b - a).norm() / (b - a).norm();
}

double smallest_extent(const Markers& m) {
  double e = INFINITY;
  for (int k = 0; k < 4; ++k) e = std::min(e, point_to_plane(m, k));
  return e;
}

RC_GTEST_PROP(FaceHeights, AreTheDistancesOfEachMarkerToTheOppositeFace, ()) {
  const Markers m = *gen_markers();
  RC_PRE(smallest_extent(m) > 0.01);  // well away from flat: the reference is then accurate
  const auto h = face_heights(edges_of(m));
  for (int k = 0; k < 4; ++k) RC_ASSERT(std::abs(h[k] - point_to_plane(m, k)) < 1e-9);
}

RC_GTEST_PROP(FaceHeights, NeverExceedAnyTriangleAltitude, ()) {
  const Markers m = *gen_markers();
  RC_PRE(smallest_extent(m) > 1e-3);
  const Edges e = edges_of(m);
  double reference = INFINITY;
  for (int i = 0; i < 4; ++i) {
    for (const auto& edge : kEdgeMarkers) {
      if (edge[0] != i && edge[1] != i) reference = std::min(reference, point_to_line(m[i], m[edge[0]], m[edge[1]]));
    }
  }
  RC_ASSERT(std::abs(min_triangle_altitude(e) - reference) < 1e-9);
  RC_ASSERT(min_face_height(e) <= min_triangle_altitude(e) + 1e-12);
}

RC_GTEST_PROP(Embed, RealisesTheEdgesItIsGiven, ()) {
  const Markers m = *gen_markers();
  RC_PRE(smallest_extent(m) > 1e-3);
  const Edges e = edges_of(m);
  const Edges back = edges_of(embed(e));
  for (int k = 0; k < 6; ++k) RC_ASSERT(std::abs(back[k] - e[k]) < 1e-9);
}

TEST(Tetrahedron, RegularOneHasHeightEdgeTimesSqrtTwoThirds) {
  const double a = 0.2;
  const Edges e{a, a, a, a, a, a};
  for (double h : face_heights(e)) EXPECT_NEAR(h, a * std::sqrt(2.0 / 3.0), 1e-12);
  EXPECT_NEAR(tetrahedron_volume(e), a * a * a / (6 * std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(volume_ratio(e), 1.0, 1e-12);
}

TEST(Tetrahedron, UnrealisableEdgesHaveNegativeHeights) {
  // Marker 0 at the centre of an equilateral triangle of side 0.3 would be 0.173 m from
  // each corner; 0.1 m cannot close the tetrahedron.
  const Edges e{0.1, 0.1, 0.1, 0.3, 0.3, 0.3};
  EXPECT_LT(tetrahedron_volume(e), 0);
  EXPECT_LT(min_face_height(e), 0);
  // Sides violating the triangle inequality give a negative area.
  EXPECT_LT(triangle_area(0.1, 0.1, 0.3), 0);
}

TEST(Tetrahedron, FlatMarkersHaveZeroHeight) {
  const Markers square{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, 0, 0), Eigen::Vector3d(0.2, 0.2, 0),
                       Eigen::Vector3d(0, 0.2, 0)};
  EXPECT_NEAR(min_face_height(edges_of(square)), 0.0, 1e-6);
  // Seen along their normal, flat markers keep every distance.
  const Edges seen = projected_edges(square, Eigen::Vector3d::UnitZ());
  const Edges real = edges_of(square);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(seen[k], real[k], 1e-15);
}

TEST(Tetrahedron, PaperTargetMeetsItsHeightConstraint) {
  // The paper's H = 12 cm holds for its target under the height defined in tetrahedron.hpp.
  const Edges e = edges_of(kPaperTarget);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(face_heights(e)[k], point_to_plane(kPaperTarget, k), 1e-12);
  EXPECT_GT(min_face_height(e), 0.12);
  EXPECT_LT(min_face_height(e), 0.13);
}

RC_GTEST_PROP(ProjectedEdges, AreTheEdgesOfTheMarkersDroppedOntoThePlane, ()) {
  const Markers m = *gen_markers();
  const Eigen::Vector3d up =
      Eigen::Vector3d(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(1, 101))
          .normalized();
  // Rotate up onto z and drop z.
  const Eigen::Matrix3d r = Eigen::Quaterniond::FromTwoVectors(up, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Edges seen = projected_edges(m, up);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d d = r * (m[kEdgeMarkers[k][0]] - m[kEdgeMarkers[k][1]]);
    RC_ASSERT(std::abs(seen[k] - d.head<2>().norm()) < 1e-12);
  }
}

}  // namespace
}  // namespace tetrapulse::hardware

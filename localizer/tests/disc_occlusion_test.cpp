// hidden_part against the area and centroid of the far disc's visible part counted
// on a fine grid: overlapping, touching, nested and apart discs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../src/disc_occlusion.hpp"

namespace tetrapulse::localizer_internal {
namespace {

// Far disc at the origin, near disc at (d, 0): the far disc's hidden area, and the
// x of the centroid of its visible part (negative: away from the near disc), by
// counting the cells of an n x n grid over the far disc.
void by_grid(double rn, double rf, double d, int n, double* hidden, double* visible_x) {
  const double cell = 2 * rf / n;
  double seen = 0, sum_x = 0, covered = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -rf + (i + 0.5) * cell, y = -rf + (j + 0.5) * cell;
      if (x * x + y * y > rf * rf) continue;
      if ((x - d) * (x - d) + y * y <= rn * rn) {
        covered += cell * cell;
      } else {
        seen += cell * cell;
        sum_x += x * cell * cell;
      }
    }
  *hidden = covered;
  *visible_x = seen > 0 ? sum_x / seen : 0;
}

TEST(DiscOcclusion, HiddenAreaAndVisibleCentroidMatchAFineGrid) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> radius(1.0, 6.0), unit(0.0, 1.0);
  int overlapping = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double rn = radius(rng), rf = radius(rng), d = unit(rng) * 1.2 * (rn + rf);
    double hidden = 0, visible_x = 0;
    by_grid(rn, rf, d, 1200, &hidden, &visible_x);
    const HiddenPart p = hidden_part(rn, rf, d);
    const double area = M_PI * rf * rf;
    EXPECT_NEAR(p.area, hidden, 2e-3 * area) << "rn " << rn << " rf " << rf << " d " << d;
    if (area - hidden > 0.02 * area) {  // enough in view for its centroid to be counted well
      EXPECT_NEAR(-p.shift, visible_x, 2e-3 * rf) << "rn " << rn << " rf " << rf << " d " << d;
    }
    overlapping += hidden > 0 && hidden < area;
  }
  EXPECT_GT(overlapping, 100);
}

TEST(DiscOcclusion, LimitCases) {
  EXPECT_EQ(hidden_part(2, 3, 5).area, 0);  // touching
  EXPECT_EQ(hidden_part(2, 3, 5).shift, 0);
  EXPECT_DOUBLE_EQ(hidden_part(4, 1, 2).area, M_PI);  // wholly hidden
  const HiddenPart nested = hidden_part(1, 3, 1);     // a near disc inside the far one
  EXPECT_DOUBLE_EQ(nested.area, M_PI);
  EXPECT_DOUBLE_EQ(nested.shift, M_PI * 1 / (M_PI * 9 - M_PI));  // the lens (the near disc) 1 px off the centre
}

}  // namespace
}  // namespace tetrapulse::localizer_internal

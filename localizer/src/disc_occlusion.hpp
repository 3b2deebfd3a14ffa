#pragma once
// Internal to Localizer: two balls' images that overlap, the nearer hiding part of
// the farther, as two uniform discs in the image (pixels).
#include <algorithm>
#include <cmath>

namespace tetrapulse::localizer_internal {

// What a nearer disc (centre cn, radius rn) hides of a farther one (centre cf,
// radius rf), d = |cf - cn|, pixels: the area of their overlap (the lens), and how
// far the centroid of what stays in view lies from cf, along cf - cn (the lens is on
// the near side, so the crescent left in view is centred away from it). The lens is
// two circular segments cut by their common chord; a segment of a circle of radius
// r cut at distance a from its centre has area r^2 acos(a / r) - a sqrt(r^2 - a^2),
// and its first moment about the chord is 2 h^3 / 3, h the half chord: the same
// for both, so the lens's centroid divides the centres' distance in the ratio of
// the segments' areas: at d a_n / (a_n + a_f) from cf.
struct HiddenPart {
  double area = 0;   // px^2
  double shift = 0;  // px
};

inline HiddenPart hidden_part(double rn, double rf, double d) {
  HiddenPart out;
  if (d >= rn + rf) return out;
  const double far_area = M_PI * rf * rf;
  if (rn >= rf + d) {  // wholly hidden: no centroid in view
    out.area = far_area;
    return out;
  }
  double lens_from_cf = 0;  // the lens's centroid, from cf towards cn
  if (rf >= rn + d) {  // the near disc wholly in front of the far one
    out.area = M_PI * rn * rn;
    lens_from_cf = d;
  } else {
    const auto segment_area = [](double r, double a) {
      return r * r * std::acos(std::clamp(a / r, -1.0, 1.0)) - a * std::sqrt(std::max(r * r - a * a, 0.0));
    };
    const double xn = (d * d + rn * rn - rf * rf) / (2 * d);  // the chord, from cn towards cf
    const double an = segment_area(rn, xn);                    // the near disc's part beyond the chord
    const double af = segment_area(rf, d - xn);                // the far disc's part before it
    out.area = an + af;
    lens_from_cf = out.area > 0 ? d * an / out.area : 0;
  }
  const double seen = far_area - out.area;
  out.shift = seen > 0 ? out.area * lens_from_cf / seen : 0;
  return out;
}

}  // namespace tetrapulse::localizer_internal

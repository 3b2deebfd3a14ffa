#include "tetrapulse/sim/coverage_patch.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse::sim {

void CoveragePatch::reset(int x0, int y0, int width, int height) {
  x0_ = x0;
  y0_ = y0;
  width_ = std::max(width, 0);
  height_ = std::max(height, 0);
  acc_.assign(static_cast<size_t>(height_) * stride(), 0.0);
}

void CoveragePatch::add_polygon(const std::vector<Eigen::Vector2d>& polygon, double weight, double scale) {
  const size_t n = polygon.size();
  if (n < 3 || width_ == 0 || height_ == 0) return;
  // Shoelace: with y down, a positive signed area means the edges leave the
  // interior on their left, where the running sum counts -dy; flip to +weight.
  double twice_area = 0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  const double k = twice_area > 0 ? -weight : weight;
  // Patch coordinates: cell x0 spans [0, 1); (u + 0.5) s - 0.5 - (x0 - 0.5) = (u + 0.5) s - x0.
  const auto cx = [&](const Eigen::Vector2d& p) { return (p.x() + 0.5) * scale - x0_; };
  const auto cy = [&](const Eigen::Vector2d& p) { return (p.y() + 0.5) * scale - y0_; };
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    add_edge(cx(a), cy(a), cx(b), cy(b), k);
  }
}

void CoveragePatch::add_edge(double ax, double ay, double bx, double by, double k) {
  if (ay == by) return;
  const double sign = by > ay ? 1.0 : -1.0;
  const double ylo = std::min(ay, by), yhi = std::max(ay, by);
  const double dxdy = (bx - ax) / (by - ay);
  if (yhi <= 0 || ylo >= height_) return;
  const int j0 = std::max(0, static_cast<int>(std::floor(ylo)));
  const int j1 = std::min(height_ - 1, static_cast<int>(std::ceil(std::min(yhi, static_cast<double>(height_)))) - 1);
  for (int j = j0; j <= j1; ++j) {
    const double y0 = std::max(ylo, static_cast<double>(j));
    const double y1 = std::min(yhi, static_cast<double>(j + 1));
    if (!(y1 > y0)) continue;
    const double xa = ax + (y0 - ay) * dxdy;
    const double xb = ax + (y1 - ay) * dxdy;
    add_row_piece(j, xa, xb, sign * (y1 - y0) * k);
  }
}

void CoveragePatch::add_row_piece(int j, double xa, double xb, double dy) {
  double* row = acc_.data() + static_cast<size_t>(j) * stride();
  const double xmin = std::min(xa, xb), xmax = std::max(xa, xb);
  // Cell i gains dy times the part of it right of the piece; cells beyond gain dy
  // (through the running sum: row[i] += dy (1 - m), row[i+1] += dy m, m = mean x - i).
  auto deposit = [&](int i, double d, double m) {
    if (i < 0) {  // left of the patch: all of it lies right of the piece
      row[0] += d;
    } else if (i < width_) {
      row[i] += d * (1 - m);
      row[i + 1] += d * m;
    }  // right of the patch: nothing of it lies right of the piece
  };
  if (xmax <= 0) {
    row[0] += dy;
    return;
  }
  if (xmin >= width_) return;
  // Cells left of the patch behave alike, and so do those right of it: clamp to -1 and width.
  const int i0 = xmin < -1 ? -1 : static_cast<int>(std::floor(xmin));
  const int i1 = xmax > width_ ? width_ : static_cast<int>(std::floor(xmax));
  if (i0 == i1 || !(xmax > xmin)) {
    deposit(i0, dy, 0.5 * (xa + xb) - i0);
    return;
  }
  const double span = xmax - xmin;
  for (int i = i0; i <= i1; ++i) {
    const double lo = (i == -1) ? xmin : std::max(xmin, static_cast<double>(i));
    const double hi = (i == width_) ? xmax : std::min(xmax, static_cast<double>(i + 1));
    if (!(hi > lo)) continue;
    deposit(i, dy * (hi - lo) / span, 0.5 * (lo + hi) - i);
  }
}

void CoveragePatch::resolve() {
  for (int j = 0; j < height_; ++j) {
    double* row = acc_.data() + static_cast<size_t>(j) * stride();
    double sum = 0;
    for (int i = 0; i < width_; ++i) {
      sum += row[i];
      row[i] = sum;
    }
  }
}

}  // namespace tetrapulse::sim

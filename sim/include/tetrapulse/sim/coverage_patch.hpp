#pragma once
// Exact area coverage of polygons on a grid of square cells. With scale s, cell
// (i, j) is the square [i - 0.5, i + 0.5) x [j - 0.5, j + 0.5) in coordinates
// (u + 0.5) s - 0.5 of OpenCV pixel coordinates u (integer u are pixel centres):
// s = 1 is the pixel grid, s = 4 a grid four times finer. A patch covers cells
// x0 .. x0 + width - 1, y0 .. y0 + height - 1 and accumulates
// sum_k weight_k * area(polygon_k ∩ cell) (area in cells: a fully covered cell adds its weight). Each edge adds its
// signed area to the cells it crosses and, through a running sum along the row,
// to every cell to its right (Green's theorem); polygons may cross the patch's
// border (the part outside is clipped exactly).
#include <vector>

#include <Eigen/Core>

namespace tetrapulse::sim {

class CoveragePatch {
 public:
  void reset(int x0, int y0, int width, int height);

  // Adds weight x covered area for a simple closed polygon (pixel coordinates, either
  // orientation) on the grid of scale `scale`.
  void add_polygon(const std::vector<Eigen::Vector2d>& polygon, double weight, double scale = 1.0);

  // Turns the accumulated edge terms into per-pixel values; call once after the last add_polygon.
  void resolve();

  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Value of cell (x0 + i, y0 + j) after resolve().
  double at(int i, int j) const { return acc_[static_cast<size_t>(j) * stride() + static_cast<size_t>(i)]; }
  const double* row(int j) const { return acc_.data() + static_cast<size_t>(j) * stride(); }
  double* row(int j) { return acc_.data() + static_cast<size_t>(j) * stride(); }

 private:
  size_t stride() const { return static_cast<size_t>(width_) + 1; }
  // Edge from (ax, ay) to (bx, by) in patch coordinates (cell (i, j) = [i, i+1) x [j, j+1)), scaled by k.
  void add_edge(double ax, double ay, double bx, double by, double k);
  // A piece of an edge inside row j: from x = xa (at its first y) to xb, signed height dy.
  void add_row_piece(int j, double xa, double xb, double dy);

  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<double> acc_;  // height rows of width + 1 (the last column takes what lies right of the patch)
};

}  // namespace tetrapulse::sim

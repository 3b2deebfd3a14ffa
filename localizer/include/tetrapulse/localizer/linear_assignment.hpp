#pragma once
// Globally optimal one-to-one assignment of rows to columns (the linear
// assignment problem):
//
//   minimise  sum_i cost(i, s(i))  over injective s: rows -> cols  (rows <= cols),
//             or over injective maps of the columns into the rows  (rows > cols).
//
// Non-finite entries (infinity, NaN) are forbidden pairs; allowed costs must be
// finite and below 1e100 in magnitude. When not every row (or column) can be
// matched, the answer first has the most allowed pairs and then the least cost. Shortest augmenting paths with dual potentials (Kuhn-Munkres,
// in the form of Jonker & Volgenant, Computing 38, 1987), O(n^2 m).
#include <limits>
#include <vector>

namespace tetrapulse {

class LinearAssignment {
 public:
  static constexpr double kForbidden = std::numeric_limits<double>::infinity();

  // `cost` is row-major, rows x cols (either may be 0). Writes row_to_col[i] =
  // assigned column of row i, or -1 when row i is left out or only has
  // forbidden pairs left. Returns the total cost of the allowed pairs. Scratch
  // memory is kept between calls: no allocation once sizes have been seen.
  double solve(const double* cost, int rows, int cols, std::vector<int>* row_to_col);

 private:
  std::vector<double> a_;  // the (possibly transposed) matrix with forbidden entries made finite
  std::vector<double> u_, v_, min_slack_;
  std::vector<int> match_, way_;
  std::vector<char> used_;
};

}  // namespace tetrapulse

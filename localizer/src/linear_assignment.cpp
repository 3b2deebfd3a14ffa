#include "tetrapulse/localizer/linear_assignment.hpp"

#include <algorithm>
#include <cmath>

namespace tetrapulse {

double LinearAssignment::solve(const double* cost, int rows, int cols, std::vector<int>* row_to_col) {
  row_to_col->assign(static_cast<size_t>(std::max(rows, 0)), -1);
  if (rows <= 0 || cols <= 0) return 0.0;

  // Work on n <= m: transpose when there are more rows than columns.
  const bool transposed = rows > cols;
  const int n = transposed ? cols : rows;
  const int m = transposed ? rows : cols;
  auto at = [&](int i, int j) { return transposed ? cost[size_t(j) * cols + i] : cost[size_t(i) * cols + j]; };

  // A forbidden pair costs more than any set of allowed ones can differ by, so
  // the optimum uses as few of them as possible; they are dropped at the end.
  double largest = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      if (std::isfinite(at(i, j))) largest = std::max(largest, std::abs(at(i, j)));
  const double forbidden = 2.0 * (largest + 1.0) * (n + 1);

  a_.resize(size_t(n) * m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) a_[size_t(i) * m + j] = std::isfinite(at(i, j)) ? at(i, j) : forbidden;

  // 1-based rows and columns; column 0 is the virtual start of each augmenting path.
  u_.assign(n + 1, 0.0);
  v_.assign(m + 1, 0.0);
  match_.assign(m + 1, 0);  // row matched to column j, 0 = free
  way_.assign(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    match_[0] = i;
    int j0 = 0;
    min_slack_.assign(m + 1, std::numeric_limits<double>::infinity());
    used_.assign(m + 1, 0);
    // Dijkstra on reduced costs until a free column is reached.
    do {
      used_[j0] = 1;
      const int i0 = match_[j0];
      double delta = std::numeric_limits<double>::infinity();
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used_[j]) continue;
        const double reduced = a_[size_t(i0 - 1) * m + (j - 1)] - u_[i0] - v_[j];
        if (reduced < min_slack_[j]) {
          min_slack_[j] = reduced;
          way_[j] = j0;
        }
        if (min_slack_[j] < delta) {
          delta = min_slack_[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used_[j]) {
          u_[match_[j]] += delta;
          v_[j] -= delta;
        } else {
          min_slack_[j] -= delta;
        }
      }
      j0 = j1;
    } while (match_[j0] != 0);
    // Flip the augmenting path.
    do {
      const int j1 = way_[j0];
      match_[j0] = match_[j1];
      j0 = j1;
    } while (j0 != 0);
  }

  double total = 0.0;
  for (int j = 1; j <= m; ++j) {
    const int i = match_[j];
    if (i == 0) continue;
    const double c = at(i - 1, j - 1);
    if (!std::isfinite(c)) continue;
    total += c;
    if (transposed) {
      (*row_to_col)[size_t(j - 1)] = i - 1;
    } else {
      (*row_to_col)[size_t(i - 1)] = j - 1;
    }
  }
  return total;
}

}  // namespace tetrapulse

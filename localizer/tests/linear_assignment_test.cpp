#include "tetrapulse/localizer/linear_assignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace tetrapulse {
namespace {

struct Best {
  int pairs = -1;       // allowed pairs
  double cost = 0;      // their total cost
};

// Every injective map of the smaller side into the larger one: the most
// allowed pairs, then the least cost.
Best brute_force(const std::vector<double>& cost, int rows, int cols) {
  const bool by_rows = rows <= cols;
  const int n = by_rows ? rows : cols, m = by_rows ? cols : rows;
  std::vector<int> perm(static_cast<size_t>(m));
  std::iota(perm.begin(), perm.end(), 0);
  Best best;
  // Permutations of m items, of which the first n are used; each injection
  // appears (m - n)! times, which costs nothing but time at m <= 8.
  do {
    Best b;
    b.pairs = 0;
    for (int i = 0; i < n; ++i) {
      const double c = by_rows ? cost[size_t(i) * cols + perm[size_t(i)]] : cost[size_t(perm[size_t(i)]) * cols + i];
      if (!std::isfinite(c)) continue;
      ++b.pairs;
      b.cost += c;
    }
    if (b.pairs > best.pairs || (b.pairs == best.pairs && b.cost < best.cost)) best = b;
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

TEST(LinearAssignment, MatchesBruteForceOnRandomMatricesUpTo8x8) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0, 100);
  std::uniform_int_distribution<int> size(1, 8);
  LinearAssignment solver;
  std::vector<int> row_to_col;
  int mismatches = 0, trials = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int rows = size(rng), cols = size(rng);
    const double forbidden_share = trial % 3 == 0 ? 0.0 : (trial % 3 == 1 ? 0.3 : 0.7);
    std::vector<double> cost(size_t(rows) * cols);
    for (double& c : cost) c = u(rng) < forbidden_share * 100 ? LinearAssignment::kForbidden : std::round(u(rng)) - 30;
    const double total = solver.solve(cost.data(), rows, cols, &row_to_col);
    const Best best = brute_force(cost, rows, cols);
    // The answer is a valid injection whose allowed pairs and cost are optimal.
    ASSERT_EQ(row_to_col.size(), size_t(rows));
    std::vector<int> used(size_t(cols), 0);
    int pairs = 0;
    double sum = 0;
    for (int r = 0; r < rows; ++r) {
      const int c = row_to_col[size_t(r)];
      if (c < 0) continue;
      ASSERT_LT(c, cols);
      ASSERT_EQ(used[size_t(c)]++, 0) << "column used twice";
      ASSERT_TRUE(std::isfinite(cost[size_t(r) * cols + c])) << "forbidden pair assigned";
      ++pairs;
      sum += cost[size_t(r) * cols + c];
    }
    ++trials;
    mismatches += pairs != best.pairs || std::abs(sum - best.cost) > 1e-9 || std::abs(total - sum) > 1e-9;
  }
  EXPECT_EQ(trials, 600);
  EXPECT_EQ(mismatches, 0);
}

TEST(LinearAssignment, PrefersTheGlobalOptimumToGreedyChoices) {
  // Greedy takes (0,0) = 1 and is left with (1,1) = 100; the optimum is 2 + 3.
  const std::vector<double> cost = {1, 2, 3, 100};
  LinearAssignment solver;
  std::vector<int> row_to_col;
  EXPECT_DOUBLE_EQ(solver.solve(cost.data(), 2, 2, &row_to_col), 5.0);
  EXPECT_EQ(row_to_col, (std::vector<int>{1, 0}));
}

TEST(LinearAssignment, HandlesEmptyAndAllForbiddenMatrices) {
  LinearAssignment solver;
  std::vector<int> row_to_col;
  EXPECT_EQ(solver.solve(nullptr, 0, 5, &row_to_col), 0.0);
  EXPECT_TRUE(row_to_col.empty());
  EXPECT_EQ(solver.solve(nullptr, 3, 0, &row_to_col), 0.0);
  EXPECT_EQ(row_to_col, (std::vector<int>{-1, -1, -1}));
  const std::vector<double> none(6, LinearAssignment::kForbidden);
  EXPECT_EQ(solver.solve(none.data(), 2, 3, &row_to_col), 0.0);
  EXPECT_EQ(row_to_col, (std::vector<int>{-1, -1}));
  const std::vector<double> nan = {std::nan(""), 4.0};
  EXPECT_EQ(solver.solve(nan.data(), 2, 1, &row_to_col), 4.0);
  EXPECT_EQ(row_to_col, (std::vector<int>{-1, 0}));
}

}  // namespace
}  // namespace tetrapulse

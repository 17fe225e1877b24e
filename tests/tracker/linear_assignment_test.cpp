// The Jonker-Volgenant solver against exhaustive search on random matrices of every shape.
#include "tracker/linear_assignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace rtmot::tracker {
namespace {

// Minimum total cost over every one-to-one assignment of min(rows, cols) pairs.
double brute_force_minimum(const std::vector<double>& cost, int rows, int cols) {
  if (rows == 0 || cols == 0) return 0.0;
  const bool by_rows = rows <= cols;
  const int small = std::min(rows, cols);
  const int large = std::max(rows, cols);
  std::vector<int> pick(large);
  std::iota(pick.begin(), pick.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  // Every permutation of the large side; its first `small` entries pair with the small side.
  do {
    double total = 0.0;
    for (int k = 0; k < small; ++k) {
      total += by_rows ? cost[k * cols + pick[k]] : cost[pick[k] * cols + k];
    }
    best = std::min(best, total);
  } while (std::next_permutation(pick.begin(), pick.end()));
  return best;
}

// Checks the solver's answer is a valid assignment of min(rows, cols) pairs; returns its cost.
double checked_total(const std::vector<int>& row_to_col, const std::vector<double>& cost, int rows,
                     int cols) {
  EXPECT_EQ(static_cast<int>(row_to_col.size()), rows);
  std::vector<int> used(cols, 0);
  int assigned = 0;
  double total = 0.0;
  for (int r = 0; r < rows; ++r) {
    const int c = row_to_col[r];
    if (c < 0) continue;
    EXPECT_LT(c, cols);
    EXPECT_EQ(used[c]++, 0) << "column " << c << " used twice";
    ++assigned;
    total += cost[r * cols + c];
  }
  EXPECT_EQ(assigned, std::min(rows, cols));
  return total;
}

TEST(LinearAssignment, MatchesBruteForceOnRandomMatrices) {
  std::mt19937 rng(12345);
  LinearAssignment solver;
  for (int trial = 0; trial < 3000; ++trial) {
    const int rows = static_cast<int>(rng() % 7);
    const int cols = static_cast<int>(rng() % 7);
    // A third of the matrices draw from few values, so ties are common.
    const bool ties = trial % 3 == 0;
    std::vector<double> cost(static_cast<std::size_t>(rows) * cols);
    for (double& c : cost) {
      c = ties ? static_cast<double>(rng() % 3) : std::uniform_real_distribution<>(-1, 1)(rng);
    }
    const auto& result = solver.solve(cost.data(), rows, cols);
    const double total = checked_total(result, cost, rows, cols);
    EXPECT_NEAR(total, brute_force_minimum(cost, rows, cols), 1e-9)
        << rows << "x" << cols << " trial " << trial;
  }
}

TEST(LinearAssignment, HandlesEmptyMatrices) {
  LinearAssignment solver;
  EXPECT_TRUE(solver.solve(nullptr, 0, 0).empty());
  EXPECT_TRUE(solver.solve(nullptr, 0, 5).empty());
  const auto& rows_only = solver.solve(nullptr, 3, 0);
  ASSERT_EQ(rows_only.size(), 3U);
  EXPECT_EQ(std::count(rows_only.begin(), rows_only.end(), -1), 3);
}

TEST(LinearAssignment, PrefersTheGlobalOptimumOverGreedy) {
  // Greedy takes (0,0)=1 and then must pay (1,1)=100; the optimum pays 2 + 3.
  const std::vector<double> cost{1.0, 2.0, 3.0, 100.0};
  LinearAssignment solver;
  const auto& result = solver.solve(cost.data(), 2, 2);
  EXPECT_EQ(result[0], 1);
  EXPECT_EQ(result[1], 0);
}

TEST(LinearAssignment, TallMatrixLeavesTheCostliestRowsOut) {
  // 3 rows, 1 column: only the cheapest row gets it.
  const std::vector<double> cost{5.0, -2.0, 4.0};
  LinearAssignment solver;
  const auto& result = solver.solve(cost.data(), 3, 1);
  EXPECT_EQ(result[0], -1);
  EXPECT_EQ(result[1], 0);
  EXPECT_EQ(result[2], -1);
}

}  // namespace
}  // namespace rtmot::tracker

#include "tracker/linear_assignment.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace rtmot::tracker {
namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}

void LinearAssignment::reserve(int rows, int cols) {
  const auto small = static_cast<std::size_t>(std::min(rows, cols));
  const auto large = static_cast<std::size_t>(std::max(rows, cols));
  transposed_.reserve(small * large);
  u_.reserve(small);
  col_for_row_.reserve(small);
  row_seen_.reserve(small);
  v_.reserve(large);
  shortest_.reserve(large);
  path_.reserve(large);
  row_for_col_.reserve(large);
  col_seen_.reserve(large);
  remaining_.reserve(large);
  result_.reserve(large);
}

// Dijkstra-like search from `row` over reduced costs for the cheapest path to a free column.
int LinearAssignment::augment(int nc, int row, double& min_value) {
  double min_val = 0.0;
  int num_remaining = nc;
  for (int it = 0; it < nc; ++it) remaining_[it] = nc - it - 1;
  std::fill(row_seen_.begin(), row_seen_.end(), 0);
  std::fill(col_seen_.begin(), col_seen_.end(), 0);
  std::fill(shortest_.begin(), shortest_.end(), kInfinity);
  int i = row;
  int sink = -1;
  while (sink == -1) {
    int index = -1;
    double lowest = kInfinity;
    row_seen_[i] = 1;
    const double* cost_row = cost_ + static_cast<std::size_t>(i) * nc;
    for (int it = 0; it < num_remaining; ++it) {
      const int j = remaining_[it];
      const double reduced = min_val + cost_row[j] - u_[i] - v_[j];
      if (reduced < shortest_[j]) {
        path_[j] = i;
        shortest_[j] = reduced;
      }
      // Among equals, prefer a free column: it ends the search sooner (scipy's rule).
      if (shortest_[j] < lowest || (shortest_[j] == lowest && row_for_col_[j] == -1)) {
        lowest = shortest_[j];
        index = it;
      }
    }
    min_val = lowest;
    if (index < 0 || min_val == kInfinity) return -1;  // only with non-finite costs
    const int j = remaining_[index];
    if (row_for_col_[j] == -1) {
      sink = j;
    } else {
      i = row_for_col_[j];
    }
    col_seen_[j] = 1;
    remaining_[index] = remaining_[--num_remaining];
  }
  min_value = min_val;
  return sink;
}

const std::vector<int>& LinearAssignment::solve(const double* cost, int rows, int cols) {
  result_.assign(static_cast<std::size_t>(std::max(rows, 0)), -1);
  if (rows <= 0 || cols <= 0) return result_;

  // The search needs at least as many columns as rows.
  const bool transpose = cols < rows;
  int nr = rows;
  int nc = cols;
  cost_ = cost;
  if (transpose) {
    transposed_.resize(static_cast<std::size_t>(rows) * cols);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        transposed_[static_cast<std::size_t>(c) * rows + r] =
            cost[static_cast<std::size_t>(r) * cols + c];
      }
    }
    cost_ = transposed_.data();
    std::swap(nr, nc);
  }

  u_.assign(nr, 0.0);
  v_.assign(nc, 0.0);
  shortest_.resize(nc);
  path_.assign(nc, -1);
  col_for_row_.assign(nr, -1);
  row_for_col_.assign(nc, -1);
  row_seen_.resize(nr);
  col_seen_.resize(nc);
  remaining_.resize(nc);

  for (int current = 0; current < nr; ++current) {
    double min_value = 0.0;
    int j = augment(nc, current, min_value);
    if (j < 0) return result_;  // infeasible: leave everything unassigned
    u_[current] += min_value;
    for (int i = 0; i < nr; ++i) {
      if (row_seen_[i] && i != current) u_[i] += min_value - shortest_[col_for_row_[i]];
    }
    for (int c = 0; c < nc; ++c) {
      if (col_seen_[c]) v_[c] -= min_value - shortest_[c];
    }
    while (true) {
      const int i = path_[j];
      row_for_col_[j] = i;
      std::swap(col_for_row_[i], j);
      if (i == current) break;
    }
  }

  if (transpose) {
    for (int c = 0; c < nr; ++c) result_[col_for_row_[c]] = c;
  } else {
    std::copy(col_for_row_.begin(), col_for_row_.end(), result_.begin());
  }
  return result_;
}

}  // namespace rtmot::tracker

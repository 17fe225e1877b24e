#pragma once
// Optimal assignment on a rectangular cost matrix: the shortest augmenting path method of
// Jonker-Volgenant in Crouse's formulation (as scipy's linear_sum_assignment, so ties fall the
// same way as in SORT's reference). Hand-written because the only packaged solvers allocate per
// call or pull in large dependencies; this one reuses its workspace and allocates nothing once
// it has seen the largest matrix.
#include <vector>

namespace rtmot::tracker {

class LinearAssignment {
 public:
  /// Minimises the total cost of a one-to-one assignment of min(rows, cols) pairs. `cost` is
  /// row-major rows x cols, every entry finite. Returns, for each row, its column or -1.
  /// The reference stays valid until the next call.
  const std::vector<int>& solve(const double* cost, int rows, int cols);

  /// Grows the workspace for matrices up to rows x cols now, so that solve() will not.
  void reserve(int rows, int cols);

 private:
  int augment(int nc, int row, double& min_value);

  std::vector<double> transposed_;
  const double* cost_{nullptr};
  std::vector<double> u_;
  std::vector<double> v_;
  std::vector<double> shortest_;
  std::vector<int> path_;
  std::vector<int> col_for_row_;
  std::vector<int> row_for_col_;
  std::vector<char> row_seen_;
  std::vector<char> col_seen_;
  std::vector<int> remaining_;
  std::vector<int> result_;
};

}  // namespace rtmot::tracker

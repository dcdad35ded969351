// Minimum-cost assignment (Hungarian algorithm, O(n^2 m)) for a rectangular cost matrix; the matching the
// Building3D metrics use (scipy's linear_sum_assignment).
#pragma once

#include <vector>

namespace lc2wf {

// cost[i][j] for rows i < n, columns j < m (all rows the same length, finite). Returns, for every row, its
// assigned column or -1: min(n, m) pairs with the smallest total cost, each row and column used at most once.
std::vector<int> min_cost_assignment(const std::vector<std::vector<double>>& cost);

}  // namespace lc2wf

#include "infer/hungarian.h"

#include <limits>
#include <stdexcept>

namespace lc2wf {
namespace {

// Rows <= columns: the potentials form (u, v) with augmenting paths from each new row.
std::vector<int> assign_rows(const std::vector<std::vector<double>>& a, int n, int m) {
  const double inf = std::numeric_limits<double>::infinity();
  // 1-based arrays; p[j] = row assigned to column j, 0 = none.
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = a[i0 - 1][j - 1] - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) u[p[j]] += delta, v[j] -= delta;
        else minv[j] -= delta;
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {  // flip the augmenting path
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> row_to_col(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j] != 0) row_to_col[p[j] - 1] = j - 1;
  return row_to_col;
}

}  // namespace

std::vector<int> min_cost_assignment(const std::vector<std::vector<double>>& cost) {
  const int n = static_cast<int>(cost.size());
  if (n == 0) return {};
  const int m = static_cast<int>(cost[0].size());
  for (const auto& row : cost)
    if (static_cast<int>(row.size()) != m) throw std::invalid_argument("min_cost_assignment: ragged cost matrix");
  if (m == 0) return std::vector<int>(n, -1);
  if (n <= m) return assign_rows(cost, n, m);
  // More rows than columns: solve the transpose and invert the assignment.
  std::vector<std::vector<double>> t(m, std::vector<double>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) t[j][i] = cost[i][j];
  const std::vector<int> col_to_row = assign_rows(t, m, n);
  std::vector<int> row_to_col(n, -1);
  for (int j = 0; j < m; ++j)
    if (col_to_row[j] >= 0) row_to_col[col_to_row[j]] = j;
  return row_to_col;
}

}  // namespace lc2wf

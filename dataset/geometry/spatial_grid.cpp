#include "dataset/geometry/spatial_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lc2wf {

SpatialGrid::SpatialGrid(const std::vector<Vec3>& points, double cell) : points_(points), cell_(cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("SpatialGrid cell must be > 0");
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  if (!points.empty()) lo = hi = points[0];
  for (const auto& p : points) {
    if (!p.allFinite()) throw std::invalid_argument("SpatialGrid: non-finite point");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  origin_ = lo;
  // Enlarge cells when the grid would be much larger than the point set (sparse points over a wide extent).
  // Cell counts stay in double until they fit an int: far-apart points or an extent that overflows must
  // neither wrap the int nor loop; halves keep hi - lo finite and give the same quotient bit for bit.
  const double cell_budget = std::max(64.0, 4.0 * static_cast<double>(points.size()));
  for (;;) {
    double cells = 1;
    Vec3 axis_cells;
    for (int k = 0; k < 3; ++k) {
      axis_cells[k] = std::floor((hi[k] / 2 - lo[k] / 2) / (cell_ / 2)) + 1;
      cells *= axis_cells[k];
    }
    if (cells <= cell_budget) {
      for (int k = 0; k < 3; ++k) dims_[k] = static_cast<int>(axis_cells[k]);
      break;
    }
    cell_ *= std::max(1.1, std::cbrt(cells / cell_budget));
  }
  const int64_t cells = int64_t{dims_[0]} * dims_[1] * dims_[2];
  std::vector<int> count(cells + 1, 0);
  std::vector<int64_t> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    keys[i] = key(cell_of(points[i]));
    ++count[keys[i] + 1];
  }
  for (int64_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  cell_start_ = count;
  items_.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) items_[count[keys[i]]++] = static_cast<int>(i);  // ascending per cell
}

Eigen::Vector3i SpatialGrid::cell_of(const Vec3& p) const {
  Eigen::Vector3i c;
  for (int k = 0; k < 3; ++k) {
    const double v = std::floor((p[k] / 2 - origin_[k] / 2) / (cell_ / 2));  // overflow-safe, as in the constructor
    c[k] = static_cast<int>(std::clamp(v, 0.0, static_cast<double>(dims_[k] - 1)));
  }
  return c;
}

int64_t SpatialGrid::key(const Eigen::Vector3i& c) const { return (int64_t{c[2]} * dims_[1] + c[1]) * dims_[0] + c[0]; }

template <bool Strict>
void SpatialGrid::query_impl(const Vec3& q, double radius, std::vector<int>& out) const {
  out.clear();
  const Eigen::Vector3i lo = cell_of(q - Vec3::Constant(radius)), hi = cell_of(q + Vec3::Constant(radius));
  const double r2 = radius * radius;
  for (int z = lo[2]; z <= hi[2]; ++z) {
    for (int y = lo[1]; y <= hi[1]; ++y) {
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const int64_t c = key({x, y, z});
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const double d2 = (points_[items_[k]] - q).squaredNorm();
          if (Strict ? d2 < r2 : d2 <= r2) out.push_back(items_[k]);
        }
      }
    }
  }
}

void SpatialGrid::count_within(const Vec3& q, double outer, double inner, int& n_outer, int& n_inner) const {
  n_outer = n_inner = 0;
  const Eigen::Vector3i lo = cell_of(q - Vec3::Constant(outer)), hi = cell_of(q + Vec3::Constant(outer));
  const double o2 = outer * outer, i2 = inner * inner;
  for (int z = lo[2]; z <= hi[2]; ++z) {
    for (int y = lo[1]; y <= hi[1]; ++y) {
      const int64_t row = key({lo[0], y, z});
      for (int k = cell_start_[row]; k < cell_start_[row + hi[0] - lo[0] + 1]; ++k) {
        const double d2 = (points_[items_[k]] - q).squaredNorm();
        n_outer += d2 <= o2;
        n_inner += d2 <= i2;
      }
    }
  }
}

void SpatialGrid::query(const Vec3& q, double radius, std::vector<int>& out) const { query_impl<false>(q, radius, out); }
void SpatialGrid::query_strict(const Vec3& q, double radius, std::vector<int>& out) const { query_impl<true>(q, radius, out); }

}  // namespace lc2wf

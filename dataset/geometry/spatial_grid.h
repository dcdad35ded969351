// Uniform grid over 3D points for radius queries (density counts, point NMS). Deterministic: results
// come back in a fixed order (cell by cell, ascending index within a cell).
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

class SpatialGrid {
 public:
  // `cell` should be about the largest query radius.
  SpatialGrid(const std::vector<Vec3>& points, double cell);
  // Indices i with |points[i] - q| <= radius.
  void query(const Vec3& q, double radius, std::vector<int>& out) const;
  // Counts of points within `outer` and within `inner` (<=, inner <= outer) without allocating.
  void count_within(const Vec3& q, double outer, double inner, int& n_outer, int& n_inner) const;
  // Same with strict < radius.
  void query_strict(const Vec3& q, double radius, std::vector<int>& out) const;

 private:
  template <bool Strict>
  void query_impl(const Vec3& q, double radius, std::vector<int>& out) const;
  Eigen::Vector3i cell_of(const Vec3& p) const;
  int64_t key(const Eigen::Vector3i& c) const;

  const std::vector<Vec3>& points_;
  double cell_;
  Vec3 origin_;
  Eigen::Vector3i dims_;
  std::vector<int> cell_start_;  // CSR over cells
  std::vector<int> items_;
};

}  // namespace lc2wf

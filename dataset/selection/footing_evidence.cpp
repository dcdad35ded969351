#include "dataset/selection/footing_evidence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/geometry/spatial_grid.h"

namespace lc2wf {

void FootingEvidenceOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("FootingEvidenceOptions." + what); };
  if (!(radius_m >= 0) || !std::isfinite(radius_m)) fail("radius_m must be a distance >= 0 in metres (0: off)");
  if (!(min_rise_m > 0) || !std::isfinite(min_rise_m)) fail("min_rise_m must be a height > 0 in metres");
  if (!(ground_band_m >= 0) || !std::isfinite(ground_band_m)) fail("ground_band_m must be a height >= 0 in metres");
  if (!std::isfinite(ground_z_m)) fail("ground_z_m must be a finite height in metres");
}

std::vector<char> footing_evidence(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                   const FootingEvidenceOptions& o) {
  o.Check();
  std::vector<char> stands(junctions.size(), 1);
  if (!o.enabled() || junctions.empty()) return stands;
  std::vector<size_t> tested;
  const double top = o.ground_z_m + o.ground_band_m;
  double lowest = top;
  for (size_t j = 0; j < junctions.size(); ++j)
    if (junctions[j].z() <= top) tested.push_back(j), lowest = std::min(lowest, junctions[j].z());
  if (tested.empty()) return stands;
  // Only ends high enough to stand over some tested junction matter; they are searched in plan (z = 0).
  std::vector<Vec3> plan;
  std::vector<double> height;
  for (const Segment3& s : segments)
    for (const Vec3& p : {s.a, s.b})
      if (p.allFinite() && p.z() >= lowest + o.min_rise_m) plan.emplace_back(p.x(), p.y(), 0.0), height.push_back(p.z());
  const SpatialGrid grid(plan, o.radius_m);
  std::vector<int> near;
  for (size_t j : tested) {
    const Vec3& v = junctions[j];
    grid.query(Vec3(v.x(), v.y(), 0.0), o.radius_m, near);
    stands[j] = std::any_of(near.begin(), near.end(),
                            [&](int k) { return height[static_cast<size_t>(k)] >= v.z() + o.min_rise_m; });
  }
  return stands;
}

}  // namespace lc2wf

#include "dataset/selection/corner_evidence.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/geometry/spatial_grid.h"

namespace lc2wf {

void CornerEvidenceOptions::Check() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("CornerEvidenceOptions." + what); };
  if (!(radius_m >= 0) || !std::isfinite(radius_m)) fail("radius_m must be a distance >= 0 in metres (0: off)");
  if (!(min_angle_deg > 0 && min_angle_deg <= 90)) fail("min_angle_deg must be in (0, 90]");
}

std::vector<char> corner_evidence(const std::vector<Vec3>& junctions, const std::vector<Segment3>& segments,
                                  const CornerEvidenceOptions& o) {
  o.Check();
  std::vector<char> shown(junctions.size(), 1);
  if (!o.enabled() || junctions.empty()) return shown;
  // Both endpoints of every segment with a direction, each knowing its segment's unit direction.
  std::vector<Vec3> ends, direction;
  for (const Segment3& s : segments) {
    const double length = s.length();
    if (!(length > 1e-9) || !std::isfinite(length)) continue;
    const Vec3 d = (s.b - s.a) / length;
    ends.push_back(s.a), ends.push_back(s.b);
    direction.push_back(d), direction.push_back(d);
  }
  const double max_cos = std::cos(o.min_angle_deg * M_PI / 180.0);
  const SpatialGrid grid(ends, o.radius_m);
  std::vector<int> near;
  for (size_t j = 0; j < junctions.size(); ++j) {
    grid.query(junctions[j], o.radius_m, near);
    // Every pair is compared, so a crowd of ends is thinned to an even spread of kMaxEndsCompared first: the
    // time stays bounded however many lines a map piles on one spot (real clouds have at most ≈ 230 there).
    if (near.size() > kMaxEndsCompared) {
      const size_t stride = (near.size() + kMaxEndsCompared - 1) / kMaxEndsCompared;
      size_t n = 0;
      for (size_t k = 0; k < near.size(); k += stride) near[n++] = near[k];
      near.resize(n);
    }
    bool turns = false;
    for (size_t a = 0; a < near.size() && !turns; ++a)
      for (size_t b = a + 1; b < near.size() && !turns; ++b)
        turns = std::abs(direction[static_cast<size_t>(near[a])].dot(direction[static_cast<size_t>(near[b])])) <= max_cos;
    shown[j] = turns;
  }
  return shown;
}

}  // namespace lc2wf

// Point non-maximum suppression over scored 3D points: junction candidates before pairing and the density
// seeds of the junction sampling. One implementation of both rules, so every caller decides the same way.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

enum class PointNmsRule {
  // Classic greedy NMS: walk points by descending score; a point survives unless a *surviving* point lies
  // within the radius.
  kGreedy,
  // The release's rule (its "suppressor" NMS): a point is also removed by a stronger neighbour that was
  // itself suppressed, so on a chain A > B > C (A–B and B–C close, A–C far) only A survives.
  kSuppressor,
};

// Indices of the surviving points in descending score order (ties: lower index first). Neighbours are
// points at distance < radius (strict); radius 0 keeps every point. Throws std::invalid_argument on
// mismatched sizes.
std::vector<int> point_nms(const std::vector<Vec3>& points, const std::vector<double>& scores, double radius,
                           PointNmsRule rule);

}  // namespace lc2wf

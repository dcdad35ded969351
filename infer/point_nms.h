// Point non-maximum suppression over scored 3D points (junction candidates, density seeds).
#pragma once

#include <vector>

#include "dataset/geometry.h"

namespace lc2wf {

enum class PointNmsRule {
  // Classic greedy NMS: walk points by descending confidence; a point survives unless a *surviving* point
  // lies within the radius.
  kGreedy,
  // The release's rule (reference spec §2.9): a point is also removed by a stronger neighbour that was
  // itself suppressed, so on a chain A > B > C (A–B and B–C close, A–C far) only A survives.
  // Implemented by the dataset layer's suppressor_nms (also used for the density seeds).
  kSuppressor,
};

// Indices of the surviving points in descending confidence order (ties: lower index first). Neighbours
// are points at distance < radius (strict).
std::vector<int> point_nms(const std::vector<Vec3>& points, const std::vector<double>& confidences, double radius,
                           PointNmsRule rule);

}  // namespace lc2wf

#include "model/edge_visibility.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <utility>

#include "model/scored_wireframe.h"

namespace lc2wf {

FootprintOccluder::FootprintOccluder(const Wireframe& w) {
  if (w.edges.empty()) return;
  Vec2 lo = w.junctions[w.edges[0][0]].head<2>(), hi = lo;
  z_lo_ = z_hi_ = w.junctions[w.edges[0][0]].z();
  for (const auto& e : w.edges)
    for (int j : e) {
      lo = lo.cwiseMin(w.junctions[j].head<2>()), hi = hi.cwiseMax(w.junctions[j].head<2>());
      z_lo_ = std::min(z_lo_, w.junctions[j].z()), z_hi_ = std::max(z_hi_, w.junctions[j].z());
    }
  // Fine enough for a notch, at most 256 cells a side whatever the building's size.
  cell_ = std::max(0.25, (hi - lo).maxCoeff() / 256.0);
  origin_ = lo - Vec2::Constant(2 * cell_);
  nx_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)) + 3;
  ny_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)) + 3;
  std::vector<uint8_t> wall(static_cast<size_t>(nx_) * ny_, 0);
  auto index = [&](const Vec2& p) {
    const int i = std::clamp(static_cast<int>((p.x() - origin_.x()) / cell_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((p.y() - origin_.y()) / cell_), 0, ny_ - 1);
    return static_cast<size_t>(j) * nx_ + i;
  };
  for (const auto& e : w.edges) {
    const Vec2 a = w.junctions[e[0]].head<2>(), b = w.junctions[e[1]].head<2>();
    const int steps = static_cast<int>(std::ceil(2.0 * (b - a).norm() / cell_)) + 1;
    for (int k = 0; k <= steps; ++k) wall[index(a + (b - a) * (static_cast<double>(k) / steps))] = 1;
  }
  // Everything the edges do not enclose is reached from the border.
  std::vector<uint8_t> outside(wall.size(), 0);
  std::deque<size_t> queue;
  for (int i = 0; i < nx_; ++i) queue.push_back(i), queue.push_back(static_cast<size_t>(ny_ - 1) * nx_ + i);
  for (int j = 0; j < ny_; ++j) queue.push_back(static_cast<size_t>(j) * nx_), queue.push_back(static_cast<size_t>(j) * nx_ + nx_ - 1);
  while (!queue.empty()) {
    const size_t c = queue.front();
    queue.pop_front();
    if (outside[c] || wall[c]) continue;
    outside[c] = 1;
    const int i = static_cast<int>(c % nx_), j = static_cast<int>(c / nx_);
    if (i > 0) queue.push_back(c - 1);
    if (i + 1 < nx_) queue.push_back(c + 1);
    if (j > 0) queue.push_back(c - nx_);
    if (j + 1 < ny_) queue.push_back(c + nx_);
  }
  // The cells the edges cross do not hide: a view along a wall, at a slant, still sees that wall's edges.
  inside_.resize(wall.size());
  for (size_t c = 0; c < wall.size(); ++c) inside_[c] = !outside[c] && !wall[c];
}

bool FootprintOccluder::inside(const Vec2& p) const {
  const double x = (p.x() - origin_.x()) / cell_, y = (p.y() - origin_.y()) / cell_;
  if (!(x >= 0 && y >= 0 && x < nx_ && y < ny_)) return false;
  return inside_[static_cast<size_t>(y) * nx_ + static_cast<size_t>(x)];
}

bool FootprintOccluder::hides(const Vec3& eye, const Vec3& point, double tolerance_m) const {
  if (inside_.empty()) return false;
  const Vec3 d = eye - point;
  const double length = d.norm();
  if (!(length > tolerance_m)) return false;
  const Vec3 u = d / length;
  // March from the point towards the eye in half cells until the path leaves the block's box.
  const double margin = (nx_ + ny_) * cell_ + (z_hi_ - z_lo_);
  for (double s = tolerance_m; s < length && s < tolerance_m + margin; s += 0.5 * cell_) {
    const Vec3 q = point + s * u;
    if (q.z() >= z_lo_ && q.z() <= z_hi_ && inside(q.head<2>())) return true;
  }
  return false;
}

int cameras_seeing(const Vec3& u, const Vec3& v, const std::vector<Camera>& cameras, const FootprintOccluder& occluder,
                   double tolerance_m) {
  int seeing = 0;
  for (const Camera& cam : cameras) {
    bool sees = true;
    for (double t : {0.25, 0.5, 0.75}) {
      const Vec3 p = u + t * (v - u);
      if (!(cam.to_camera(p).z() > 0)) { sees = false; break; }
      const Vec2 q = cam.project(p);
      if (!(q.x() >= -0.5 && q.y() >= -0.5 && q.x() <= cam.width - 0.5 && q.y() <= cam.height - 0.5) ||
          occluder.hides(cam.center(), p, tolerance_m)) {
        sees = false;
        break;
      }
    }
    seeing += sees;
  }
  return seeing;
}

Wireframe seen_part(const Wireframe& wireframe, const std::vector<Camera>& cameras, int min_cameras, double tolerance_m) {
  const FootprintOccluder occluder(wireframe);
  Wireframe seen;
  seen.junctions = wireframe.junctions;
  for (const auto& e : wireframe.edges)
    if (cameras_seeing(wireframe.junctions[e[0]], wireframe.junctions[e[1]], cameras, occluder, tolerance_m) >= min_cameras)
      seen.edges.push_back(e);
  return referenced_junctions_only(ScoredWireframe::with_unit_scores(std::move(seen))).wireframe;
}

}  // namespace lc2wf

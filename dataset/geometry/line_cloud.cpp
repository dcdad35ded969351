#include "dataset/geometry/line_cloud.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/LU>  // determinant()

#include "core/util/fnv1a.h"
#include "dataset/formats/errors.h"

namespace lc2wf {
namespace {

template <typename Derived>
bool finite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}

}  // namespace

std::vector<int> endpoint_labels(const LineCloud& cloud, double max_distance_m) {
  std::vector<int> out(2 * cloud.segments.size(), -1);
  for (size_t i = 0; i < cloud.labels.size() && i < cloud.segments.size(); ++i) {
    const auto& l = cloud.labels[i];
    if (l.d1 <= max_distance_m) out[2 * i] = l.i1;
    if (l.d2 <= max_distance_m) out[2 * i + 1] = l.i2;
  }
  return out;
}

LineCloud keep_segments(const LineCloud& cloud, const std::vector<bool>& keep) {
  if (keep.size() != cloud.segments.size())
    throw std::invalid_argument("keep_segments: " + std::to_string(keep.size()) + " flags for " +
                                std::to_string(cloud.segments.size()) + " segments");
  LineCloud out = cloud;
  out.segments.clear();
  out.labels.clear();
  out.support.clear();
  for (size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    out.segments.push_back(cloud.segments[i]);
    if (!cloud.labels.empty()) out.labels.push_back(cloud.labels[i]);
    if (!cloud.support.empty()) out.support.push_back(cloud.support[i]);
  }
  return out;
}

uint64_t segments_fingerprint(const LineCloud& cloud) {
  std::string bytes = cloud.name;
  bytes.reserve(bytes.size() + cloud.segments.size() * 6 * sizeof(double));
  for (const Segment3& s : cloud.segments)
    for (const Vec3* v : {&s.a, &s.b}) bytes.append(reinterpret_cast<const char*>(v->data()), 3 * sizeof(double));
  return fnv1a64(bytes);
}

SegmentLabel make_edge_label(const Segment3& s, const Wireframe& wf, int j, int k) {
  const Vec3& J = wf.junctions.at(j);
  const Vec3& K = wf.junctions.at(k);
  SegmentLabel l;
  l.f = true;
  const double direct = (s.a - J).norm() + (s.b - K).norm();
  const double swapped = (s.a - K).norm() + (s.b - J).norm();
  l.i1 = direct <= swapped ? j : k;
  l.i2 = direct <= swapped ? k : j;
  l.d1 = (s.a - wf.junctions[l.i1]).norm();
  l.d2 = (s.b - wf.junctions[l.i2]).norm();
  return l;
}

void validate_line_cloud(const LineCloud& c, const std::string& src) {
  const size_t n = c.segments.size();
  const int nv = static_cast<int>(c.wireframe.junctions.size());
  for (size_t i = 0; i < n; ++i) {
    const auto& s = c.segments[i];
    if (!within_coordinate_limit(s.a) || !within_coordinate_limit(s.b))
      throw DataError(src, "segment " + std::to_string(i) + " has a non-finite coordinate or one beyond +-1e9");
    if (s.length() <= 0) throw DataError(src, "segment " + std::to_string(i) + " has zero length");
  }
  for (size_t v = 0; v < c.cameras.size(); ++v) {
    const auto& cam = c.cameras[v];
    if (!finite(cam.K) || !finite(cam.R) || !finite(cam.t)) throw DataError(src, "camera " + std::to_string(v) + " has a non-finite entry");
    if (cam.width <= 0 || cam.height <= 0) throw DataError(src, "camera " + std::to_string(v) + " has no image size");
    if (!(std::abs(cam.R.determinant() - 1.0) < 1e-3)) throw DataError(src, "camera " + std::to_string(v) + " R is not a rotation");
  }
  for (size_t j = 0; j < c.wireframe.junctions.size(); ++j) {
    if (!within_coordinate_limit(c.wireframe.junctions[j]))
      throw DataError(src, "GT junction " + std::to_string(j) + " is not finite or beyond +-1e9");
  }
  for (size_t e = 0; e < c.wireframe.edges.size(); ++e) {
    const auto& ed = c.wireframe.edges[e];
    if (ed[0] < 0 || ed[1] < 0 || ed[0] >= nv || ed[1] >= nv || ed[0] == ed[1]) {
      throw DataError(src, "GT edge " + std::to_string(e) + " has junction ids out of range or repeated");
    }
  }
  if (!c.support.empty()) {
    if (c.support.size() != n) throw DataError(src, "support lists: " + std::to_string(c.support.size()) + " for " + std::to_string(n) + " segments");
    for (size_t i = 0; i < n; ++i) {
      for (const auto& o : c.support[i]) {
        if (o.view < 0 || o.view >= static_cast<int>(c.cameras.size())) {
          throw DataError(src, "segment " + std::to_string(i) + " support view " + std::to_string(o.view) + " out of range (" +
                                   std::to_string(c.cameras.size()) + " cameras)");
        }
        if (!finite(o.seg.a) || !finite(o.seg.b)) throw DataError(src, "segment " + std::to_string(i) + " has a non-finite 2D observation");
      }
    }
  }
  if (!c.labels.empty()) {
    if (c.labels.size() != n) throw DataError(src, "labels: " + std::to_string(c.labels.size()) + " for " + std::to_string(n) + " segments");
    for (size_t i = 0; i < n; ++i) {
      const auto& l = c.labels[i];
      for (int id : {l.i1, l.i2}) {
        if (id < -1 || id >= nv) throw DataError(src, "segment " + std::to_string(i) + " label junction " + std::to_string(id) + " out of range (" + std::to_string(nv) + " GT junctions)");
      }
      if (l.f && (l.i1 < 0 || l.i2 < 0)) throw DataError(src, "segment " + std::to_string(i) + " has f = 1 without two junctions");
      if (!std::isfinite(l.d1) || !std::isfinite(l.d2)) throw DataError(src, "segment " + std::to_string(i) + " has a non-finite label distance");
    }
  }
}

}  // namespace lc2wf

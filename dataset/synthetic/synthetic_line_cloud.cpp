#include "dataset/synthetic/synthetic_line_cloud.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dataset/sampling/rng.h"
#include "dataset/labels/visibility.h"

namespace lc2wf {
namespace {

Vec3 noise3(DataRng& rng, double sigma) { return sigma * Vec3(rng.normal(), rng.normal(), rng.normal()); }

// Point-in-polygon on a planar face, using the two axes the face normal is least aligned with.
bool inside_face(const PolyMesh& m, const std::vector<int>& f, const Vec3& n, const Vec3& p) {
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  bool in = false;
  for (size_t i = 0, j = f.size() - 1; i < f.size(); j = i++) {
    const Vec3& a = m.vertices[f[i]];
    const Vec3& b = m.vertices[f[j]];
    if ((a[v] > p[v]) != (b[v] > p[v]) && p[u] < (b[u] - a[u]) * (p[v] - a[v]) / (b[v] - a[v]) + a[u]) in = !in;
  }
  return in;
}

double face_area(const PolyMesh& m, const std::vector<int>& f, Vec3* normal) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < f.size(); ++k) n += m.vertices[f[k]].cross(m.vertices[f[(k + 1) % f.size()]]);
  if (normal) *normal = n.norm() > 0 ? Vec3(n.normalized()) : n;
  return 0.5 * n.norm();
}

}  // namespace

void CameraRingOptions::Check() const {
  if (num_views < 1) throw std::invalid_argument("CameraRingOptions.num_views must be >= 1");
  if (!(elevation_deg > 0 && elevation_deg < 90)) throw std::invalid_argument("CameraRingOptions.elevation_deg must be in (0, 90)");
  if (!(distance_factor > 1)) throw std::invalid_argument("CameraRingOptions.distance_factor must be > 1");
  if (width < 1 || height < 1) throw std::invalid_argument("CameraRingOptions.width/height must be >= 1");
  if (!(focal_px > 0)) throw std::invalid_argument("CameraRingOptions.focal_px must be > 0");
}

void SyntheticCloudOptions::Check() const {
  if (!(edge_pieces_per_metre > 0)) throw std::invalid_argument("SyntheticCloudOptions.edge_pieces_per_metre must be > 0");
  if (!(piece_median_m > 0)) throw std::invalid_argument("SyntheticCloudOptions.piece_median_m must be > 0");
  if (!(anchored_fraction >= 0 && anchored_fraction <= 1)) throw std::invalid_argument("SyntheticCloudOptions.anchored_fraction must be in [0, 1]");
  if (!(piece_log_sigma >= 0)) throw std::invalid_argument("SyntheticCloudOptions.piece_log_sigma must be >= 0");
  if (!(noise_m >= 0)) throw std::invalid_argument("SyntheticCloudOptions.noise_m must be >= 0");
  if (!(texture_per_roof_m2 >= 0)) throw std::invalid_argument("SyntheticCloudOptions.texture_per_roof_m2 must be >= 0");
  if (!(clutter_fraction >= 0)) throw std::invalid_argument("SyntheticCloudOptions.clutter_fraction must be >= 0");
  if (!(min_length_m > 0)) throw std::invalid_argument("SyntheticCloudOptions.min_length_m must be > 0");
  if (!(pixel_noise >= 0)) throw std::invalid_argument("SyntheticCloudOptions.pixel_noise must be >= 0");
  if (max_support_views < 0) throw std::invalid_argument("SyntheticCloudOptions.max_support_views must be >= 0");
  cameras.Check();
}

std::vector<Camera> make_camera_ring(const Building& b, const CameraRingOptions& o) {
  o.Check();
  Vec3 lo = b.mesh.vertices.at(0), hi = lo;
  for (const auto& v : b.mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double dist = o.distance_factor * 0.5 * (hi - lo).norm();
  const double el = o.elevation_deg * M_PI / 180.0;
  std::vector<Camera> cams;
  for (int i = 0; i < o.num_views; ++i) {
    const double az = 2.0 * M_PI * i / o.num_views;
    const Vec3 C = centre + dist * Vec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    const Vec3 z = (centre - C).normalized();
    const Vec3 x = z.cross(Vec3::UnitZ()).normalized();  // image x right, y down (OpenCV)
    const Vec3 y = z.cross(x);
    Camera c;
    c.R.row(0) = x.transpose();
    c.R.row(1) = y.transpose();
    c.R.row(2) = z.transpose();
    c.t = -c.R * C;
    c.K << o.focal_px, 0, 0.5 * (o.width - 1), 0, o.focal_px, 0.5 * (o.height - 1), 0, 0, 1;
    c.width = o.width;
    c.height = o.height;
    cams.push_back(c);
  }
  return cams;
}

LineCloud make_synthetic_line_cloud(const Building& b, uint64_t seed, const SyntheticCloudOptions& o) {
  o.Check();
  DataRng rng(seed);
  LineCloud c;
  c.name = b.name;
  c.units = b.units;
  c.wireframe = b.wireframe;
  c.cameras = make_camera_ring(b, o.cameras);
  const auto& J = b.wireframe.junctions;
  auto piece_length = [&] { return o.piece_median_m * std::exp(o.piece_log_sigma * rng.normal()); };

  // GT edge pieces (f = 1).
  for (const auto& e : b.wireframe.edges) {
    const Vec3 A = J[e[0]], B = J[e[1]];
    const double len = (B - A).norm();
    const int pieces = std::max(1, static_cast<int>(std::lround(len * o.edge_pieces_per_metre)));
    for (int k = 0; k < pieces; ++k) {
      const double l = std::clamp(piece_length(), o.min_length_m, len);
      const double free_t0 = rng.uniform(0.0, 1.0 - l / len);
      const double t0 = rng.uniform() < o.anchored_fraction ? (rng.uniform() < 0.5 ? 0.0 : 1.0 - l / len) : free_t0;
      Segment3 s{A + t0 * (B - A) + noise3(rng, o.noise_m), A + (t0 + l / len) * (B - A) + noise3(rng, o.noise_m)};
      if (rng.uniform() < 0.5) std::swap(s.a, s.b);
      if (s.length() < o.min_length_m) continue;
      c.segments.push_back(s);
      c.labels.push_back(make_edge_label(s, b.wireframe, e[0], e[1]));
    }
  }
  const size_t edge_pieces = c.segments.size();

  // Texture lines inside roof and wall faces (f = 0): along the slope or horizontal, like tiles/siding.
  std::vector<double> cum_area;
  std::vector<Vec3> normals(b.mesh.faces.size());
  double roof_area = 0, total = 0;
  for (size_t f = 0; f < b.mesh.faces.size(); ++f) {
    const bool usable = b.mesh.labels.empty() || b.mesh.labels[f] != FaceLabel::Base;
    const double a = usable ? face_area(b.mesh, b.mesh.faces[f], &normals[f]) : 0.0;
    if (!b.mesh.labels.empty() && b.mesh.labels[f] == FaceLabel::Roof) roof_area += a;
    total += a;
    cum_area.push_back(total);
  }
  const int textures = static_cast<int>(std::lround(o.texture_per_roof_m2 * roof_area));
  for (int k = 0, tries = 0; k < textures && tries < 50 * (textures + 1); ++tries) {
    const double pick = rng.uniform(0.0, total);
    const size_t f = std::min<size_t>(std::lower_bound(cum_area.begin(), cum_area.end(), pick) - cum_area.begin(), cum_area.size() - 1);
    const auto& face = b.mesh.faces[f];
    const Vec3& n = normals[f];
    Vec3 lo = b.mesh.vertices[face[0]], hi = lo;
    for (int id : face) {
      lo = lo.cwiseMin(b.mesh.vertices[id]);
      hi = hi.cwiseMax(b.mesh.vertices[id]);
    }
    Vec3 p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()), rng.uniform(lo.z(), hi.z()));
    p -= n * n.dot(p - b.mesh.vertices[face[0]]);  // onto the face plane
    Vec3 horiz = n.cross(Vec3::UnitZ());
    if (horiz.norm() < 1e-6) horiz = Vec3::UnitX();
    horiz.normalize();
    const Vec3 dir = rng.uniform() < 0.5 ? horiz : Vec3(n.cross(horiz).normalized());
    const double l = std::max(o.min_length_m, 0.7 * piece_length());
    const Segment3 s{p - 0.5 * l * dir + noise3(rng, o.noise_m), p + 0.5 * l * dir + noise3(rng, o.noise_m)};
    // Keep texture strictly inside the face, away from the GT edges it would otherwise imitate.
    const double margin = 0.3;
    if (!inside_face(b.mesh, face, n, s.a - margin * dir) || !inside_face(b.mesh, face, n, s.b + margin * dir)) continue;
    bool near_edge = false;
    for (const auto& e : b.wireframe.edges) {
      const Vec3 A = J[e[0]], u = (J[e[1]] - A).normalized();
      if (u.cross(s.a - A).norm() < margin && u.cross(s.b - A).norm() < margin) near_edge = true;
    }
    if (near_edge) continue;
    c.segments.push_back(s);
    c.labels.push_back({});
    ++k;
  }

  // Clutter around the building (f = 0).
  Vec3 lo = J.at(0), hi = lo;
  for (const auto& v : J) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const int clutter = static_cast<int>(std::lround(o.clutter_fraction * static_cast<double>(edge_pieces)));
  for (int k = 0; k < clutter; ++k) {
    const Vec3 p(rng.uniform(lo.x() - 2, hi.x() + 2), rng.uniform(lo.y() - 2, hi.y() + 2), rng.uniform(0.0, hi.z() + 1));
    const Vec3 dir = Vec3(rng.normal(), rng.normal(), rng.normal()).normalized();
    const double l = std::max(o.min_length_m, piece_length());
    c.segments.push_back({p - 0.5 * l * dir, p + 0.5 * l * dir});
    c.labels.push_back({});
  }

  // 2D support: views that see the segment's midpoint unoccluded with both endpoints in the image.
  const MeshOccluder occ(b.mesh);
  c.support.resize(c.segments.size());
  for (size_t i = 0; i < c.segments.size(); ++i) {
    const auto& s = c.segments[i];
    std::vector<Observation> seen;
    for (size_t v = 0; v < c.cameras.size(); ++v) {
      const Camera& cam = c.cameras[v];
      if (cam.to_camera(s.a).z() <= 0 || cam.to_camera(s.b).z() <= 0) continue;
      if (occ.occluded(cam.center(), 0.5 * (s.a + s.b), 0.05)) continue;
      Segment2 p{cam.project(s.a), cam.project(s.b)};
      p.a += o.pixel_noise * Vec2(rng.normal(), rng.normal());
      p.b += o.pixel_noise * Vec2(rng.normal(), rng.normal());
      auto in_image = [&](const Vec2& q) { return q.x() >= 0 && q.y() >= 0 && q.x() <= cam.width - 1 && q.y() <= cam.height - 1; };
      if (!in_image(p.a) || !in_image(p.b)) continue;
      seen.push_back({static_cast<int>(v), p});
    }
    // Deterministic subset: evenly spread over the views that see it.
    if (static_cast<int>(seen.size()) > o.max_support_views) {
      std::vector<Observation> kept;
      for (int k = 0; k < o.max_support_views; ++k) kept.push_back(seen[k * seen.size() / o.max_support_views]);
      seen = std::move(kept);
    }
    c.support[i] = std::move(seen);
  }
  return c;
}

}  // namespace lc2wf

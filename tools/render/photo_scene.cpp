#include "tools/render/photo_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dataset/sampling/rng.h"
#include "tools/render/face_frames.h"
#include "tools/render/value_noise.h"

namespace lc2wf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A box turned by `yaw` about z: footprint centre, half sizes along its own axes, z range.
struct OrientedBox {
  Vec2 centre = Vec2::Zero();
  double yaw = 0;
  Vec2 half = Vec2::Zero();
  double z0 = 0, z1 = 0;

  Vec3 local(const Vec3& p) const {
    const Vec2 d = p.head<2>() - centre;
    const double c = std::cos(yaw), s = std::sin(yaw);
    return Vec3(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), p.z());
  }
  bool contains(const Vec3& p, double margin) const {
    const Vec3 q = local(p);
    return std::abs(q.x()) <= half.x() + margin && std::abs(q.y()) <= half.y() + margin && q.z() >= z0 - margin && q.z() <= z1 + margin;
  }
  // Slab test of the segment a-b against the box.
  bool hits_segment(const Vec3& a, const Vec3& b) const {
    const Vec3 p = local(a), d = local(b) - p;
    const double lo[3] = {-half.x(), -half.y(), z0}, hi[3] = {half.x(), half.y(), z1};
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-12) {
        if (p[k] < lo[k] || p[k] > hi[k]) return false;
        continue;
      }
      double ta = (lo[k] - p[k]) / d[k], tb = (hi[k] - p[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
      if (t0 > t1) return false;
    }
    return true;
  }
  std::array<Vec3, 8> corners() const {
    std::array<Vec3, 8> out;
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (int i = 0; i < 8; ++i) {
      const double x = (i & 1 ? 1 : -1) * half.x(), y = (i & 2 ? 1 : -1) * half.y();
      out[i] = Vec3(centre.x() + c * x - s * y, centre.y() + s * x + c * y, i & 4 ? z1 : z0);
    }
    return out;
  }
};

class SceneBuilder {
 public:
  SceneBuilder(PhotoScene& scene, const std::vector<Vec3>& cameras) : scene_(scene), cameras_(cameras) {}

  bool clear_of_cameras(const OrientedBox& b, double margin) const {
    for (const Vec3& c : cameras_)
      if (b.contains(c, margin)) return false;
    return true;
  }
  bool hides(const OrientedBox& b, const Vec3& target) const {
    for (const Vec3& c : cameras_)
      if (b.hits_segment(c, target)) return true;
    return false;
  }
  void add_face(std::vector<Vec3> pts, ClutterKind kind) {
    std::vector<int> face;
    for (const Vec3& p : pts) {
      face.push_back(static_cast<int>(scene_.clutter.vertices.size()));
      scene_.clutter.vertices.push_back(p);
    }
    scene_.clutter.faces.push_back(std::move(face));
    scene_.kinds.push_back(kind);
    scene_.objects.push_back(object_);
  }
  // Eight corners in the order of OrientedBox::corners (bit 0: +x, bit 1: +y, bit 2: top).
  void add_box(const std::array<Vec3, 8>& c, ClutterKind sides, ClutterKind top) {
    ++object_;
    add_face({c[0], c[1], c[3], c[2]}, sides);
    add_face({c[4], c[5], c[7], c[6]}, top);
    add_face({c[0], c[1], c[5], c[4]}, sides);
    add_face({c[2], c[3], c[7], c[6]}, sides);
    add_face({c[0], c[2], c[6], c[4]}, sides);
    add_face({c[1], c[3], c[7], c[5]}, sides);
  }
  void add_cone(const Vec2& at, double z0, double z1, double radius, int sides, ClutterKind kind) {
    ++object_;
    std::vector<Vec3> ring;
    for (int k = 0; k < sides; ++k)
      ring.emplace_back(at.x() + radius * std::cos(2 * kPi * k / sides), at.y() + radius * std::sin(2 * kPi * k / sides), z0);
    for (int k = 0; k < sides; ++k) add_face({ring[k], ring[(k + 1) % sides], Vec3(at.x(), at.y(), z1)}, kind);
    add_face(ring, kind);
  }
  // A lumpy crown: rings of jittered radius joined by triangles.
  void add_blob(const Vec3& centre, double radius, double half_height, DataRng& rng) {
    ++object_;
    constexpr int kSides = 9, kRings = 4;
    std::vector<std::vector<Vec3>> rings;
    for (int r = 1; r <= kRings; ++r) {
      const double lat = -kPi / 2 + kPi * r / (kRings + 1);
      std::vector<Vec3> ring;
      for (int k = 0; k < kSides; ++k) {
        const double a = 2 * kPi * (k + 0.5 * (r % 2)) / kSides, s = radius * std::cos(lat) * rng.uniform(0.8, 1.15);
        ring.emplace_back(centre.x() + s * std::cos(a), centre.y() + s * std::sin(a), centre.z() + half_height * std::sin(lat));
      }
      rings.push_back(ring);
    }
    const Vec3 bottom = centre - Vec3(0, 0, half_height), top = centre + Vec3(0, 0, half_height);
    for (int k = 0; k < kSides; ++k) {
      const int n = (k + 1) % kSides;
      add_face({bottom, rings[0][n], rings[0][k]}, ClutterKind::Foliage);
      add_face({top, rings[kRings - 1][k], rings[kRings - 1][n]}, ClutterKind::Foliage);
      for (int r = 0; r + 1 < kRings; ++r) {
        add_face({rings[r][k], rings[r][n], rings[r + 1][k]}, ClutterKind::Foliage);
        add_face({rings[r][n], rings[r + 1][n], rings[r + 1][k]}, ClutterKind::Foliage);
      }
    }
  }

 private:
  PhotoScene& scene_;
  const std::vector<Vec3>& cameras_;
  uint32_t object_ = 0;
};

// Ray parity against the mesh's triangles: is X inside the closed building?
bool inside_mesh(const FacedMesh& m, const Vec3& X) {
  const Vec3 d = Vec3(0.5773, 0.5917, 0.5627).normalized();  // off-axis: misses edges of axis-aligned meshes
  int hits = 0;
  for (const MeshTriangle& t : m.triangles) {
    const Vec3 &a = m.vertices[t.v[0]], &b = m.vertices[t.v[1]], &c = m.vertices[t.v[2]];
    const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-12) continue;
    const Vec3 s = X - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    if (e2.dot(q) / det > 0) ++hits;
  }
  return hits % 2 == 1;
}

// A point on a wall frame at facade coordinates (u, z), pushed `out` metres along `normal`.
Vec3 wall_point(const FaceFrame& f, double u, double z, const Vec3& normal, double out) {
  const double t = std::abs(f.axis_v.z()) > 1e-9 ? (z - f.origin.z()) / f.axis_v.z() : 0.0;
  return f.origin + u * f.axis_u + t * f.axis_v + out * normal;
}

bool inside_polygon_xy(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) in = !in;
  }
  return in;
}

}  // namespace

void PhotoOptions::Check() const {
  facades.Check();
  if (!(exposure_stops >= 0 && exposure_stops <= 3)) throw std::invalid_argument("PhotoOptions.exposure_stops must be in [0, 3]");
  if (!(noise_gain >= 1 && noise_gain <= 10)) throw std::invalid_argument("PhotoOptions.noise_gain must be in [1, 10]");
  if (!(blur_gain >= 1 && blur_gain <= 5)) throw std::invalid_argument("PhotoOptions.blur_gain must be in [1, 5]");
}

ViewPhotometry view_photometry(const PhotoOptions& o, uint64_t seed, uint64_t view) {
  DataRng rng(mix_seed(mix_seed(seed, 0xE1905u), view));
  ViewPhotometry p;
  p.exposure = std::exp2(o.exposure_stops * rng.uniform(-1.0, 1.0));
  p.noise_gain = rng.uniform(1.0, o.noise_gain);
  p.blur_gain = rng.uniform(1.0, o.blur_gain);
  return p;
}

PolyMesh scene_mesh(const PolyMesh& building, const PhotoScene& scene) {
  PolyMesh m = building;
  if (m.labels.empty()) m.labels.assign(m.faces.size(), FaceLabel::Wall);
  const int base = static_cast<int>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), scene.clutter.vertices.begin(), scene.clutter.vertices.end());
  for (auto face : scene.clutter.faces) {
    for (int& v : face) v += base;
    m.faces.push_back(std::move(face));
    m.labels.push_back(FaceLabel::Wall);
  }
  return m;
}

PhotoScene make_photo_scene(const PolyMesh& building, const std::vector<Vec3>& camera_centres, const PhotoOptions& options,
                            uint64_t seed) {
  options.Check();
  const FacedMesh fm = build_faced_mesh(building);
  PhotoScene scene;
  scene.options = options;
  scene.facades = layout_facades(building, fm.frames, options.facades, seed);
  DataRng rng(mix_seed(seed, 0x5CE7Eu));
  const Vec3 lo = fm.box_min, hi = fm.box_max, centre = 0.5 * (lo + hi);
  const double height = hi.z() - lo.z(), radius = 0.5 * (hi - lo).head<2>().norm();
  // Sizes follow the storey height of the tallest wall: about the target, whatever the building's size.
  double h = 0;
  for (const FacadeLayout& f : scene.facades)
    if (f.wall && f.top_z - f.ground_z > h * std::max(1, f.storeys) - 1e-9) h = f.storey_height;
  if (h <= 0) h = height > 0 ? height / std::max(1.0, std::round(height / options.facades.storey_height_m)) : options.facades.storey_height_m;
  scene.storey_height = h;
  if (options.vary_sun) {
    scene.sun_azimuth_deg = rng.uniform(0.0, 360.0);
    scene.sun_elevation_deg = rng.uniform(30.0, 65.0);
  }
  SceneBuilder add(scene, camera_centres);
  const Vec3 target = centre;  // big objects must not hide this from any camera

  // Balconies: a parapet box under the windows of one or two columns of upper storeys, outside the wall.
  if (options.balconies)
    for (size_t f = 0; f < scene.facades.size(); ++f) {
      const FacadeLayout& L = scene.facades[f];
      if (!L.wall || L.storeys < 2 || rng.uniform() > 0.35) continue;
      const FaceFrame& fr = fm.frames[f];
      const double hh = L.storey_height;
      for (size_t w = 0; w < L.windows.size(); ++w) {
        if (L.window_storey[w] < 1) continue;
        const FacadeRect& r = L.windows[w];
        const double mid = 0.5 * (r.u0 + r.u1);
        if (cell_random(static_cast<int64_t>(std::floor(mid / hh)), static_cast<int64_t>(f), seed) < 0.5) continue;  // whole columns
        const Vec3 probe = wall_point(fr, mid, r.z0, fr.normal, 0.05 * hh);
        const Vec3 out = inside_mesh(fm, probe) ? Vec3(-fr.normal) : fr.normal;
        const double floor = L.ground_z + L.window_storey[w] * hh, u0 = r.u0 - 0.1 * hh, u1 = r.u1 + 0.1 * hh;
        std::array<Vec3, 8> c;
        for (int i = 0; i < 8; ++i)
          c[i] = wall_point(fr, i & 1 ? u1 : u0, i & 4 ? floor + 0.27 * hh : floor - 0.02 * hh, out, i & 2 ? 0.4 * hh : 0.0);
        add.add_box(c, ClutterKind::Balcony, ClutterKind::Balcony);
      }
    }

  // Chimneys on the larger roof faces.
  if (options.chimneys && rng.uniform() < 0.7) {
    const int count = rng.uniform() < 0.3 ? 2 : 1;
    std::vector<size_t> roofs;
    for (size_t f = 0; f < fm.frames.size(); ++f)
      if (fm.frames[f].kind == SurfaceKind::SlopedRoof || fm.frames[f].kind == SurfaceKind::FlatRoof) roofs.push_back(f);
    for (int k = 0; k < count && !roofs.empty(); ++k) {
      const size_t f = roofs[rng.below(roofs.size())];
      const FaceFrame& fr = fm.frames[f];
      std::vector<Vec2> poly;
      Vec2 plo = Vec2::Constant(1e300), phi = Vec2::Constant(-1e300);
      for (int v : building.faces[f]) {
        poly.push_back(building.vertices[v].head<2>());
        plo = plo.cwiseMin(poly.back()), phi = phi.cwiseMax(poly.back());
      }
      const Vec2 a = fr.axis_u.head<2>().normalized(), b(-a.y(), a.x());
      const double s = 0.14 * h;
      for (int attempt = 0; attempt < 40; ++attempt) {
        const Vec2 p(rng.uniform(plo.x(), phi.x()), rng.uniform(plo.y(), phi.y()));
        bool ok = true;
        double zlo = 1e300, zhi = -1e300;
        for (int i = 0; i < 4 && ok; ++i) {
          const Vec2 q = p + (i & 1 ? 1.3 : -1.3) * s * a + (i & 2 ? 1.3 : -1.3) * s * b;
          ok = inside_polygon_xy(poly, q);
          const double z = (fr.offset - fr.normal.x() * q.x() - fr.normal.y() * q.y()) / fr.normal.z();
          zlo = std::min(zlo, z), zhi = std::max(zhi, z);
        }
        if (!ok) continue;
        OrientedBox box{p, std::atan2(a.y(), a.x()), Vec2(s, s), zlo - 0.02 * h, zhi + 0.45 * h};
        if (!add.clear_of_cameras(box, 0.5 * h)) continue;
        add.add_box(box.corners(), ClutterKind::Chimney, ClutterKind::Chimney);
        break;
      }
    }
  }

  // The street side: the widest wall that reaches the ground (it has the front door).
  int front = -1;
  double front_width = 0;
  for (size_t f = 0; f < scene.facades.size(); ++f) {
    if (!scene.facades[f].wall) continue;
    double umin = 1e300, umax = -1e300, zmin = 1e300;
    for (int v : building.faces[f]) {
      const Vec3& p = building.vertices[v];
      umin = std::min(umin, (p - fm.frames[f].origin).dot(fm.frames[f].axis_u));
      umax = std::max(umax, (p - fm.frames[f].origin).dot(fm.frames[f].axis_u));
      zmin = std::min(zmin, p.z());
    }
    if (zmin < lo.z() + 0.05 * h && umax - umin > front_width) front = static_cast<int>(f), front_width = umax - umin;
  }
  Vec2 street_dir = Vec2::UnitX(), street_normal = Vec2::UnitY();
  if (front >= 0) {
    const FaceFrame& fr = fm.frames[front];
    street_dir = fr.axis_u.head<2>().normalized();
    street_normal = Vec2(-street_dir.y(), street_dir.x());
    const Vec3 probe = wall_point(fr, 0.5 * front_width, lo.z() + 0.5 * h, Vec3(street_normal.x(), street_normal.y(), 0), 0.05 * h);
    if (inside_mesh(fm, probe)) street_normal = -street_normal;
  }
  const double street_yaw = std::atan2(street_dir.y(), street_dir.x());
  if (options.ground) {
    double reach = 0;  // footprint's extent towards the street
    for (const Vec3& v : building.vertices) reach = std::max(reach, (v.head<2>() - centre.head<2>()).dot(street_normal));
    GroundLayout& g = scene.ground;
    g.road = true;
    g.road_half_width = 1.0 * h;
    g.road_dir = street_dir;
    g.road_point = centre.head<2>() + street_normal * (reach + rng.uniform(1.5, 3.0) * h + g.road_half_width);
    g.path_half_width = 0.3 * h;
    for (size_t f = 0; f < scene.facades.size(); ++f)
      for (const FacadeRect& d : scene.facades[f].doors) {
        const FaceFrame& fr = fm.frames[f];
        const Vec3 door = wall_point(fr, 0.5 * (d.u0 + d.u1), lo.z(), fr.normal, 0.0);
        Vec3 n = fr.normal;
        if (inside_mesh(fm, wall_point(fr, 0.5 * (d.u0 + d.u1), lo.z() + 0.3 * h, n, 0.05 * h))) n = -n;
        const Vec2 out = n.head<2>().normalized();
        const double to_road = (g.road_point - door.head<2>()).dot(street_normal);
        const double length = out.dot(street_normal) > 0.7 ? (to_road - g.road_half_width) / out.dot(street_normal) : 1.5 * h;
        g.paths.push_back({door.head<2>(), door.head<2>() + out * std::max(0.5 * h, length)});
      }
    // Cars parked along the road.
    const int cars = 1 + static_cast<int>(rng.below(3));
    for (int k = 0; k < cars; ++k) {
      const double along = rng.uniform(-1.0, 1.0) * (radius + 2 * h), lane = (rng.uniform() < 0.5 ? -0.5 : 0.5) * g.road_half_width;
      const Vec2 p = g.road_point + street_dir * along + street_normal * lane;
      const OrientedBox body{p, street_yaw, Vec2(0.75 * h, 0.3 * h), lo.z() + 0.1 * h, lo.z() + 0.42 * h};
      const OrientedBox cabin{p - street_dir * 0.1 * h, street_yaw, Vec2(0.4 * h, 0.27 * h), body.z1, body.z1 + 0.2 * h};
      if (!add.clear_of_cameras(body, 0.5 * h) || !add.clear_of_cameras(cabin, 0.5 * h)) continue;
      add.add_box(body.corners(), ClutterKind::CarBody, ClutterKind::CarBody);
      add.add_box(cabin.corners(), ClutterKind::CarCabin, ClutterKind::CarCabin);
    }
  }

  std::vector<OrientedBox> taken;  // footprints of trees and neighbours, kept apart
  auto free_of = [&](const OrientedBox& b) {
    for (const OrientedBox& t : taken)
      if ((t.centre - b.centre).norm() < t.half.norm() + b.half.norm()) return false;
    if (scene.ground.road && std::abs((b.centre - scene.ground.road_point).dot(street_normal)) < scene.ground.road_half_width + b.half.norm())
      return false;
    return true;
  };
  auto reach_towards = [&](const Vec2& dir) {
    double r = 0;
    for (const Vec3& v : building.vertices) r = std::max(r, (v.head<2>() - centre.head<2>()).dot(dir));
    return r;
  };

  // Trees: cones (conifers) and lumpy crowns on trunks, a little away from the walls.
  if (options.trees) {
    const int trees = 2 + static_cast<int>(rng.below(3));
    for (int k = 0; k < trees; ++k)
      for (int attempt = 0; attempt < 10; ++attempt) {
        const double theta = rng.uniform(0.0, 2 * kPi), crown = rng.uniform(0.5, 0.9) * h, tall = rng.uniform(1.3, 2.8) * h;
        const Vec2 dir(std::cos(theta), std::sin(theta));
        const Vec2 at = centre.head<2>() + dir * (reach_towards(dir) + crown + rng.uniform(0.3, 1.5) * h);
        const OrientedBox bound{at, 0.0, Vec2(crown, crown), lo.z(), lo.z() + tall};
        if (!free_of(bound) || !add.clear_of_cameras(bound, 0.5 * h)) continue;
        const bool conifer = rng.uniform() < 0.5;
        const double trunk_top = lo.z() + (conifer ? 0.25 : 0.45) * tall;
        const OrientedBox trunk{at, theta, Vec2(0.05 * h, 0.05 * h), lo.z(), trunk_top + 0.1 * h};
        add.add_box(trunk.corners(), ClutterKind::Trunk, ClutterKind::Trunk);
        if (conifer) {
          add.add_cone(at, trunk_top, lo.z() + tall, crown, 8, ClutterKind::Foliage);
        } else {
          const double half = 0.5 * (lo.z() + tall - trunk_top);
          add.add_blob(Vec3(at.x(), at.y(), trunk_top + half), crown, half, rng);
        }
        taken.push_back(bound);
        break;
      }
  }

  // Neighbouring buildings: boxes of about this building's size beside it, lowered until they hide its
  // centre from no camera; failing that, beyond the cameras (background).
  if (options.neighbours) {
    const int count = rng.uniform() < 0.5 ? 2 : 1;
    const Vec2 size = (hi - lo).head<2>();
    double ring = 0;
    for (const Vec3& c : camera_centres) ring = std::max(ring, (c.head<2>() - centre.head<2>()).norm());
    for (int k = 0; k < count; ++k)
      for (int attempt = 0; attempt < 30; ++attempt) {
        const double theta = rng.uniform(0.0, 2 * kPi);
        const Vec2 dir(std::cos(theta), std::sin(theta));
        const Vec2 half(0.5 * size.x() * rng.uniform(0.6, 1.2), 0.5 * size.y() * rng.uniform(0.6, 1.2));
        const double beside = reach_towards(dir) + rng.uniform(0.3, 1.0) * radius + h + half.norm();
        const double dist = attempt < 20 ? beside : std::max(beside, ring + half.norm() + 2 * h);
        OrientedBox box{centre.head<2>() + dir * dist, street_yaw, half, lo.z(), lo.z() + std::max(h, height * rng.uniform(0.6, 1.3))};
        while (box.z1 - box.z0 > h && add.hides(box, target)) box.z1 = box.z0 + std::max(h, 0.8 * (box.z1 - box.z0));
        if (!free_of(box) || !add.clear_of_cameras(box, 1.0 * h) || add.hides(box, target)) continue;
        add.add_box(box.corners(), ClutterKind::NeighbourWall, ClutterKind::NeighbourRoof);
        taken.push_back(box);
        break;
      }
  }
  return scene;
}

}  // namespace lc2wf

#include "dataset/geometry/building.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"

namespace lc2wf {
namespace {

using EdgeKey = std::pair<int, int>;

EdgeKey key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// Newell normal: robust for non-convex polygons.
Vec3 face_normal(const PolyMesh& m, const std::vector<int>& f) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < f.size(); ++k) {
    const Vec3& a = m.vertices[f[k]];
    const Vec3& b = m.vertices[f[(k + 1) % f.size()]];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
  }
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : n;
}

double planarity_deviation(const PolyMesh& m, const std::vector<int>& f) {
  Vec3 c = Vec3::Zero();
  for (int id : f) c += m.vertices[id];
  c /= static_cast<double>(f.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int id : f) {
    const Vec3 d = m.vertices[id] - c;
    cov += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  const Vec3 n = es.eigenvectors().col(0);
  double dev = 0;
  for (int id : f) dev = std::max(dev, std::abs(n.dot(m.vertices[id] - c)));
  return dev;
}

std::map<EdgeKey, std::vector<int>> edge_faces(const PolyMesh& m) {
  std::map<EdgeKey, std::vector<int>> out;
  for (size_t fi = 0; fi < m.faces.size(); ++fi) {
    const auto& f = m.faces[fi];
    for (size_t k = 0; k < f.size(); ++k) out[key(f[k], f[(k + 1) % f.size()])].push_back(static_cast<int>(fi));
  }
  return out;
}

}  // namespace

void WireframeOptions::Check() const {
  if (!(coplanar_angle_deg >= 0 && coplanar_angle_deg < 90)) {
    throw std::invalid_argument("WireframeOptions.coplanar_angle_deg must be in [0, 90)");
  }
}

void BuildingOptions::Check() const {
  if (!(raw_per_metre > 0) || !std::isfinite(raw_per_metre)) throw std::invalid_argument("BuildingOptions.raw_per_metre must be > 0");
  if (!(duplicate_tol_m >= 0)) throw std::invalid_argument("BuildingOptions.duplicate_tol_m must be >= 0");
  if (!(planarity_tol_m > 0)) throw std::invalid_argument("BuildingOptions.planarity_tol_m must be > 0");
  wireframe.Check();
}

Wireframe build_wireframe(const PolyMesh& mesh, const WireframeOptions& options) {
  options.Check();
  Wireframe wf;
  wf.junctions = mesh.vertices;
  const double cos_tol = std::cos(options.coplanar_angle_deg * M_PI / 180.0);
  std::map<EdgeKey, std::vector<int>> faces_of;
  if (options.drop_coplanar_edges) faces_of = edge_faces(mesh);
  std::vector<Vec3> normals;
  if (options.drop_coplanar_edges) {
    for (const auto& f : mesh.faces) normals.push_back(face_normal(mesh, f));
  }
  std::map<EdgeKey, bool> seen;
  for (const auto& f : mesh.faces) {
    for (size_t k = 0; k < f.size(); ++k) {
      const EdgeKey e = key(f[k], f[(k + 1) % f.size()]);
      if (e.first == e.second || !seen.emplace(e, true).second) continue;
      if (options.drop_coplanar_edges) {
        const auto& fs = faces_of[e];
        if (fs.size() == 2 && std::abs(normals[fs[0]].dot(normals[fs[1]])) >= cos_tol) continue;
      }
      wf.edges.push_back({e.first, e.second});
    }
  }
  return wf;
}

MeshReport analyse_mesh(const PolyMesh& mesh, double duplicate_tolerance) {
  MeshReport r;
  const double tol2 = duplicate_tolerance * duplicate_tolerance;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (size_t j = i + 1; j < mesh.vertices.size(); ++j) {
      if ((mesh.vertices[i] - mesh.vertices[j]).squaredNorm() <= tol2) ++r.duplicate_vertex_pairs;
    }
  }
  const auto ef = edge_faces(mesh);
  r.unique_edges = static_cast<int>(ef.size());
  for (const auto& [e, fs] : ef) {
    if (fs.size() != 2) ++r.non_manifold_edges;
  }
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    r.max_planarity_deviation = std::max(r.max_planarity_deviation, planarity_deviation(mesh, mesh.faces[fi]));
    if (fi < mesh.labels.size() && mesh.labels[fi] == FaceLabel::Roof) ++r.roof_faces;
  }
  return r;
}

int merge_duplicate_vertices(PolyMesh& mesh, double tolerance, int* dropped_faces) {
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<int> rep(n);
  std::iota(rep.begin(), rep.end(), 0);
  const double tol2 = tolerance * tolerance;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < j; ++i) {
      if (rep[i] == i && (mesh.vertices[i] - mesh.vertices[j]).squaredNorm() <= tol2) {
        rep[j] = i;
        break;
      }
    }
  }
  std::vector<int> new_id(n, -1);
  std::vector<Vec3> kept;
  for (int i = 0; i < n; ++i) {
    if (rep[i] == i) {
      new_id[i] = static_cast<int>(kept.size());
      kept.push_back(mesh.vertices[i]);
    }
  }
  const int merged = n - static_cast<int>(kept.size());
  if (merged == 0) return 0;
  std::vector<std::vector<int>> faces;
  std::vector<FaceLabel> labels;
  for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    std::vector<int> f;
    for (int id : mesh.faces[fi]) {
      const int v = new_id[rep[id]];
      if (f.empty() || f.back() != v) f.push_back(v);
    }
    while (f.size() > 1 && f.front() == f.back()) f.pop_back();
    std::vector<int> distinct = f;
    std::sort(distinct.begin(), distinct.end());
    if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() < 3) {
      if (dropped_faces) ++*dropped_faces;
      continue;
    }
    faces.push_back(std::move(f));
    if (fi < mesh.labels.size()) labels.push_back(mesh.labels[fi]);
  }
  mesh.vertices = std::move(kept);
  mesh.faces = std::move(faces);
  if (!mesh.labels.empty()) mesh.labels = std::move(labels);
  return merged;
}

Building make_building(const std::string& name, PolyMesh mesh, const BuildingOptions& options) {
  options.Check();
  if (mesh.vertices.size() < 2) throw DataError(name, "mesh has fewer than 2 vertices");
  if (mesh.faces.empty()) throw DataError(name, "mesh has no faces");
  if (!mesh.labels.empty() && mesh.labels.size() != mesh.faces.size()) {
    throw DataError(name, "face label count does not match face count");
  }
  Building b;
  b.name = name;
  Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  b.units.raw_per_metre = options.raw_per_metre;
  b.units.origin_raw = options.recentre_xy ? Vec3(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z())
                                           : Vec3(0, 0, lo.z());
  for (auto& v : mesh.vertices) v = b.units.to_metres(v);
  if (!options.gt_after_repair) b.wireframe = build_wireframe(mesh, options.wireframe);

  b.issues.merged_vertices = merge_duplicate_vertices(mesh, options.duplicate_tol_m, &b.issues.dropped_faces);
  if (b.issues.merged_vertices > 0) {
    b.issues.warnings.push_back(name + ": merged " + std::to_string(b.issues.merged_vertices) +
                                " duplicate vertices, dropped " + std::to_string(b.issues.dropped_faces) +
                                " degenerate faces");
  }
  const MeshReport rep = analyse_mesh(mesh, 0.0);
  b.issues.non_manifold_edges = rep.non_manifold_edges;
  if (rep.non_manifold_edges > 0) {
    b.issues.warnings.push_back(name + ": " + std::to_string(rep.non_manifold_edges) +
                                " edges not shared by exactly two faces (kept)");
  }
  b.issues.max_planarity_dev_m = rep.max_planarity_deviation;
  b.issues.non_planar = rep.max_planarity_deviation > options.planarity_tol_m;
  if (b.issues.non_planar) {
    const std::string msg = "non-planar face, deviation " + std::to_string(rep.max_planarity_deviation) + " m";
    if (options.non_planar == NonPlanarPolicy::Skip) throw BuildingSkipped(name, msg);
    b.issues.warnings.push_back(name + ": " + msg + " (kept)");
  }
  if (options.gt_after_repair) b.wireframe = build_wireframe(mesh, options.wireframe);
  b.mesh = std::move(mesh);
  return b;
}

Building load_roof_image_building(const std::filesystem::path& polyshape, const BuildingOptions& options) {
  return make_building(polyshape.stem().string(), read_polyshape(polyshape), options);
}

std::vector<std::string> list_polyshape_names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  std::filesystem::directory_iterator it(dir, ec);
  if (ec) throw DataError(dir.string(), "cannot list folder");
  for (const auto& entry : it) {
    if (entry.path().extension() == ".polyshape") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace lc2wf

#include "tools/render/facade_layout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dataset/sampling/rng.h"

namespace lc2wf {
namespace {

bool inside_polygon(const std::vector<Vec2>& poly, double u, double z) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > z) != (b.y() > z) && u < (b.x() - a.x()) * (z - a.y()) / (b.y() - a.y()) + a.x()) in = !in;
  }
  return in;
}

// The rectangle grown by `margin` must lie inside the face (gable ends, walls that start above ground).
bool fits(const std::vector<Vec2>& poly, const FacadeRect& r, double margin) {
  for (double u : {r.u0 - margin, r.u1 + margin, 0.5 * (r.u0 + r.u1)})
    for (double z : {r.z0 - margin, r.z1 + margin})
      if (!inside_polygon(poly, u, z)) return false;
  return true;
}

}  // namespace

void FacadeOptions::Check() const {
  if (!(storey_height_m >= 0.5 && storey_height_m <= 20))
    throw std::invalid_argument("FacadeOptions.storey_height_m must be in [0.5, 20]");
}

std::vector<FacadeLayout> layout_facades(const PolyMesh& mesh, const std::vector<FaceFrame>& frames,
                                         const FacadeOptions& options, uint64_t seed) {
  options.Check();
  if (frames.size() != mesh.faces.size()) throw std::invalid_argument("layout_facades: one frame per face expected");
  double ground = 1e300;
  for (const Vec3& v : mesh.vertices) ground = std::min(ground, v.z());
  std::vector<FacadeLayout> out(mesh.faces.size());
  int widest = -1;
  double widest_width = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const FaceFrame& fr = frames[f];
    FacadeLayout& L = out[f];
    L.ground_z = ground;
    // Vertical gable triangles are labelled roof: attic, no storeys of their own.
    if (fr.kind != SurfaceKind::Wall || (!mesh.labels.empty() && mesh.labels[f] == FaceLabel::Roof)) continue;
    std::vector<Vec2> poly;
    double umin = 1e300, umax = -1e300, zmin = 1e300, zmax = -1e300;
    for (int v : mesh.faces[f]) {
      const Vec3& p = mesh.vertices[v];
      poly.emplace_back((p - fr.origin).dot(fr.axis_u), p.z());
      umin = std::min(umin, poly.back().x()), umax = std::max(umax, poly.back().x());
      zmin = std::min(zmin, p.z()), zmax = std::max(zmax, p.z());
    }
    // Eave: the lowest vertex of the upper part (a gable's peak does not count).
    double top = zmax;
    for (const Vec2& p : poly)
      if (p.y() > zmin + 0.25 * (zmax - zmin)) top = std::min(top, p.y());
    const double height = top - ground;
    if (height <= 0) continue;
    L.wall = true;
    L.top_z = top;
    L.peak_z = zmax;
    L.storeys = std::max(1, static_cast<int>(std::lround(height / options.storey_height_m)));
    const double h = height / L.storeys;
    L.storey_height = h;
    if (!options.windows) continue;
    const double width = umax - umin;
    const int bays = static_cast<int>(std::floor(width / h));  // one window per storey height of wall
    if (bays < 1) continue;
    const double bay = width / bays, half = 0.21 * h, frame = 0.04 * h;
    for (int k = 0; k < L.storeys; ++k)
      for (int b = 0; b < bays; ++b) {
        const double c = umin + (b + 0.5) * bay;
        const FacadeRect r{c - half, c + half, ground + k * h + 0.3 * h, ground + k * h + 0.75 * h};
        if (!fits(poly, r, frame + 0.05 * h)) continue;
        L.windows.push_back(r);
        L.window_storey.push_back(k);
      }
    if (zmin <= ground + 0.05 * h && width > widest_width) widest = static_cast<int>(f), widest_width = width;
  }
  if (!options.doors) return out;
  DataRng rng(mix_seed(seed, 0xD00Du));
  for (size_t f = 0; f < out.size(); ++f) {
    FacadeLayout& L = out[f];
    const bool ground_floor = std::count(L.window_storey.begin(), L.window_storey.end(), 0) > 0;
    std::vector<size_t> ground_windows;
    for (size_t w = 0; w < L.windows.size(); ++w)
      if (L.window_storey[w] == 0) ground_windows.push_back(w);
    // The widest ground wall always has the front door; walls of three bays or more now and then a side door.
    const bool side_door = ground_windows.size() >= 3 && rng.uniform() < 0.3;
    if (!ground_floor || (static_cast<int>(f) != widest && !side_door)) continue;
    const size_t w = ground_windows[rng.below(ground_windows.size())];
    const double c = 0.5 * (L.windows[w].u0 + L.windows[w].u1), h = L.storey_height;
    L.doors.push_back({c - 0.19 * h, c + 0.19 * h, L.ground_z, L.ground_z + 0.72 * h});
    L.windows.erase(L.windows.begin() + w);
    L.window_storey.erase(L.window_storey.begin() + w);
  }
  return out;
}

}  // namespace lc2wf

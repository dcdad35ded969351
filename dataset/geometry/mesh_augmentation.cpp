#include "dataset/geometry/mesh_augmentation.h"

#include <cmath>
#include <stdexcept>

#include "dataset/sampling/rng.h"

namespace lc2wf {
namespace {

double log_uniform(DataRng& rng, double lo, double hi) { return lo * std::exp(rng.uniform() * std::log(hi / lo)); }
double round_to(double x, double step) { return std::round(x / step) * step; }

}  // namespace

void MeshAugmentOptions::Check() const {
  if (!(height_min_m > 0 && std::isfinite(height_max_m) && height_max_m >= height_min_m))
    throw std::invalid_argument("MeshAugmentOptions.height_min_m must be > 0 and <= MeshAugmentOptions.height_max_m");
  if (!(stretch_min > 0 && std::isfinite(stretch_max) && stretch_max >= stretch_min))
    throw std::invalid_argument("MeshAugmentOptions.stretch_min must be > 0 and <= MeshAugmentOptions.stretch_max");
}

MeshAugmentation draw_mesh_augmentation(uint64_t seed, const MeshAugmentOptions& options) {
  options.Check();
  DataRng rng(seed);
  MeshAugmentation a;
  // Every value is drawn whatever the flags, so turning one part off leaves the others unchanged.
  const double height = round_to(log_uniform(rng, options.height_min_m, options.height_max_m), 0.01);
  const double sx = round_to(log_uniform(rng, options.stretch_min, options.stretch_max), 0.001);
  const double sy = round_to(log_uniform(rng, options.stretch_min, options.stretch_max), 0.001);
  const double turn = round_to(2 * M_PI * rng.uniform(), 0.0001);
  a.target_height_m = options.scale_height ? height : 0.0;
  a.scale_x = sx;
  a.scale_y = sy;
  a.turn_rad = options.turn ? turn : 0.0;
  return a;
}

PolyMesh augment_mesh(const PolyMesh& mesh, const MeshAugmentation& a) {
  if (mesh.vertices.empty()) throw std::invalid_argument("augment_mesh: the mesh has no vertex");
  Eigen::AlignedBox3d box;
  for (const Vec3& v : mesh.vertices) box.extend(v);
  const double height = box.sizes().z();
  if (!(height > 0)) throw std::invalid_argument("augment_mesh: the mesh has no height");
  const double sz = a.target_height_m > 0 ? a.target_height_m / height : 1.0;
  const Vec3 origin(0.5 * (box.min().x() + box.max().x()), 0.5 * (box.min().y() + box.max().y()), box.min().z());
  const double c = std::cos(a.turn_rad), s = std::sin(a.turn_rad);
  PolyMesh out = mesh;
  for (Vec3& v : out.vertices) {
    const Vec3 p = v - origin;
    const double x = a.scale_x * p.x(), y = a.scale_y * p.y();
    v = Vec3(c * x - s * y, s * x + c * y, sz * p.z());
  }
  return out;
}

PolyMesh augment_mesh(const PolyMesh& mesh, uint64_t seed, const MeshAugmentOptions& options) {
  return augment_mesh(mesh, draw_mesh_augmentation(seed, options));
}

}  // namespace lc2wf

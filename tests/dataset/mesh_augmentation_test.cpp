// Mesh augmentation keeps a building closed and planar, hits its target height with the ground at 0, and
// is a function of its seed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset/formats/mesh_io.h"
#include "dataset/geometry/closed_mesh.h"
#include "dataset/geometry/mesh_augmentation.h"
#include "dataset/synthetic/lod2_generator.h"

namespace lc2wf {
namespace {

Eigen::AlignedBox3d box_of(const PolyMesh& m) {
  Eigen::AlignedBox3d b;
  for (const Vec3& v : m.vertices) b.extend(v);
  return b;
}

TEST(MeshAugmentation, KeepsClosureAndHitsTheTargetHeight) {
  MeshAugmentOptions o;
  for (Lod2Kind kind : {Lod2Kind::Dormers, Lod2Kind::Courtyard, Lod2Kind::RowHouses, Lod2Kind::Tower}) {
    PolyMesh m = generate_lod2_building(kind, 5).mesh;
    for (Vec3& v : m.vertices) v.z() += 100;  // any ground height comes down to 0
    for (uint64_t seed = 0; seed < 5; ++seed) {
      const MeshAugmentation draw = draw_mesh_augmentation(seed, o);
      EXPECT_GE(draw.target_height_m, 3.0);
      EXPECT_LE(draw.target_height_m, 60.0);
      const PolyMesh a = augment_mesh(m, draw);
      const ClosedMeshReport r = inspect_closed_mesh(a);
      EXPECT_TRUE(r.closed()) << lod2_kind_name(kind) << " seed " << seed;
      EXPECT_LT(r.max_planarity_deviation, 1e-6);
      EXPECT_NEAR(box_of(a).min().z(), 0.0, 1e-9);
      EXPECT_NEAR(box_of(a).max().z(), draw.target_height_m, 1e-9);
      EXPECT_EQ(a.faces, m.faces);
      EXPECT_EQ(polyshape_string(augment_mesh(m, seed, o)), polyshape_string(a));
    }
  }
}

TEST(MeshAugmentation, StretchesAlongItsOwnAxesWithoutTurn) {
  Lod2Options g;
  g.turn = false;
  const PolyMesh m = generate_lod2_building(Lod2Kind::Gabled, 2, g).mesh;
  const MeshAugmentation draw{3.0, 1.2, 0.9, 0.0};
  const PolyMesh a = augment_mesh(m, draw);
  EXPECT_NEAR(box_of(a).sizes().x(), 1.2 * box_of(m).sizes().x(), 1e-9);
  EXPECT_NEAR(box_of(a).sizes().y(), 0.9 * box_of(m).sizes().y(), 1e-9);
  EXPECT_NEAR(box_of(a).sizes().z(), 3.0, 1e-9);
  MeshAugmentOptions keep;
  keep.scale_height = false;
  keep.turn = false;
  EXPECT_NEAR(box_of(augment_mesh(m, 7, keep)).sizes().z(), box_of(m).sizes().z(), 1e-9);
}

TEST(MeshAugmentation, BadOptionsAndFlatMeshesAreRefused) {
  MeshAugmentOptions o;
  o.height_min_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.height_max_m = 2;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.stretch_max = 0.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  PolyMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  flat.faces = {{0, 1, 2}};
  EXPECT_THROW(augment_mesh(flat, 1, MeshAugmentOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

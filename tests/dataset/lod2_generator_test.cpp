// Procedural LoD2 buildings: every kind closed, planar and manifold with the roof it promises; the union
// of blocks keeps only the outer surface; sizes from 3 m to 60 m high and up to 150 m long; determinism.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "dataset/formats/mesh_io.h"
#include "dataset/geometry/building.h"
#include "dataset/geometry/closed_mesh.h"
#include "dataset/geometry/polygon_2d.h"
#include "dataset/geometry/roof_kind.h"
#include "dataset/synthetic/block_assembly.h"
#include "dataset/synthetic/footprints.h"
#include "dataset/synthetic/lod2_generator.h"
#include "dataset/synthetic/roof_shapes.h"
#include "dataset/synthetic/synthetic_building.h"

namespace lc2wf {
namespace {

std::vector<int> faces_labelled(const PolyMesh& m, FaceLabel label) {
  std::vector<int> out;
  for (size_t f = 0; f < m.faces.size(); ++f)
    if (m.labels[f] == label) out.push_back(static_cast<int>(f));
  return out;
}

double face_height_span(const PolyMesh& m, int f) {
  double lo = 1e9, hi = -1e9;
  for (int v : m.faces[f]) {
    lo = std::min(lo, m.vertices[v].z());
    hi = std::max(hi, m.vertices[v].z());
  }
  return hi - lo;
}

void expect_closed(const PolyMesh& m, const std::string& what) {
  const ClosedMeshReport r = inspect_closed_mesh(m);
  EXPECT_TRUE(r.closed()) << what << ": not shared by two " << r.edges_not_shared_by_two << ", same direction "
                          << r.edges_same_direction << ", T-junctions " << r.vertices_inside_edges << ", duplicates "
                          << r.duplicate_vertex_pairs << ", degenerate " << r.degenerate_faces << ", volume " << r.volume;
  EXPECT_LT(r.max_planarity_deviation, 1e-6) << what;
  EXPECT_EQ(m.labels.size(), m.faces.size()) << what;
  for (const Vec3& v : m.vertices) EXPECT_GE(v.z(), -1e-9) << what;
  for (int f : faces_labelled(m, FaceLabel::Base)) EXPECT_LT(face_height_span(m, f), 1e-9) << what;
}

TEST(Lod2Generator, EveryKindAtSeveralSeedsIsClosedWithItsRoof) {
  for (int k = 0; k < kLod2KindCount; ++k) {
    const Lod2Kind kind = static_cast<Lod2Kind>(k);
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      const GeneratedBuilding b = generate_lod2_building(kind, seed);
      const std::string what = std::string(lod2_kind_name(kind)) + " seed " + std::to_string(seed);
      expect_closed(b.mesh, what);
      EXPECT_GE(inspect_closed_mesh(b.mesh).min_vertex_distance, 0.1) << what;
      const auto roofs = faces_labelled(b.mesh, FaceLabel::Roof);
      std::set<long> flat_levels;
      int tilted = 0;
      for (int f : roofs) {
        if (face_height_span(b.mesh, f) < 1e-9) flat_levels.insert(std::lround(b.mesh.vertices[b.mesh.faces[f][0]].z() * 1000));
        else ++tilted;
      }
      const RoofKind classified = classify_roof(b.mesh);
      switch (kind) {
        case Lod2Kind::Flat: EXPECT_EQ(roofs.size(), 1u) << what; EXPECT_EQ(classified, RoofKind::Flat) << what; break;
        case Lod2Kind::FlatMulti: EXPECT_EQ(tilted, 0) << what; EXPECT_GE(flat_levels.size(), 2u) << what;
          EXPECT_EQ(classified, RoofKind::FlatMulti) << what; break;
        case Lod2Kind::Gabled: EXPECT_EQ(roofs.size(), 2u) << what; EXPECT_EQ(classified, RoofKind::Gabled) << what; break;
        case Lod2Kind::Shed: EXPECT_EQ(roofs.size(), 1u) << what; EXPECT_EQ(tilted, 1) << what;
          EXPECT_EQ(classified, RoofKind::Shed) << what; break;
        case Lod2Kind::Hipped: EXPECT_EQ(roofs.size(), 4u) << what; EXPECT_EQ(classified, RoofKind::Hipped) << what; break;
        case Lod2Kind::Pyramid: {
          EXPECT_EQ(roofs.size(), 4u) << what;
          std::set<int> shared(b.mesh.faces[roofs[0]].begin(), b.mesh.faces[roofs[0]].end());
          for (int f : roofs) {
            std::set<int> next;
            for (int v : b.mesh.faces[f]) if (shared.count(v)) next.insert(v);
            shared = next;
          }
          EXPECT_EQ(shared.size(), 1u) << what << ": the four faces meet in one apex";
          break;
        }
        case Lod2Kind::Mansard: EXPECT_TRUE(roofs.size() == 5u || roofs.size() == 8u) << what << " " << roofs.size(); break;
        case Lod2Kind::Gambrel: EXPECT_EQ(roofs.size(), 4u) << what; EXPECT_EQ(tilted, 4) << what; break;
        case Lod2Kind::SawTooth: EXPECT_GE(tilted, 3) << what; EXPECT_EQ(flat_levels.size(), 0u) << what; break;
        case Lod2Kind::Dormers: {  // a dormer's front and cheeks are walls standing on the roof, above the eaves
          double eaves = 1e9;
          for (int f : roofs)
            for (int v : b.mesh.faces[f]) eaves = std::min(eaves, b.mesh.vertices[v].z());
          int on_roof = 0;
          for (int f : faces_labelled(b.mesh, FaceLabel::Wall)) {
            double low = 1e9;
            for (int v : b.mesh.faces[f]) low = std::min(low, b.mesh.vertices[v].z());
            on_roof += low > eaves + 0.1;
          }
          EXPECT_GE(roofs.size(), 3u) << what;
          EXPECT_GE(on_roof, 1) << what;
          break;
        }
        case Lod2Kind::Tower: EXPECT_GE(b.height_m, 18 - 1e-9) << what; EXPECT_LE(b.height_m, 60 + 1e-9) << what; break;
        case Lod2Kind::LargeBlock: EXPECT_GE(b.footprint_long_m, 60 - 1e-9) << what; EXPECT_LE(b.footprint_long_m, 150 + 1e-9) << what; break;
        case Lod2Kind::RowHouses: EXPECT_GE(b.footprint_long_m, 13.5 - 1e-9) << what; break;
        case Lod2Kind::LShape: case Lod2Kind::TShape: case Lod2Kind::UShape: {
          const auto base = faces_labelled(b.mesh, FaceLabel::Base);
          ASSERT_EQ(base.size(), 1u) << what;
          EXPECT_EQ(b.mesh.faces[base[0]].size(), kind == Lod2Kind::LShape ? 6u : 8u) << what;
          break;
        }
        case Lod2Kind::Courtyard: {  // a face cannot hold the hole: the base is split in two at its own corners
          const auto base = faces_labelled(b.mesh, FaceLabel::Base);
          EXPECT_EQ(base.size(), 2u) << what;
          size_t corners = 0;
          for (int f : base) corners += b.mesh.faces[f].size();
          EXPECT_EQ(corners, 12u) << what << ": 8 footprint corners, the two shared by both pieces twice";
          break;
        }
        case Lod2Kind::MultiPart: EXPECT_GE(roofs.size(), 2u) << what; break;
      }
    }
  }
}

TEST(Lod2Generator, SameSeedSameBytesOtherSeedOtherBuilding) {
  Lod2Options o;
  for (uint64_t seed : {3u, 4u, 99u}) {
    const GeneratedBuilding a = generate_lod2_building(seed, o), b = generate_lod2_building(seed, o);
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(polyshape_string(a.mesh), polyshape_string(b.mesh));
  }
  EXPECT_NE(polyshape_string(generate_lod2_building(Lod2Kind::Gabled, 1).mesh),
            polyshape_string(generate_lod2_building(Lod2Kind::Gabled, 2).mesh));
}

TEST(Lod2Generator, HeightsAndLengthsSpanTheirRanges) {
  double shed_low = 1e9, tower_high = 0, block_long = 0;
  for (uint64_t seed = 0; seed < 200; ++seed) {
    shed_low = std::min(shed_low, generate_lod2_building(Lod2Kind::Shed, seed).height_m);
    tower_high = std::max(tower_high, generate_lod2_building(Lod2Kind::Tower, seed).height_m);
    block_long = std::max(block_long, generate_lod2_building(Lod2Kind::LargeBlock, seed).footprint_long_m);
  }
  EXPECT_LT(shed_low, 3.5);
  EXPECT_GT(tower_high, 50);
  EXPECT_LE(tower_high, 60 + 1e-9);
  EXPECT_GT(block_long, 130);
}

TEST(BlockAssembly, ThreeMetreShedSixtyMetreTowerAndA150MetreBlockClose) {
  const PolyMesh shed = assemble_blocks({shed_block({0, 0, 5, 4}, Side::South, 2.4, 0.15)});
  expect_closed(shed, "shed");
  double top = 0;
  for (const Vec3& v : shed.vertices) top = std::max(top, v.z());
  EXPECT_NEAR(top, 3.0, 1e-9);
  EXPECT_EQ(shed.vertices.size(), 8u);
  const PolyMesh tower = assemble_blocks({pyramid_block({0, 0, 8, 8}, 52, 8), flat_block({-4, -4, 14, 12}, 6)});
  expect_closed(tower, "tower");
  for (const Vec3& v : tower.vertices) top = std::max(top, v.z());
  EXPECT_NEAR(top, 60.0, 1e-9);
  const PolyMesh block = assemble_blocks({flat_block({0, 0, 150, 20}, 25)});
  expect_closed(block, "block");
  EXPECT_EQ(block.vertices.size(), 8u);
  EXPECT_EQ(build_wireframe(block).edges.size(), 12u);
}

TEST(BlockAssembly, PartsOfDifferentHeightsKeepOnlyTheOuterSurface) {
  // A 6 m block beside a 3 m block: the wall they share shows only above 3 m; the front and back walls are
  // one stepped polygon each.
  const PolyMesh m = assemble_blocks({flat_block({0, 0, 10, 8}, 6), flat_block({10, 0, 16, 8}, 3)});
  expect_closed(m, "two heights");
  EXPECT_EQ(m.vertices.size(), 12u);
  EXPECT_EQ(m.faces.size(), 8u);  // 2 roofs, base, 4 outer walls, the step
  for (size_t f = 0; f < m.faces.size(); ++f) {
    bool on_shared_line = true, below_step = true;
    for (int v : m.faces[f]) {
      on_shared_line = on_shared_line && std::abs(m.vertices[v].x() - 10) < 1e-9;
      below_step = below_step && m.vertices[v].z() < 3 + 1e-9;
    }
    EXPECT_FALSE(on_shared_line && below_step) << "the shared wall below 3 m must not appear";
  }
  // Equal heights: one roof face, one box.
  const PolyMesh same = assemble_blocks({flat_block({0, 0, 10, 8}, 6), flat_block({10, 0, 16, 8}, 6)});
  expect_closed(same, "equal heights");
  EXPECT_EQ(same.vertices.size(), 8u);
  EXPECT_EQ(faces_labelled(same, FaceLabel::Roof).size(), 1u);
}

TEST(BlockAssembly, HippedLIsTheHandMadeLRoof) {
  // Two overlapping hipped wings: the hips and the valley of the hand-made L (15 junctions, 26 edges).
  const double s = std::tan(37.0 * M_PI / 180.0);
  std::vector<RoofedBlock> blocks;
  for (const Wing& w : l_wings(16, 14, 8, false)) blocks.push_back(hip_block(w.rect, 3.75, s, s, w.along_x));
  const PolyMesh m = assemble_blocks(blocks);
  expect_closed(m, "L");
  const Wireframe wf = build_wireframe(m), hand = build_wireframe(make_l_mesh(LBuildingSpec{}));
  EXPECT_EQ(wf.junctions.size(), hand.junctions.size());
  EXPECT_EQ(wf.edges.size(), hand.edges.size());
  EXPECT_EQ(faces_labelled(m, FaceLabel::Roof).size(), 6u);
}

TEST(BlockAssembly, BadBlocksAreRefused) {
  EXPECT_THROW(assemble_blocks({}), std::invalid_argument);
  EXPECT_THROW(assemble_blocks({flat_block({0, 0, 0, 5}, 3)}), std::invalid_argument);
  EXPECT_THROW(assemble_blocks({flat_block({0, 0, 5, 5}, -1)}), std::invalid_argument);
  RoofedBlock none = flat_block({0, 0, 5, 5}, 3);
  none.planes.clear();
  EXPECT_THROW(assemble_blocks({none}), std::invalid_argument);
}

TEST(Polygon2d, OutlinesSubtractionAndHoles) {
  const Polygon2 a = {{0, 0}, {2, 0}, {2, 1}, {0, 1}}, b = {{0, 1}, {1, 1}, {1, 2}, {0, 2}};
  const auto l = union_outline({a, b});
  ASSERT_EQ(l.size(), 1u);
  EXPECT_NEAR(signed_area(l[0]), 3.0, 1e-12);
  double rest = 0;
  for (const Polygon2& p : subtract_convex({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{1, 1}, {3, 1}, {3, 3}, {1, 3}})) rest += signed_area(p);
  EXPECT_NEAR(rest, 12.0, 1e-12);
  // A ring: an outer loop and a hole; without holes: pieces of the same area, none clockwise.
  const std::vector<Polygon2> ring = {{{0, 0}, {5, 0}, {5, 1}, {0, 1}}, {{0, 4}, {5, 4}, {5, 5}, {0, 5}},
                                      {{0, 1}, {1, 1}, {1, 4}, {0, 4}}, {{4, 1}, {5, 1}, {5, 4}, {4, 4}}};
  const auto with_hole = union_outline(ring);
  EXPECT_EQ(with_hole.size(), 2u);
  double total = 0;
  for (const Polygon2& p : union_outline_without_holes(ring)) {
    EXPECT_GT(signed_area(p), 0);
    total += signed_area(p);
  }
  EXPECT_NEAR(total, 16.0, 1e-9);
  // Two holes in a 7 x 3 plate of unit tiles: joined at existing corners, three pieces, no new point.
  std::vector<Polygon2> plate;
  for (int x = 0; x < 7; ++x)
    for (int y = 0; y < 3; ++y)
      if (!(y == 1 && (x == 1 || x == 4))) plate.push_back({{x, y}, {x + 1.0, y}, {x + 1.0, y + 1.0}, {x, y + 1.0}});
  const auto pieces = union_outline_without_holes(plate);
  EXPECT_EQ(pieces.size(), 3u);
  total = 0;
  for (const Polygon2& p : pieces) {
    EXPECT_GT(signed_area(p), 0);
    total += signed_area(p);
    for (const Vec2& v : p) EXPECT_EQ(v, Vec2(std::round(v.x()), std::round(v.y()))) << "a new point";
  }
  EXPECT_NEAR(total, 19.0, 1e-9);
}

TEST(Lod2Kinds, NamesWeightsAndChecks) {
  for (int k = 0; k < kLod2KindCount; ++k)
    EXPECT_EQ(parse_lod2_kind(lod2_kind_name(static_cast<Lod2Kind>(k))), static_cast<Lod2Kind>(k));
  const Lod2KindWeights w = parse_lod2_kind_weights("gabled:3,shed");
  EXPECT_EQ(w[Lod2Kind::Gabled], 3.0);
  EXPECT_EQ(w[Lod2Kind::Shed], 1.0);
  EXPECT_EQ(w[Lod2Kind::Flat], 0.0);
  for (double u : {0.0, 0.5, 0.74, 0.76, 0.999}) EXPECT_EQ(w.pick(u), u < 0.75 ? Lod2Kind::Gabled : Lod2Kind::Shed);
  EXPECT_THROW(parse_lod2_kind_weights("castle"), std::invalid_argument);
  EXPECT_THROW(parse_lod2_kind_weights("flat:-1"), std::invalid_argument);
  EXPECT_THROW(parse_lod2_kind_weights("flat:0"), std::invalid_argument);
  Lod2Options o;
  o.max_attempts = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

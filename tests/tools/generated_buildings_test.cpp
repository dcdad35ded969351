// A 3 m shed and a 40 m tower from the procedural generator go through the whole raster lc2wf-dataset
// path: their clouds carry GT wireframes with the generated junction and edge counts, and line segments on
// those edges. No step may assume Roof-Image's 7-9 m heights.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/geometry/building.h"
#include "dataset/geometry/mesh_augmentation.h"
#include "dataset/synthetic/block_assembly.h"
#include "dataset/synthetic/lod2_generator.h"
#include "dataset/synthetic/roof_shapes.h"
#include "tests/common/run_cli.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

TEST(GeneratedBuildings, ShedAndTowerBecomeLabelledClouds) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("lc2wf_generated_clouds_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "meshes");
  const PolyMesh shed = assemble_blocks({shed_block({0, 0, 5, 4}, Side::South, 2.4, 0.15)});  // 3.0 m
  Lod2Options plain;
  plain.turn = false;
  const PolyMesh tower =
      augment_mesh(generate_lod2_building(Lod2Kind::Tower, 11, plain).mesh, MeshAugmentation{40.0, 1.0, 1.0, 0.6});
  const UnitTransform raw{kRawUnitsPerMetre, Vec3::Zero()};
  write_polyshape(dir / "meshes" / "shed.polyshape", shed, &raw);
  write_polyshape(dir / "meshes" / "tower.polyshape", tower, &raw);
  const auto r = testing::run_argv({LC2WF_DATASET_EXE, "--meshes", (dir / "meshes").string(), "--out", (dir / "out").string(),
                                    "--renderer", "raster", "--views", "12", "-j", "1", "-q"});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  for (const auto& [name, mesh, height] : {std::tuple{"shed", shed, 3.0}, std::tuple{"tower", tower, 40.0}}) {
    const LineCloud cloud = read_line_cloud(dir / "out" / "clouds" / (std::string(name) + ".lcloud"));
    const Wireframe wf = build_wireframe(mesh);
    EXPECT_EQ(cloud.wireframe.junctions.size(), mesh.vertices.size()) << name;
    EXPECT_EQ(cloud.wireframe.edges.size(), wf.edges.size()) << name;
    double top = 0;
    for (const Vec3& j : cloud.wireframe.junctions) top = std::max(top, j.z());
    EXPECT_NEAR(top, height, 1e-3) << name;
    ASSERT_GT(cloud.segments.size(), 20u) << name;
    ASSERT_EQ(cloud.labels.size(), cloud.segments.size()) << name;
    int on_edges = 0;
    for (const SegmentLabel& l : cloud.labels) on_edges += l.f == 1;
    EXPECT_GT(on_edges, 10) << name;
  }
  const auto summary = nlohmann::json::parse(std::ifstream(dir / "out" / "summary.json"));
  EXPECT_EQ(summary["done"], 2);
  EXPECT_GT(summary["gt_edge_coverage_by_positives"]["mean"].get<double>(), 0.5);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf

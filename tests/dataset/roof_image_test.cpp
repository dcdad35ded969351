// Every Roof-Image building: parse, check, import; counts against the published dataset statistics
// (3,583 buildings; vertices 9 / 20 / 70, faces 9 / 16 / 51 min / median / max).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>

#include "dataset/geometry/building.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/splits/splits.h"
#include "test_util.h"

namespace lc2wf {
namespace {

struct Stats {
  std::vector<int> vertices, faces, roof_faces, edges;
  std::vector<std::string> duplicate, near_duplicate, non_manifold, non_planar;
  std::map<std::string, int> prefixes;
  int imported = 0, merged_vertices = 0, dropped_faces = 0, non_manifold_after = 0, non_planar_after = 0;
};

double median(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double mean(const std::vector<int>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }

// The release's GT definition on the published test split: the totals behind every Table 2 number.
TEST(RoofImage, TestSplitGroundTruthTotals) {
  const auto dir = test::shared_data_dir() / "roof-image" / "res_building";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "Roof-Image data not found at " << dir << " (set LC2WF_DATA_DIR)";
  const auto names = read_name_list(std::filesystem::path(LC2WF_SOURCE_DIR) / "configs" / "splits" / "test.txt");
  ASSERT_EQ(names.size(), 757u);
  size_t vertices = 0, edges = 0, repaired_vertices = 0, repaired_edges = 0;
  BuildingOptions repaired;
  repaired.gt_after_repair = true;
  for (const auto& name : names) {
    const Building b = load_roof_image_building(dir / (name + ".polyshape"));
    vertices += b.wireframe.junctions.size();
    edges += b.wireframe.edges.size();
    const Building r = load_roof_image_building(dir / (name + ".polyshape"), repaired);
    repaired_vertices += r.wireframe.junctions.size();
    repaired_edges += r.wireframe.edges.size();
  }
  EXPECT_EQ(vertices, 15883u);
  EXPECT_EQ(edges, 26804u);
  EXPECT_EQ(repaired_vertices, 15873u);  // 5 mm duplicates merged: the option, not the default
  EXPECT_EQ(repaired_edges, 26789u);
}

TEST(RoofImage, AllBuildingsMatchPublishedStatistics) {
  const auto dir = test::shared_data_dir() / "roof-image" / "res_building";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "Roof-Image data not found at " << dir << " (set LC2WF_DATA_DIR)";
  const auto names = list_polyshape_names(dir);
  ASSERT_EQ(names.size(), 3583u);
  Stats s;
  for (const auto& name : names) {
    const auto path = dir / (name + ".polyshape");
    const PolyMesh raw = read_polyshape(path);
    const MeshReport r = analyse_mesh(raw, 0.0075);  // raw units: the 2 duplicates are < 0.0055 apart
    s.vertices.push_back(static_cast<int>(raw.vertices.size()));
    s.faces.push_back(static_cast<int>(raw.faces.size()));
    s.roof_faces.push_back(r.roof_faces);
    s.edges.push_back(r.unique_edges);
    if (r.duplicate_vertex_pairs > 0) s.duplicate.push_back(name);
    if (analyse_mesh(raw, 0.1).duplicate_vertex_pairs > 0) s.near_duplicate.push_back(name);  // the 5 mm default
    if (r.non_manifold_edges > 0) s.non_manifold.push_back(name);
    if (r.max_planarity_deviation > 1.0) s.non_planar.push_back(name);  // 1 raw = 5 cm
    ++s.prefixes[name.substr(0, 4)];
    const Building b = make_building(name, raw);
    EXPECT_EQ(b.wireframe.junctions.size(), raw.vertices.size());  // the release's GT: every polyshape vertex
    EXPECT_EQ(static_cast<int>(b.wireframe.edges.size()), r.unique_edges);
    s.merged_vertices += b.issues.merged_vertices;
    s.dropped_faces += b.issues.dropped_faces;
    s.non_manifold_after += b.issues.non_manifold_edges > 0;
    s.non_planar_after += b.issues.non_planar;
    ++s.imported;
  }
  EXPECT_EQ(s.imported, 3583);
  EXPECT_EQ(*std::min_element(s.vertices.begin(), s.vertices.end()), 9);
  EXPECT_EQ(median(s.vertices), 20);
  EXPECT_EQ(*std::max_element(s.vertices.begin(), s.vertices.end()), 70);
  EXPECT_NEAR(mean(s.vertices), 21.1, 0.05);
  EXPECT_EQ(*std::min_element(s.faces.begin(), s.faces.end()), 9);
  EXPECT_EQ(median(s.faces), 16);
  EXPECT_EQ(*std::max_element(s.faces.begin(), s.faces.end()), 51);
  EXPECT_NEAR(mean(s.faces), 16.4, 0.05);
  EXPECT_EQ(*std::min_element(s.roof_faces.begin(), s.roof_faces.end()), 2);
  EXPECT_EQ(median(s.roof_faces), 7);
  EXPECT_EQ(*std::max_element(s.roof_faces.begin(), s.roof_faces.end()), 22);
  EXPECT_EQ(*std::min_element(s.edges.begin(), s.edges.end()), 16);
  EXPECT_EQ(median(s.edges), 35);
  EXPECT_EQ(*std::max_element(s.edges.begin(), s.edges.end()), 119);
  EXPECT_NEAR(mean(s.edges), 35.5, 0.05);
  EXPECT_EQ(s.non_manifold.size(), 17u);
  EXPECT_EQ(s.duplicate, (std::vector<std::string>{"CG10_500_039070_0001", "CG10_500_043070_0023"}));
  EXPECT_EQ(s.near_duplicate.size(), 20u);
  EXPECT_EQ(s.merged_vertices, 48);
  EXPECT_EQ(s.dropped_faces, 24);
  EXPECT_EQ(s.non_manifold_after, 17);  // T-junction edges survive the merge; kept (harmless for wireframes)
  EXPECT_EQ(s.non_planar_after, 1);     // kept by the default policy, with a warning
  EXPECT_EQ(s.non_planar, (std::vector<std::string>{"BK39_500_017028_00107"}));
  EXPECT_EQ(s.prefixes["CG10"], 2495);
  EXPECT_EQ(s.prefixes["BK39"], 1057);
  EXPECT_EQ(s.prefixes["BJ39"], 31);
  std::cout << "[ stats    ] buildings with merged vertices " << s.near_duplicate.size() << ", merged vertices " << s.merged_vertices << ", dropped degenerate faces "
            << s.dropped_faces << ", non-manifold buildings " << s.non_manifold.size() << " (after repair "
            << s.non_manifold_after << "), non-planar kept " << s.non_planar_after << "\n";
}

}  // namespace
}  // namespace lc2wf

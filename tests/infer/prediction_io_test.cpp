#include "infer/prediction_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dataset/formats/errors.h"
#include "infer/eval_inputs.h"
#include "test_files.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

ScoredWireframe triangle() {
  ScoredWireframe p;
  p.wireframe.junctions = {{0, 0, 0}, {3, 0, 0}, {3, 4, 0.5}};
  p.wireframe.edges = {{1, 2}, {0, 1}, {0, 2}};
  p.junction_scores = {.9, .8, .7};
  p.edge_scores = {.6, .5, .4};
  return p;
}

void expect_near(const ScoredWireframe& a, const ScoredWireframe& b) {
  ASSERT_EQ(a.wireframe.junctions.size(), b.wireframe.junctions.size());
  for (size_t k = 0; k < a.wireframe.junctions.size(); ++k)
    EXPECT_LT((a.wireframe.junctions[k] - b.wireframe.junctions[k]).norm(), 1e-6);
  EXPECT_EQ(a.wireframe.edges, b.wireframe.edges);
  EXPECT_EQ(a.junction_scores, b.junction_scores);
  EXPECT_EQ(a.edge_scores, b.edge_scores);
}

TEST(PredictionIo, RoundTripInMetresAndRawUnits) {
  testing::ScratchDir dir("pred_io");
  write_prediction(dir.path(), "m", triangle(), {"note"});
  expect_near(read_prediction(dir.path() / "m.obj"), triangle());
  EXPECT_EQ(parse_scores_json(testing::read_text(dir.path() / "m.json"), "m.json").notes,
            std::vector<std::string>{"note"});
  UnitTransform raw{20.0, {100, -50, 0}};
  write_prediction(dir.path(), "r", triangle(), {}, &raw);
  EXPECT_THAT(testing::read_text(dir.path() / "r.obj"), HasSubstr("v 100 -50 0"));
  expect_near(read_prediction(dir.path() / "r.obj", &raw), triangle());
}

// Regression: a cloud's `name` field named the output files, so "../x", an absolute path or NUL wrote
// outside the output folder. The writer now takes plain file names only.
TEST(PredictionIo, NamesThatLeaveTheFolderAreRefused) {
  testing::ScratchDir dir("pred_names");
  for (const std::string& name : std::vector<std::string>{"../x", "/tmp/x", ".", "..", "", std::string("a\0b", 3), "a/b"})
    EXPECT_THROW(write_prediction(dir.path() / "out", name, triangle(), {}), std::invalid_argument) << name;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.obj"));
  EXPECT_NO_THROW(write_prediction(dir.path() / "out", ".hidden name", triangle(), {}));
}

TEST(PredictionIo, WithoutSidecarEveryScoreIsOne) {
  testing::ScratchDir dir("pred_nosidecar");
  testing::write_text(dir.path() / "a.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2 3\n");
  const ScoredWireframe p = read_prediction(dir.path() / "a.obj");
  EXPECT_EQ(p.wireframe.edges, (std::vector<std::array<int, 2>>{{0, 1}, {1, 2}}));
  EXPECT_EQ(p.junction_scores, (std::vector<double>{1, 1, 1}));
  EXPECT_EQ(p.edge_scores, (std::vector<double>{1, 1}));
}

TEST(PredictionIo, BadFilesNameTheFile) {
  testing::ScratchDir dir("pred_bad");
  testing::write_text(dir.path() / "a.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  auto expect_error = [&](const std::string& json, const std::string& what) {
    testing::write_text(dir.path() / "a.json", json);
    try {
      read_prediction(dir.path() / "a.obj");
      FAIL() << "accepted " << json;
    } catch (const DataError& e) {
      const std::string msg = e.what();
      EXPECT_THAT(msg, HasSubstr("a.json")) << msg;
      EXPECT_THAT(msg, HasSubstr(what)) << msg;
    }
  };
  expect_error("{\"format\": \"lc2wf-wireframe-scores\", \"version\": 1, \"edge_scores\": [0.5, 0.2]}", "edge scores");
  expect_error("{\"format\": \"lc2wf-wireframe-scores\", \"version\": 1, \"junction_scores\": [1]}", "junction scores");
  expect_error("{\"format\": \"other\", \"version\": 1, \"edge_scores\": [1]}", "format");
  expect_error("{\"format\": \"lc2wf-wireframe-scores\", \"version\": 1, \"edge_scores\": [\"x\"]}", "finite");
  expect_error("[1, 2", "JSON");
  std::filesystem::remove(dir.path() / "a.json");
  testing::write_text(dir.path() / "f.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  EXPECT_THROW(read_prediction(dir.path() / "f.obj"), DataError);
}

TEST(EvalInputs, NameListSkipsCommentsAndRejectsDuplicates) {
  testing::ScratchDir dir("names");
  testing::write_text(dir.path() / "s.txt", "# test split\nCG10_a\n\n  BK39_b  \r\n");
  EXPECT_EQ(read_name_list(dir.path() / "s.txt"), (std::vector<std::string>{"CG10_a", "BK39_b"}));
  testing::write_text(dir.path() / "d.txt", "a\nb\na\n");
  try {
    read_name_list(dir.path() / "d.txt");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("d.txt:3")) << e.what();
  }
  EXPECT_THROW(read_name_list(dir.path() / "none.txt"), DataError);
}

TEST(EvalInputs, PolyshapeGroundTruthInMetres) {
  testing::ScratchDir dir("gt_poly");
  testing::write_text(dir.path() / "box.polyshape", testing::box_polyshape(40));
  GroundTruthSource src;
  src.dir = dir.path();
  const auto path = find_ground_truth(src, "box");
  ASSERT_TRUE(path.has_value());
  EXPECT_FALSE(find_ground_truth(src, "nothing").has_value());
  const GroundTruth gt = load_ground_truth(src, *path);
  EXPECT_EQ(gt.wireframe.junctions.size(), 8u);
  EXPECT_EQ(gt.wireframe.edges.size(), 12u);
  // 10 raw units long = 0.5 m; raw coordinates map back through the building's own transform.
  EXPECT_NEAR((gt.wireframe.junctions[0] - gt.wireframe.junctions[1]).norm(), 0.5, 1e-12);
  EXPECT_LT((gt.units.to_metres({40, 0, 4}) - gt.wireframe.junctions[0]).norm(), 1e-12);
  EXPECT_EQ(list_ground_truth_names(src), std::vector<std::string>{"box"});
  testing::write_text(dir.path() / "box.obj", "v 0 0 0\n");
  EXPECT_THROW(find_ground_truth(src, "box"), DataError);
}

TEST(EvalInputs, RawObjGroundTruthIsScaled) {
  testing::ScratchDir dir("gt_obj");
  testing::write_text(dir.path() / "t.obj", "v 0 0 0\nv 20 0 0\nv 20 40 0\nf 1 2 3\n");
  GroundTruthSource src;
  src.dir = dir.path();
  src.obj_units = CoordinateUnits::kRaw;
  const GroundTruth gt = load_ground_truth(src, dir.path() / "t.obj");
  EXPECT_EQ(gt.wireframe.edges.size(), 3u);
  EXPECT_NEAR(gt.wireframe.junctions[2].y(), 2.0, 1e-12);
}

}  // namespace
}  // namespace lc2wf

namespace lc2wf {
namespace {

TEST(EvalInputs, ReleaseLineCloudJsonGroundTruth) {
  testing::ScratchDir dir("gt_release");
  testing::write_text(dir.path() / "r.json", R"({"junc3DList": [[0, 0, 0], [20, 0, 0]], "label": [0, 1],
      "objGTJunc3D": [[0, 0, 0], [20, 0, 0], [20, 40, 0]], "line_idx": [[0, 1], [1, 2]]})");
  GroundTruthSource src;
  src.kind = GroundTruthSource::Kind::kLineCloudDir;
  src.dir = dir.path();
  const auto path = find_ground_truth(src, "r");
  ASSERT_TRUE(path.has_value());
  const GroundTruth gt = load_ground_truth(src, *path);
  ASSERT_EQ(gt.wireframe.junctions.size(), 3u);
  EXPECT_EQ(gt.wireframe.edges.size(), 2u);
  EXPECT_NEAR(gt.wireframe.junctions[2].y(), 2.0, 1e-12);  // 40 raw = 2 m
}

}  // namespace
}  // namespace lc2wf

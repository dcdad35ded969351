// lc2wf-eval --weights against mesh ground truth. It compares the predictions with the GT in one frame: a cloud whose metric
// frame is moved (its origin moved back the same amount, so its raw coordinates stay) scores what
// lc2wf-infer --units raw + lc2wf-eval --pred --units raw score for it. It scored 0 before: the predictions
// were taken to be in the GT mesh's frame (origin at its bounding-box centre).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "tests/common/run_cli.h"
#include "tests/common/tiny_weights.h"
#include "tests/infer/test_files.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

// The building's mesh back in its raw coordinates, as a Roof-Image polyshape (1-based ids, label last).
void write_raw_polyshape(const fs::path& path, const Building& b) {
  std::ofstream out(path);
  out.precision(17);
  out << "# Number of verts: " << b.mesh.vertices.size() << "\n# Number of faces: " << b.mesh.faces.size() << "\n";
  for (const Vec3& v : b.mesh.vertices) {
    const Vec3 raw = b.units.to_raw(v);
    out << raw.x() << "," << raw.y() << "," << raw.z() << "\n";
  }
  for (size_t f = 0; f < b.mesh.faces.size(); ++f) {
    for (int i : b.mesh.faces[f]) out << i + 1 << ",";
    out << static_cast<int>(b.mesh.labels[f]) << "\n";
  }
}

nlohmann::json metrics_of(const fs::path& out) { return nlohmann::json::parse(testing::read_text(out / "metrics.json")); }

testing::CliResult run(const std::string& args) { return testing::run_cli(args + " --quiet -j 1"); }

TEST(EvalFrame, ACloudMovedWithItsOriginScoresAlikeThroughWeightsAndPred) {
  testing::ScratchDir dir("eval_frame");
  const fs::path gt = dir.path() / "gt", data = dir.path() / "data", weights = dir.path() / "weights";
  fs::create_directories(gt), fs::create_directories(data);
  test::write_tiny_weights(weights, 16, /*connect_pairs=*/true);
  const Building b = make_random_building(11, "moved");
  write_raw_polyshape(gt / "moved.polyshape", b);
  // The cloud 37 m east of the GT's metric frame, its origin 37 m west: the same raw coordinates.
  LineCloud cloud = make_synthetic_line_cloud(b, 5);
  ASSERT_DOUBLE_EQ(cloud.units.raw_per_metre, b.units.raw_per_metre);
  const Vec3 shift(37.0, 0.0, 0.0);
  for (Segment3& s : cloud.segments) s = {s.a + shift, s.b + shift};
  for (Vec3& j : cloud.wireframe.junctions) j += shift;
  cloud.units.origin_raw -= shift * cloud.units.raw_per_metre;
  write_line_cloud(data / "moved.lcloud", cloud);
  // Every candidate junction and every edge: the random weights' confidences, offsets and places (no
  // corner there), and their pairs no line runs along (the facade rule of this partial capture), would
  // leave nothing to score.
  const std::string select = " --min-confidence 0 --max-offset 0 --corner-radius 0 --edge-support 0";
  const std::string eval = LC2WF_EVAL_BIN, infer = std::string(LC2WF_INFER_BIN) + select;

  const fs::path through_weights = dir.path() / "weights_eval";
  testing::CliResult r = run(eval + select + " --weights " + weights.string() + " --data " + data.string() + " --gt " + gt.string() +
                             " -o " + through_weights.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path raw_pred = dir.path() / "raw_pred", through_pred = dir.path() / "pred_eval";
  r = run(infer + " --weights " + weights.string() + " --units raw -o " + raw_pred.string() + " " + (data / "moved.lcloud").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run(eval + " --pred " + raw_pred.string() + " --gt " + gt.string() + " --units raw -o " + through_pred.string());
  ASSERT_EQ(r.code, 0) << r.err;

  const nlohmann::json w = metrics_of(through_weights), p = metrics_of(through_pred);
  ASSERT_GT(w["per_building"][0]["pred_vertices"].get<int>(), 0) << "an empty prediction would make this vacuous: "
                                                                 << testing::read_text(raw_pred / "moved.json");
  for (const char* key : {"vertex", "edge"})
    for (size_t k = 0; k < w[key].size(); ++k) {
      EXPECT_NEAR(w[key][k]["ap"].get<double>(), p[key][k]["ap"].get<double>(), 1e-9) << key << k;
      EXPECT_NEAR(w[key][k]["recall"].get<double>(), p[key][k]["recall"].get<double>(), 1e-9) << key << k;
    }
  const double wed = w["per_building"][0]["wed"]["total_dist"].get<double>();
  EXPECT_NEAR(wed, p["per_building"][0]["wed"]["total_dist"].get<double>(), 1e-6);

  // The frame matters here: the same predictions in the cloud's metres, read as if in the GT's frame, score
  // otherwise (what --weights did before).
  const fs::path metre_pred = dir.path() / "metre_pred", as_metres = dir.path() / "metres_eval";
  r = run(infer + " --weights " + weights.string() + " -o " + metre_pred.string() + " " + (data / "moved.lcloud").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run(eval + " --pred " + metre_pred.string() + " --gt " + gt.string() + " --units metres -o " + as_metres.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(std::abs(metrics_of(as_metres)["per_building"][0]["wed"]["total_dist"].get<double>() - wed), 1.0);
}

// A cloud that cannot be read is named on stderr (also with -q), scored as an empty wireframe among the
// others, and the run exits 1 (it stopped before scoring anything).
TEST(EvalFrame, AnUnreadableCloudIsNamedAndScoredEmpty) {
  testing::ScratchDir dir("eval_bad_cloud");
  const fs::path gt = dir.path() / "gt", data = dir.path() / "data", weights = dir.path() / "weights", out = dir.path() / "out";
  fs::create_directories(gt), fs::create_directories(data);
  test::write_tiny_weights(weights, 16, /*connect_pairs=*/true);
  const Building b = make_random_building(11, "good");
  write_raw_polyshape(gt / "good.polyshape", b);
  write_raw_polyshape(gt / "junk.polyshape", b);
  write_line_cloud(data / "good.lcloud", make_synthetic_line_cloud(b, 5));
  std::ofstream(data / "junk.lcloud") << "not a line cloud";
  const testing::CliResult r = run(std::string(LC2WF_EVAL_BIN) + " --weights " + weights.string() + " --data " + data.string() +
                                   " --gt " + gt.string() + " -o " + out.string());
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("skipping " + (data / "junk.lcloud").string() + ": ")) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("have no prediction in " + (out / "predictions").string() + " (scored as empty): 'junk'"))
      << r.err;
  const nlohmann::json m = metrics_of(out);
  EXPECT_EQ(m["buildings"], 2);
  EXPECT_EQ(m["missing_predictions"], nlohmann::json::array({"junk"}));
}

}  // namespace
}  // namespace lc2wf

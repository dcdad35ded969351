// Runs the lc2wf-eval binary on small generated cases.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "dataset/geometry/building.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "infer/prediction_io.h"
#include "test_files.h"
#include "tests/common/run_cli.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

using testing::CliResult;

CliResult run_eval(const fs::path&, const std::string& args) {
  return testing::run_cli(std::string(LC2WF_EVAL_BIN) + " " + args);
}

// The box of testing::box_polyshape(x0) as a raw-unit prediction with all 12 edges.
std::string box_prediction_raw(double x0) {
  std::string s;
  for (int z : {4, 0})
    for (auto [x, y] : {std::pair{0, 0}, {10, 0}, {10, 6}, {0, 6}})
      s += "v " + std::to_string(x0 + x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
  s += "l 1 2 3 4 1\nl 5 6 7 8 5\nl 1 5\nl 2 6\nl 3 7\nl 4 8\n";
  return s;
}

TEST(EvalCli, HelpAndUsageErrors) {
  testing::ScratchDir dir("cli_usage");
  const CliResult help = run_eval(dir.path(), "--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_THAT(help.out, HasSubstr("Usage: lc2wf-eval"));
  for (const char* flag : {"--html", "--html-compare"}) EXPECT_THAT(help.out, HasSubstr(flag)) << flag;
  const CliResult none = run_eval(dir.path(), "--pred " + dir.path().string() + " --out x");
  EXPECT_EQ(none.code, 2);
  EXPECT_THAT(none.err, HasSubstr("--gt"));
  const CliResult bad = run_eval(dir.path(), "--bogus");
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--bogus"));
  const CliResult units = run_eval(dir.path(), "--pred . --gt . --out x --units feet");
  EXPECT_EQ(units.code, 2);
  const CliResult precision = run_eval(dir.path(), "--pred . --gt . --out x --precision bf16");
  EXPECT_EQ(precision.code, 2);
  EXPECT_THAT(precision.err, HasSubstr("--precision only apply with --weights"));
  for (const char* flag : {"--pair-support 0.1", "--min-confidence 0.5", "--nms-radius 0.5", "--max-offset 1"}) {
    const CliResult without_weights = run_eval(dir.path(), std::string("--pred . --gt . --out x ") + flag);
    EXPECT_EQ(without_weights.code, 2) << flag;
    EXPECT_THAT(without_weights.err, HasSubstr("only apply with --weights")) << flag;
  }
  const CliResult range = run_eval(dir.path(), "--weights . --data . --out x --pair-support 2");
  EXPECT_EQ(range.code, 2);
  EXPECT_THAT(range.err, HasSubstr("--pair-support must be in [0, 1]"));
}

TEST(EvalCli, PolyshapeGroundTruthRawPredictionsAndAMissingOne) {
  testing::ScratchDir dir("cli_poly");
  const fs::path gt = dir.path() / "gt", pred = dir.path() / "pred", out = dir.path() / "out";
  testing::write_text(gt / "b1.polyshape", testing::box_polyshape(100));
  testing::write_text(gt / "b2.polyshape", testing::box_polyshape(300));
  testing::write_text(pred / "b1.obj", box_prediction_raw(100));
  testing::write_text(dir.path() / "split.txt", "b1\nb2\n");
  const CliResult r = run_eval(dir.path(), "--pred " + pred.string() + " --gt " + gt.string() + " --split " +
                                         (dir.path() / "split.txt").string() + " --out " + out.string() +
                                         " --units raw --strict-wed --method box");
  ASSERT_EQ(r.code, 1) << r.err;  // scored, but one building had no prediction
  EXPECT_THAT(r.out, HasSubstr("| box | 50.0/50.0 |")) << r.out;
  // Exit 1 names what it skipped and where the name came from (it named neither before).
  EXPECT_THAT(r.err, HasSubstr("1 of 2 buildings listed in " + (dir.path() / "split.txt").string() + " have no prediction in " +
                               pred.string() + " (scored as empty): 'b2'"));
  const auto j = nlohmann::json::parse(testing::read_text(out / "metrics.json"));
  EXPECT_EQ(j["missing_predictions"], nlohmann::json::array({"b2"}));
  EXPECT_DOUBLE_EQ(j["vertex"][0]["ap"].get<double>(), 0.5);  // 8 of 16 GT vertices, all exact, scores 1
  EXPECT_DOUBLE_EQ(j["edge"][0]["recall"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["per_building"][0]["wed"]["total_num"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["wed_strict"]["add_vertex"].get<double>(), 4.0);
  const std::string csv = testing::read_text(out / "per_building.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
  EXPECT_THAT(testing::read_text(out / "metrics.md"), HasSubstr("Building3D"));
  EXPECT_THAT(j["building3d"]["frame"].get<std::string>(), HasSubstr("GT corners"));  // no line cloud
  EXPECT_DOUBLE_EQ(j["building3d"]["cr"].get<double>(), 0.5);  // b1's 8 corners exact, b2 missing
  // --html without three.js: exit 1 naming the package; nothing half-written.
  const CliResult html = testing::run_cli("LC2WF_THREE_JS_DIR=" + (dir.path() / "none").string() + " " +
                                          LC2WF_EVAL_BIN + " --pred " + pred.string() + " --gt " + gt.string() +
                                          " --out " + (dir.path() / "out_html").string() + " --units raw --html --quiet");
  EXPECT_EQ(html.code, 3);
  EXPECT_THAT(html.err, HasSubstr("libjs-three")) << html.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out_html" / "report.html"));
  // Read in metres instead, the raw coordinates are 20x too large: nothing matches.
  const CliResult metres = run_eval(dir.path(), "--pred " + pred.string() + " --gt " + gt.string() + " --out " +
                                              (dir.path() / "out_m").string() + " --quiet");
  ASSERT_EQ(metres.code, 1) << metres.err;  // b2 still has no prediction
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(testing::read_text(dir.path() / "out_m" / "metrics.json"))["vertex"][2]["ap"]
                       .get<double>(),
                   0.0);
}

TEST(EvalCli, LineCloudGroundTruthWithScores) {
  testing::ScratchDir dir("cli_cloud");
  const fs::path data = dir.path() / "data", pred = dir.path() / "pred", out = dir.path() / "out";
  LineCloud cloud;
  cloud.name = "c1";
  cloud.segments = {{{0, 0, 0}, {1, 0, 0}}};
  cloud.wireframe.junctions = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}};
  cloud.wireframe.edges = {{0, 1}, {1, 2}, {0, 2}};
  cloud.units.raw_per_metre = 20;
  fs::create_directories(data);
  write_line_cloud(data / "c1.lcl", cloud);
  // Two junctions exact, one 0.3 m off; the sidecar ranks the bad one lowest.
  testing::write_text(pred / "c1.obj", "v 0 0 0\nv 4 0 0\nv 4 3.3 0\nl 1 2 3 1\n");
  testing::write_text(pred / "c1.json", R"({"format": "lc2wf-wireframe-scores", "version": 1,
      "junction_scores": [0.9, 0.8, 0.1], "edge_scores": [0.9, 0.5, 0.4]})");
  const CliResult r = run_eval(dir.path(), "--pred " + pred.string() + " --data " + data.string() + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(testing::read_text(out / "metrics.json"));
  EXPECT_NEAR(j["vertex"][0]["ap"].get<double>(), 2.0 / 3.0, 1e-12);  // TP TP FP of 3
  EXPECT_NEAR(j["vertex"][2]["ap"].get<double>(), 1.0, 1e-12);        // 0.3 m < 0.35 m
  EXPECT_NEAR(j["edge"][0]["ap"].get<double>(), 1.0 / 3.0, 1e-12);    // 0.25 m: only the exact edge, TP FP FP
  EXPECT_NEAR(j["edge"][2]["ap"].get<double>(), 1.0, 1e-12);          // 0.50 m: the 0.3 m-off edges count
}

// A 10 x 6 x 4 m box photographed from one side only (a street capture): scored against the part its cameras
// saw, the four front edges it drew are most of what was there to find; against the whole box, a third.
TEST(EvalCli, GroundTruthSeenByTheCloudsCameras) {
  testing::ScratchDir dir("cli_seen");
  const fs::path data = dir.path() / "data", bare = dir.path() / "bare", pred = dir.path() / "pred";
  LineCloud cloud;
  cloud.name = "front";
  cloud.segments = {{{-5, 3, 0}, {5, 3, 0}}};
  Wireframe& w = cloud.wireframe;
  for (double z : {0.0, 4.0})
    for (auto [x, y] : {std::pair{-5.0, -3.0}, {5.0, -3.0}, {5.0, 3.0}, {-5.0, 3.0}}) w.junctions.push_back(Vec3(x, y, z));
  for (int k = 0; k < 4; ++k) w.edges.push_back({k, (k + 1) % 4}), w.edges.push_back({4 + k, 4 + (k + 1) % 4}), w.edges.push_back({k, 4 + k});
  Building b;
  b.mesh.vertices = w.junctions;
  CameraRingOptions ring;
  ring.num_views = 16;
  ring.elevation_deg = 5;
  const std::vector<Camera> all = make_camera_ring(b, ring);
  cloud.cameras.assign(all.begin() + 2, all.begin() + 7);  // azimuths 45-135 degrees: the +y side
  fs::create_directories(data);
  write_line_cloud(data / "front.lcl", cloud);
  testing::write_text(pred / "front.obj", "v -5 3 0\nv 5 3 0\nv 5 3 4\nv -5 3 4\nl 1 2 3 4 1\n");
  auto recall = [&](const std::string& extra, const std::string& tag) {
    const fs::path out = dir.path() / tag;
    const CliResult r = run_eval(dir.path(), "--pred " + pred.string() + " --data " + data.string() + " -o " + out.string() + extra);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(testing::read_text(out / "metrics.json"))["edge"][0]["recall"].get<double>();
  };
  const double whole = recall("", "whole"), seen = recall(" --gt-seen-by 2", "seen");
  EXPECT_NEAR(whole, 4.0 / 12.0, 1e-12);
  EXPECT_GT(seen, whole);
  EXPECT_LT(seen, 1.0);  // the side walls' edges were in view too (along them, from the end cameras)
  // A cloud without cameras cannot say what was seen; the ground truth of meshes carries no cameras.
  cloud.cameras.clear();
  fs::create_directories(bare);
  write_line_cloud(bare / "front.lcl", cloud);
  const CliResult no_cameras = run_eval(dir.path(), "--pred " + pred.string() + " --data " + bare.string() + " -o " +
                                                        (dir.path() / "bare-out").string() + " --gt-seen-by 2");
  EXPECT_EQ(no_cameras.code, 3);
  EXPECT_THAT(no_cameras.err, HasSubstr("no cameras"));
  const CliResult with_meshes = run_eval(dir.path(), "--pred " + pred.string() + " --gt " + data.string() + " -o x --gt-seen-by 2");
  EXPECT_EQ(with_meshes.code, 2);
  EXPECT_THAT(with_meshes.err, HasSubstr("--gt-seen-by"));
}

TEST(EvalCli, BadInputsAreDataErrorsNamingTheProblem) {
  testing::ScratchDir dir("cli_bad");
  const fs::path gt = dir.path() / "gt", pred = dir.path() / "pred";
  testing::write_text(gt / "b1.polyshape", testing::box_polyshape(0));
  testing::write_text(pred / "b1.obj", "v 0 0 zero\n");
  const std::string base = "--pred " + pred.string() + " --gt " + gt.string() + " --out " + (dir.path() / "o").string();
  const CliResult bad_pred = run_eval(dir.path(), base);
  EXPECT_EQ(bad_pred.code, 3);
  EXPECT_THAT(bad_pred.err, HasSubstr("b1.obj:1")) << bad_pred.err;
  testing::write_text(dir.path() / "split.txt", "b1\nghost\n");
  testing::write_text(pred / "b1.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  const CliResult no_gt = run_eval(dir.path(), base + " --split " + (dir.path() / "split.txt").string());
  EXPECT_EQ(no_gt.code, 3);
  EXPECT_THAT(no_gt.err, HasSubstr("no ground truth for building 'ghost' listed in " + (dir.path() / "split.txt").string() + ": no ghost.obj or ghost.polyshape in "));
  EXPECT_FALSE(fs::exists(dir.path() / "o" / "metrics.json"));
}

TEST(EvalCli, SpecialFilesAreRefusedByNameWithoutBlocking) {
  testing::ScratchDir dir("cli_special");
  const fs::path gt = dir.path() / "gt", pred = dir.path() / "pred", out = dir.path() / "o";
  fs::create_directories(gt);
  testing::write_text(pred / "b1.obj", box_prediction_raw(0));
  // A FIFO under a building's name in the GT folder: reported as "no buildings (folder is empty)" before.
  ASSERT_EQ(::mkfifo((gt / "b1.polyshape").c_str(), 0600), 0);
  const CliResult fifo = run_eval(dir.path(), "--pred " + pred.string() + " --gt " + gt.string() + " -o " + out.string());
  EXPECT_EQ(fifo.code, 3);
  EXPECT_THAT(fifo.err, HasSubstr((gt / "b1.polyshape").string() + ": is not a regular file"));
  fs::remove(gt / "b1.polyshape");
  testing::write_text(gt / "b1.polyshape", testing::box_polyshape(0));
  // --html-compare's metrics.json: a FIFO is refused before anything is read, a JSON array escaped as a
  // type error naming no file.
  const fs::path other = dir.path() / "other";
  fs::create_directories(other);
  ASSERT_EQ(::mkfifo((other / "metrics.json").c_str(), 0600), 0);
  const std::string html = "--pred " + pred.string() + " --gt " + gt.string() + " --units raw -o " + out.string() +
                           " --quiet --html --html-compare " + other.string();
  CliResult r = run_eval(dir.path(), html);
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr((other / "metrics.json").string() + ": is not a regular file"));
  fs::remove(other / "metrics.json");
  testing::write_text(other / "metrics.json", "[1, 2]");
  r = run_eval(dir.path(), html);
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr((other / "metrics.json").string() + ": not an lc2wf-eval metrics.json: expected a JSON object"));
}

// Regression: every prediction missing (a wrong --pred folder) was scored as empty and exited 0.
TEST(EvalCli, NoPredictionAtAllIsNothingEvaluated) {
  testing::ScratchDir dir("cli_none");
  const fs::path gt = dir.path() / "gt", pred = dir.path() / "pred", out = dir.path() / "out";
  testing::write_text(gt / "b1.polyshape", testing::box_polyshape(0));
  fs::create_directories(pred);
  const CliResult r = run_eval(dir.path(), "--pred " + pred.string() + " --gt " + gt.string() + " -o " + out.string() + " -q");
  EXPECT_EQ(r.code, 3);
  EXPECT_THAT(r.err, HasSubstr("nothing to evaluate: none of the 1 buildings ('b1') has a prediction in " + pred.string()));
  EXPECT_FALSE(fs::exists(out));
}

// Regression: --weights created OUT/predictions before the other arguments were checked.
TEST(EvalCli, NothingIsWrittenBeforeTheArgumentsAreValid) {
  testing::ScratchDir dir("cli_early");
  const fs::path out = dir.path() / "out";
  fs::create_directories(dir.path() / "weights");
  for (const std::string& args : {"--weights " + (dir.path() / "weights").string() + " --data " + (dir.path() / "none").string(),
                                  "--weights " + (dir.path() / "weights").string() + " --data " + dir.path().string() + " --ties odd",
                                  "--weights " + (dir.path() / "weights").string() + " --data " + dir.path().string()}) {
    const CliResult r = run_eval(dir.path(), args + " -o " + out.string() + " -q");
    EXPECT_NE(r.code, 0) << args;
    EXPECT_FALSE(fs::exists(out)) << args << ": " << r.err;
  }
}

fs::path shared_data_dir() {
  if (const char* env = std::getenv("LC2WF_DATA_DIR"); env && *env) return env;
  return LC2WF_SHARED_DATA_DIR;
}

TEST(EvalCli, RealBuildingsPredictedByTheirOwnGroundTruthScorePerfectly) {
  const fs::path src = shared_data_dir() / "roof-image" / "res_building";
  if (!fs::is_directory(src)) GTEST_SKIP() << "Roof-Image data not found at " << src << " (set LC2WF_DATA_DIR)";
  testing::ScratchDir dir("cli_real");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(src))
    if (e.path().extension() == ".polyshape") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 25u);
  files.resize(25);
  // Each prediction is the building's GT wireframe written back in raw units through its own transform.
  fs::create_directories(dir.path() / "gt");
  for (const fs::path& f : files) {
    fs::copy_file(f, dir.path() / "gt" / f.filename());
    const Building b = load_roof_image_building(f);
    write_prediction(dir.path() / "pred", b.name, ScoredWireframe::with_unit_scores(b.wireframe), {}, &b.units);
  }
  const CliResult r = run_eval(dir.path(), "--pred " + (dir.path() / "pred").string() + " --gt " +
                                               (dir.path() / "gt").string() + " --out " + (dir.path() / "out").string() +
                                               " --units raw --strict-wed --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(testing::read_text(dir.path() / "out" / "metrics.json"));
  EXPECT_EQ(j["buildings"], 25);
  for (const char* k : {"vertex", "edge"})
    for (const auto& t : j[k]) {
      EXPECT_DOUBLE_EQ(t["ap"].get<double>(), 1.0) << k;
      EXPECT_DOUBLE_EQ(t["recall"].get<double>(), 1.0) << k;
    }
  // The release's sqrt(raw distance) turns the OBJ writer's ~1e-7 raw rounding into ~1e-5 m per vertex.
  EXPECT_EQ(j["wed"]["total_num"].get<double>(), 0.0);
  EXPECT_LT(j["wed"]["total_dist"].get<double>(), 1e-2);
  EXPECT_EQ(j["wed_strict"]["total_num"].get<double>(), 0.0);
  EXPECT_LT(j["wed_strict"]["total_dist"].get<double>(), 1e-6);
}

}  // namespace
}  // namespace lc2wf

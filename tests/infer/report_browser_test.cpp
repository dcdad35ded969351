// lc2wf-eval --html opened in a real browser: headless Chromium loads the report of a small evaluation
// (synthetic line clouds, predictions with matched, shifted, missing and spurious edges) through
// tools/report/check_report.py; no console errors, a 3D view that is not blank, faces drawn and toggled, a table
// that sorts.
// Skipped, with a message, where Chromium is not installed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "infer/prediction_io.h"
#include "test_files.h"
#include "tests/common/run_cli.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

std::string chromium_path() {
  if (const char* env = std::getenv("LC2WF_CHROMIUM"); env && *env) return env;
  return "/usr/bin/chromium";
}

// The GT with its first edge missing, its second moved to a junction 1 m off, and a spurious edge from
// junction 0 to that junction; scores decreasing.
ScoredWireframe imperfect_prediction(const Wireframe& gt) {
  ScoredWireframe p;
  p.wireframe = gt;
  const int moved = static_cast<int>(gt.junctions.size());
  p.wireframe.junctions.push_back(gt.junctions[gt.edges[1][0]] + Vec3(1, 0, 0));
  p.wireframe.edges.erase(p.wireframe.edges.begin());
  p.wireframe.edges[0] = {gt.edges[1][1], moved};
  p.wireframe.edges.push_back({0, moved});
  for (size_t j = 0; j < p.wireframe.junctions.size(); ++j) p.junction_scores.push_back(0.99 - 0.01 * j);
  for (size_t e = 0; e < p.wireframe.edges.size(); ++e) p.edge_scores.push_back(0.98 - 0.02 * e);
  return p;
}

TEST(ReportBrowser, ChromiumLoadsSortsAndRendersTheReport) {
  if (!fs::exists(chromium_path()))
    GTEST_SKIP() << "Chromium not found at " << chromium_path()
                 << ": apt-get install chromium (tools/setup-deps.sh) or set LC2WF_CHROMIUM to run the browser test";
  testing::ScratchDir dir("browser");
  const fs::path clouds = dir.path() / "clouds", pred = dir.path() / "pred", out = dir.path() / "out";
  for (int k = 0; k < 4; ++k) {
    const std::string name = "synth_" + std::to_string(k);
    const Building b = make_random_building(100 + k, name);
    write_line_cloud(clouds / (name + ".lcloud"), make_synthetic_line_cloud(b, 7 + k));
    if (k < 3) write_prediction(pred, name, imperfect_prediction(b.wireframe));  // synth_3: no prediction
  }
  // A first run to compare with (as the --release-quirks run would be), then the report.
  const std::string common = std::string(LC2WF_EVAL_BIN) + " --pred " + pred.string() + " --data " + clouds.string();
  const testing::CliResult base = testing::run_cli(common + " --out " + (dir.path() / "base").string() + " --method baseline-run --quiet");
  ASSERT_EQ(base.code, 1) << base.err;  // synth_3 has no prediction: scored as empty, exit 1
  const testing::CliResult eval = testing::run_cli(common + " --out " + out.string() + " --html --html-compare " +
                                                   (dir.path() / "base").string() + " --quiet");
  ASSERT_EQ(eval.code, 1) << eval.err;
  ASSERT_TRUE(fs::exists(out / "report.html"));
  EXPECT_THAT(testing::read_text(out / "report.html"), HasSubstr("baseline-run"));
  const testing::CliResult usage = testing::run_cli(common + " --out " + out.string() + " --html-compare " + out.string());
  EXPECT_EQ(usage.code, 2);
  EXPECT_THAT(usage.err, HasSubstr("--html-compare")) << usage.err;

  const testing::CliResult check = testing::run_cli("python3 " + std::string(LC2WF_SOURCE_DIR) +
                                                    "/tools/report/check_report.py --chromium " + chromium_path() + " " +
                                                    (out / "report.html").string());
  ASSERT_EQ(check.code, 0) << check.err;
  const nlohmann::json r = nlohmann::json::parse(check.out);
  EXPECT_TRUE(r["console_errors"].empty()) << r["console_errors"].dump(1);
  EXPECT_EQ(r["buildings"], 4);
  EXPECT_LT(r["open_seconds"].get<double>(), 20.0);
  // The report opens on the worst building by WED: synth_3, which has no prediction (cloud and GT only).
  EXPECT_EQ(r["rendered"], "synth_3");
  const nlohmann::json& first = r["canvas"];
  EXPECT_GT(first["ink"].get<double>(), 0.002) << first.dump();
  EXPECT_GT(first["green"].get<double>(), 0.0002) << first.dump();
  EXPECT_GT(first["grey"].get<double>(), 0.0002) << first.dump();
  EXPECT_EQ(first["red"].get<double>(), 0.0) << first.dump();
  // A building with a prediction: red lines too.
  const nlohmann::json& c = r["canvas_after_click"];
  EXPECT_GT(c["ink"].get<double>(), 0.002) << c.dump();
  EXPECT_GT(c["red"].get<double>(), 0.0002) << c.dump();
  EXPECT_GT(c["green"].get<double>(), 0.0002) << c.dump();
  EXPECT_GT(c["grey"].get<double>(), 0.0002) << c.dump();
  // Faces: none for synth_3 (no prediction); the clicked building's faces drawn as translucent polygons (walls
  // blue), gone when toggled off; section (d) for this run and the compared one.
  EXPECT_EQ(r["faces_first"], 0);
  EXPECT_GT(r["faces_after_click"].get<int>(), 0);
  EXPECT_GT(c["blue"].get<double>(), 0.0002) << c.dump();
  EXPECT_LT(r["canvas_faces_off"]["blue"].get<double>(), 0.2 * c["blue"].get<double>()) << r["canvas_faces_off"].dump();
  EXPECT_GT(r["canvas_faces_off"]["red"].get<double>(), 0.0002) << r["canvas_faces_off"].dump();
  EXPECT_EQ(r["face_summary_rows"], 2);
  // Sorting: name ascending, then descending; edge recall worst first (ascending).
  const auto names1 = r["order_name_1"].get<std::vector<std::string>>();
  const auto names2 = r["order_name_2"].get<std::vector<std::string>>();
  EXPECT_EQ(names1, (std::vector<std::string>{"synth_0", "synth_1", "synth_2", "synth_3"}));
  EXPECT_EQ(names2, (std::vector<std::string>{"synth_3", "synth_2", "synth_1", "synth_0"}));
  EXPECT_EQ(r["sort_sR"], "sR asc");
  const auto recall = r["column_sR"].get<std::vector<double>>();
  EXPECT_TRUE(std::is_sorted(recall.begin(), recall.end())) << r["column_sR"].dump();
  EXPECT_EQ(recall.front(), 0.0);  // synth_3 has no prediction
  EXPECT_NE(r["rendered_after_click"], r["rendered"]);
  EXPECT_EQ(r["summary_rows"], 2);  // this run and the compared one
  // Coloured by score (viridis; faces still off), the prediction's red gives way to other hues; the GT stays.
  const nlohmann::json& scored = r["canvas_by_score"];
  EXPECT_LT(scored["red"].get<double>(), 0.5 * r["canvas_faces_off"]["red"].get<double>()) << scored.dump();
  EXPECT_GT(scored["green"].get<double>(), 0.0002) << scored.dump();
}

}  // namespace
}  // namespace lc2wf

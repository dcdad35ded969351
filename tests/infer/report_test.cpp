// The HTML report's pieces: per-element match status, the geometry block and the page assembly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>

#include "model/ap_metric.h"
#include "infer/html_report.h"
#include "infer/match_status.h"
#include "infer/report_geometry.h"
#include "test_files.h"

using ::testing::HasSubstr;
using ::testing::Not;

namespace lc2wf {
namespace {

Wireframe two_edges() {
  Wireframe w;
  w.junctions = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}};
  w.edges = {{0, 1}, {1, 2}};
  return w;
}

ScoredWireframe predicted() {
  ScoredWireframe p;
  // Edge 0 = GT edge 0 shifted 0.1 m; edge 1 spurious; edge 2 = GT edge 0 again (duplicate, lower score).
  p.wireframe.junctions = {{0.1, 0, 0}, {4.1, 0, 0}, {0, 3, 0}, {0, 0, 0}, {4, 0, 0}};
  p.wireframe.edges = {{0, 1}, {1, 2}, {3, 4}};
  p.junction_scores = {0.9, 0.8, 0.7, 0.6, 0.5};
  p.edge_scores = {0.9, 0.8, 0.4};
  return p;
}

TEST(MatchStatus, MarksTheElementsTheMetricCounts) {
  const std::vector<double> eta{0.15, 0.5};
  const MatchStatus e = edge_match_status(predicted(), two_edges(), eta, 0.0);
  // At 0.15 m the 0.2 m-off edge 0 misses; the duplicate (exact) then takes GT edge 0. At 0.5 m edge 0 wins.
  EXPECT_EQ(e.pred, (std::vector<uint8_t>{0b10, 0b00, 0b01}));
  EXPECT_EQ(e.gt, (std::vector<uint8_t>{0b11, 0b00}));
  const MatchStatus j = junction_match_status(predicted(), two_edges(), eta, 0.0);
  EXPECT_EQ(j.pred, (std::vector<uint8_t>{0b11, 0b11, 0b00, 0b00, 0b00}));
  EXPECT_EQ(j.gt, (std::vector<uint8_t>{0b11, 0b11, 0b00}));
  // Same counts as the metric itself.
  for (size_t t = 0; t < eta.size(); ++t) {
    int tp = 0;
    for (const RankedHit& h : match_edges(predicted(), two_edges(), eta[t])) tp += h.true_positive;
    int bits = 0;
    for (uint8_t b : e.pred) bits += (b >> t) & 1;
    EXPECT_EQ(bits, tp) << "threshold " << eta[t];
  }
}

TEST(ReportGeometry, Base64) {
  EXPECT_EQ(base64_encode("Man"), "TWFu");
  EXPECT_EQ(base64_encode("Ma"), "TWE=");
  EXPECT_EQ(base64_encode("M"), "TQ==");
  EXPECT_EQ(base64_encode(""), "");
}

TEST(ReportGeometry, BlockSizeFollowsTheLayoutAndTheCloudCap) {
  const ScoredWireframe p = predicted();
  const Wireframe gt = two_edges();
  const std::vector<Segment3> cloud(10, Segment3{{0, 0, 0}, {1, 1, 1}});
  ReportGeometryInput in;
  in.pred = &p, in.gt = &gt, in.cloud = &cloud;
  in.junctions = junction_match_status(p, gt, {0.15}, 0.0);
  in.edges = edge_match_status(p, gt, {0.25}, 0.0);
  in.vertex_thresholds = in.edge_thresholds = 1;
  // 44 header + 4 cloud segs * 12 + (5 + 3) junctions * 6 + (3 + 2) edges * 4 + scores 5 + 3 + bits 5 + 3 + 3 + 2.
  const size_t bytes = 44 + 4 * 12 + 8 * 6 + 5 * 4 + 8 + 13;
  EXPECT_EQ(encode_report_geometry(in, 4).size(), (bytes + 2) / 3 * 4);
}

TEST(HtmlReport, OneSelfContainedPageWithABlockPerBuilding) {
  testing::ScratchDir dir("html");
  testing::write_text(dir.path() / "three" / "three.min.js", "var THREE_STUB = 1;");
  testing::write_text(dir.path() / "three" / "examples" / "js" / "controls" / "OrbitControls.js", "var ORBIT_STUB = 1;");
  HtmlReport html(HtmlReportOptions{dir.path() / "three"});
  Evaluator ev(EvalOptions{});
  const Wireframe gt = two_edges();
  for (const char* name : {"a", "b</script><b>"}) {
    ev.add(name, predicted(), gt);
    html.add(predicted(), gt, {}, EvalOptions{});
  }
  const EvalReport report = ev.report();
  const std::string page = html.html(report, "m", nullptr, {}, {});
  EXPECT_THAT(page, HasSubstr("THREE_STUB"));
  EXPECT_THAT(page, HasSubstr("ORBIT_STUB"));
  EXPECT_THAT(page, HasSubstr("id=\"g1\""));
  EXPECT_THAT(page, Not(HasSubstr("id=\"g2\"")));
  EXPECT_THAT(page, Not(HasSubstr("b</script><b>")));  // the name cannot close the data element
  EXPECT_THAT(page, HasSubstr("b<\\/script><b>"));
  EXPECT_THAT(page, Not(HasSubstr("src=\"http")));     // nothing loaded from the network
  const auto path = write_html_report(dir.path() / "out", html, report, "m", nullptr, {}, {});
  EXPECT_EQ(testing::read_text(path), page);
  EXPECT_THROW(HtmlReport(HtmlReportOptions{dir.path() / "missing"}), std::runtime_error);
}

TEST(HtmlReport, FacesOfThePredictionAndSectionDGoIntoThePage) {
  testing::ScratchDir dir("html_faces");
  testing::write_text(dir.path() / "three" / "three.min.js", "var THREE_STUB = 1;");
  testing::write_text(dir.path() / "three" / "examples" / "js" / "controls" / "OrbitControls.js", "var ORBIT_STUB = 1;");
  HtmlReport html(HtmlReportOptions{dir.path() / "three"});
  Evaluator ev(EvalOptions{});
  const Wireframe gt = two_edges();
  SurfaceModel square;
  square.vertices = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1.0006}};
  square.faces = {{{0, 1, 2}, SurfaceLabel::kWall}};
  square.status = ShellStatus::kOpenSurfaces;
  FaceReport faces;
  faces.gt_has_faces = false;
  for (const char* name : {"with_faces", "without"}) {
    ev.add(name, predicted(), gt);
    html.add(predicted(), gt, {}, EvalOptions{}, std::string(name) == "with_faces" ? &square : nullptr);
    faces.buildings.push_back({name, {}, "open_surfaces", {}, 0.001});
  }
  const std::string page = html.html(ev.report(), "m", nullptr, {}, {}, &faces);
  // Millimetre integers, rings, labels (1 = wall) and the status; no block for the building without faces.
  EXPECT_THAT(page, HasSubstr("id=\"f0\">{\"f\":[[0,1,2]],\"l\":[1],\"s\":\"open_surfaces\",\"v\":[0,0,1000,1000,0,1000,1000,1000,1001]}"));
  EXPECT_THAT(page, Not(HasSubstr("id=\"f1\"")));
  EXPECT_THAT(page, HasSubstr("\"fs\":\"open_surfaces\""));
  EXPECT_THAT(page, HasSubstr("\"closed_share\":"));
  // Face scores that are not one per building are left out rather than misattributed.
  faces.buildings.pop_back();
  EXPECT_THAT(html.html(ev.report(), "m", nullptr, {}, {}, &faces), Not(HasSubstr("\"closed_share\":")));
}

}  // namespace
}  // namespace lc2wf

#include "infer/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/util/atomic_file.h"
#include "core/util/json_text.h"
#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "infer/eval_report_io.h"
#include "infer/match_status.h"
#include "infer/report_geometry.h"

#ifndef LC2WF_THREE_JS_DEFAULT_DIR
#define LC2WF_THREE_JS_DEFAULT_DIR "/usr/share/javascript/three"
#endif

namespace lc2wf {
namespace embedded {
extern const char* const kReportJs;
extern const char* const kReportCss;
extern const char* const kReportBody;
}  // namespace embedded

namespace {

std::string read_asset(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("cannot read " + path.string() +
                             " (the HTML report inlines three.js: install Debian's libjs-three, e.g. tools/setup-deps.sh, "
                             "or point LC2WF_THREE_JS_DIR at a three.js r111 folder)");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

// JSON inside <script>: "</" would end the element early; "<\/" is the same JSON string.
std::string script_safe(std::string s) {
  for (size_t p = 0; (p = s.find("</", p)) != std::string::npos; p += 3) s.replace(p, 2, "<\\/");
  return s;
}

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

// A building's faces for the viewer: vertices in millimetres (integers keep the page small), rings, and
// labels as 0 roof / 1 wall / 2 ground.
std::string faces_block(const SurfaceModel& m) {
  nlohmann::json v = nlohmann::json::array(), f = nlohmann::json::array(), l = nlohmann::json::array();
  for (const Vec3& p : m.vertices)
    for (int k = 0; k < 3; ++k) v.push_back(std::llround(p[k] * 1000));
  for (const SurfaceFace& face : m.faces) {
    f.push_back(face.ring);
    l.push_back(face.label == SurfaceLabel::kRoof ? 0 : face.label == SurfaceLabel::kWall ? 1 : 2);
  }
  return json_text(nlohmann::json{{"v", v}, {"f", f}, {"l", l}, {"s", to_string(m.status)}});
}

}  // namespace

std::filesystem::path default_three_js_dir() {
  if (const char* env = std::getenv("LC2WF_THREE_JS_DIR"); env && *env) return env;
  return LC2WF_THREE_JS_DEFAULT_DIR;
}

HtmlReport::HtmlReport(HtmlReportOptions options) : options_(std::move(options)) {
  three_js_ = read_asset(options_.three_js_dir / "three.min.js");
  orbit_controls_js_ = read_asset(options_.three_js_dir / "examples" / "js" / "controls" / "OrbitControls.js");
}

void HtmlReport::add(const ScoredWireframe& pred_in, const Wireframe& gt, const std::vector<Segment3>& cloud,
                     const EvalOptions& eval, const SurfaceModel* faces) {
  face_blocks_.push_back(faces ? faces_block(*faces) : std::string());
  const ScoredWireframe pred = referenced_junctions_only(pred_in);  // what the metrics evaluate
  ReportGeometryInput in;
  in.pred = &pred;
  in.gt = &gt;
  in.cloud = &cloud;
  in.junctions = junction_match_status(pred, gt, eval.vertex_thresholds, eval.min_score);
  in.edges = edge_match_status(pred, gt, eval.edge_thresholds, eval.min_score);
  in.vertex_thresholds = static_cast<int>(eval.vertex_thresholds.size());
  in.edge_thresholds = static_cast<int>(eval.edge_thresholds.size());
  blocks_.push_back(encode_report_geometry(in, options_.max_cloud_segments));
  const int total = static_cast<int>(cloud.size());
  cloud_sizes_.emplace_back(total, std::min(total, options_.max_cloud_segments));
}

std::string HtmlReport::html(const EvalReport& report, const std::string& method, const Building3dReport* building3d,
                             const std::vector<nlohmann::json>& compare, const std::vector<HtmlPlot>& plots,
                             const FaceReport* faces) const {
  if (report.buildings.size() != blocks_.size())
    throw std::logic_error("HtmlReport: " + std::to_string(blocks_.size()) + " buildings added, the report has " +
                           std::to_string(report.buildings.size()));
  nlohmann::json summary = eval_json(report, method);
  summary.erase("per_building");
  if (building3d) {
    summary["building3d"] = building3d_json(*building3d);
    summary["building3d"].erase("per_building");
  }
  if (faces && faces->buildings.size() != report.buildings.size()) faces = nullptr;  // not one score per building
  if (faces) {
    summary["faces"] = faces_json(*faces);
    summary["faces"].erase("per_building");
  }
  nlohmann::json rows = nlohmann::json::array();
  for (size_t k = 0; k < report.buildings.size(); ++k) {
    const BuildingEval& b = report.buildings[k];
    nlohmann::json r = {{"n", b.name},          {"miss", b.prediction_missing}, {"gv", b.gt_vertices},
                        {"ge", b.gt_edges},     {"pv", b.pred_vertices},        {"pe", b.pred_edges},
                        {"vtp", b.vertex_tp},   {"etp", b.edge_tp},             {"wn", b.wed.total_num()},
                        {"wd", b.wed.total_dist()}, {"cloud", cloud_sizes_[k].first}, {"shown", cloud_sizes_[k].second}};
    if (building3d && k < building3d->per_building.size()) {
      const Building3dCounts& c = building3d->per_building[k];
      const double cp = ratio(c.tp_corners, c.pred_corners), cr = ratio(c.tp_corners, c.gt_corners);
      const double ep = ratio(c.tp_edges, c.pred_edges), er = ratio(c.tp_edges, c.gt_edges);
      r["cf1"] = cp + cr > 0 ? 2 * cp * cr / (cp + cr) : 0.0;
      r["ef1"] = ep + er > 0 ? 2 * ep * er / (ep + er) : 0.0;
      r["nw"] = c.nwed;
    }
    if (faces) {
      const FaceBuilding& f = faces->buildings[k];
      r["fp"] = ratio(f.scores.matched_roof, f.scores.pred_roof);
      r["fr"] = ratio(f.scores.matched_roof, f.scores.gt_roof);
      r["fs"] = f.status;
    }
    rows.push_back(std::move(r));
  }
  nlohmann::json compare_rows = nlohmann::json::array();
  for (nlohmann::json c : compare) {
    c.erase("per_building");
    if (c.contains("building3d")) c["building3d"].erase("per_building");
    compare_rows.push_back(std::move(c));
  }
  nlohmann::json plot_list = nlohmann::json::array();
  for (const HtmlPlot& p : plots) plot_list.push_back({{"title", p.title}, {"href", p.href}});
  const nlohmann::json data = {{"summary", summary}, {"rows", rows}, {"compare", compare_rows}, {"plots", plot_list}};

  std::string h;
  h.reserve(three_js_.size() + 64 * 1024 + blocks_.size() * 40 * 1024);
  h += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<meta name=\"generator\" content=\"lc2wf-eval\">\n"
       "<link rel=\"icon\" href=\"data:,\">\n"  // no favicon request (a 404 when served over HTTP)
       "<title>lc2wf evaluation: " + html_escape(method) + "</title>\n<style>\n";
  h += embedded::kReportCss;
  h += "</style>\n</head>\n<body>\n";
  h += embedded::kReportBody;
  h += "<script type=\"application/json\" id=\"report-data\">" + script_safe(json_text(data)) + "</script>\n";
  for (size_t k = 0; k < blocks_.size(); ++k)
    h += "<script type=\"text/plain\" id=\"g" + std::to_string(k) + "\">" + blocks_[k] + "</script>\n";
  for (size_t k = 0; k < face_blocks_.size(); ++k)
    if (!face_blocks_[k].empty())
      h += "<script type=\"application/json\" id=\"f" + std::to_string(k) + "\">" + script_safe(face_blocks_[k]) + "</script>\n";
  h += "<script>/* three.js r111 (MIT), Debian libjs-three */\n" + three_js_ + "\n</script>\n";
  h += "<script>\n" + orbit_controls_js_ + "\n</script>\n<script>\n";
  h += embedded::kReportJs;
  h += "</script>\n</body>\n</html>\n";
  return h;
}

std::filesystem::path write_html_report(const std::filesystem::path& out, const HtmlReport& html, const EvalReport& report,
                                        const std::string& method, const Building3dReport* building3d,
                                        const std::vector<std::filesystem::path>& compare_dirs,
                                        const std::filesystem::path& weights, const FaceReport* faces) {
  namespace fs = std::filesystem;
  std::vector<nlohmann::json> compare;
  for (const fs::path& dir : compare_dirs) {
    const fs::path file = dir / "metrics.json";
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(read_file(file));  // regular files only: a FIFO would block
    } catch (const nlohmann::json::exception& e) {
      throw DataError(file.string(), e.what());
    }
    // The page drops these rows' per-building lists: anything but an object is not a metrics.json.
    if (!j.is_object()) throw DataError(file.string(), "not an lc2wf-eval metrics.json: expected a JSON object");
    if (j.contains("building3d") && !j["building3d"].is_object()) throw DataError(file.string(), "'building3d' is not an object");
    compare.push_back(std::move(j));
  }
  std::vector<HtmlPlot> plots;
  for (const fs::path& dir : {out / "plots", weights.empty() ? fs::path() : weights / "plots"}) {
    if (dir.empty() || !fs::is_directory(dir)) continue;
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().extension() == ".png") pngs.push_back(e.path());
    std::sort(pngs.begin(), pngs.end());
    for (const fs::path& p : pngs)
      plots.push_back({p.stem().string(), fs::relative(fs::absolute(p), fs::absolute(out)).generic_string()});
  }
  const fs::path path = out / "report.html";
  write_text_atomically(path, html.html(report, method, building3d, compare, plots, faces));
  return path;
}

}  // namespace lc2wf

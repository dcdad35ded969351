// The self-contained HTML report of lc2wf-eval --html: Table 2 (plus other runs to compare), the
// Building3D-style section, a per-building table sortable by every metric and a 3D viewer (three.js from
// Debian's libjs-three, inlined) of line cloud, prediction and ground truth with matched / missed / spurious
// elements. Each building's geometry is a compact base64 block decoded only when the building is opened.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "infer/building3d_io.h"
#include "infer/surfaces/face_metrics_io.h"
#include "model/evaluator.h"

namespace lc2wf {

struct HtmlReportOptions {
  std::filesystem::path three_js_dir;  // holds three.min.js and examples/js/controls/OrbitControls.js
  int max_cloud_segments = 3000;       // per building (real clouds: 550-1130 on average); larger ones are thinned evenly
};

// LC2WF_THREE_JS_DIR from the environment, else the build's default (Debian: /usr/share/javascript/three).
std::filesystem::path default_three_js_dir();

struct HtmlPlot {
  std::string title;
  std::string href;  // relative to the report
};

class HtmlReport {
 public:
  // Reads the three.js files; throws std::runtime_error naming a missing file and the package to install.
  explicit HtmlReport(HtmlReportOptions options);

  // One building, in the evaluator's add() order, with the prediction as given to Evaluator::add; `faces`:
  // the LoD2 surfaces found in the prediction (drawn as translucent polygons by label), when given.
  void add(const ScoredWireframe& pred, const Wireframe& gt, const std::vector<Segment3>& cloud,
           const EvalOptions& eval_options, const SurfaceModel* faces = nullptr);

  // `compare`: metrics.json objects of other runs (e.g. --release-quirks), shown as extra table rows.
  // `faces`: the face scores (section (d)), one per building in add() order, when given.
  std::string html(const EvalReport& report, const std::string& method, const Building3dReport* building3d,
                   const std::vector<nlohmann::json>& compare, const std::vector<HtmlPlot>& plots,
                   const FaceReport* faces = nullptr) const;

 private:
  HtmlReportOptions options_;
  std::string three_js_, orbit_controls_js_;
  std::vector<std::string> blocks_;             // base64 geometry per building
  std::vector<std::string> face_blocks_;        // JSON faces per building ("" without faces)
  std::vector<std::pair<int, int>> cloud_sizes_;  // (segments in the cloud, segments kept)
};

// Writes `<out>/report.html` atomically. `compare_dirs`: other lc2wf-eval output folders whose metrics.json
// rows are added to the tables; plots: the PNGs in `<out>/plots/` and `<weights>/plots/` (when given) at
// writing time. Returns the report's path.
std::filesystem::path write_html_report(const std::filesystem::path& out, const HtmlReport& html, const EvalReport& report,
                                        const std::string& method, const Building3dReport* building3d,
                                        const std::vector<std::filesystem::path>& compare_dirs,
                                        const std::filesystem::path& weights, const FaceReport* faces = nullptr);

}  // namespace lc2wf

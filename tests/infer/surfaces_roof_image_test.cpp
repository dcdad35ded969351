// The face finder on the GT wireframes of ~200 Roof-Image buildings, scored against the GT mesh faces:
// share of valid closed solids, roof-facet precision / recall, labels and the time per building (printed,
// not asserted). Skipped without ../shared/data/roof-image.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "dataset/geometry/building.h"
#include "infer/surfaces/face_metrics_io.h"
#include "infer/surfaces/wireframe_surfaces.h"

namespace lc2wf {
namespace {

TEST(SurfacesRoofImage, GroundTruthWireframesCloseAndMatchTheMeshFaces) {
  const std::filesystem::path dir = std::filesystem::path(LC2WF_SHARED_DATA_DIR) / "roof-image" / "res_building";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " not present";
  const std::vector<std::string> names = list_polyshape_names(dir);
  ASSERT_GT(names.size(), 200u);
  FaceReport report;
  const size_t stride = names.size() / 200;
  int skipped = 0;
  for (size_t k = 0; k < names.size() && report.buildings.size() < 200; k += stride) {
    Building b;
    try {
      b = load_roof_image_building(dir / (names[k] + ".polyshape"));
    } catch (const std::exception&) {
      ++skipped;
      continue;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const SurfaceModel m = surfaces_from_wireframe(b.wireframe);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    report.buildings.push_back({names[k], score_faces(m, surfaces_from_mesh(b.mesh)), to_string(m.status), m.reasons, seconds});
  }
  const FaceSummary s = summarize_faces(report);
  std::printf("Roof-Image GT wireframes, %d buildings (%d unreadable): closed solids %.1f %% (%d), roof facets P %.1f %% R %.1f %% "
              "(%d matched, %d predicted, %d GT), labels %.1f %%, roof area error %.2f %%, %.2f ms per building (max %.1f)\n",
              s.buildings, skipped, 100 * s.closed_share, s.closed_solids, 100 * s.roof_precision, 100 * s.roof_recall,
              s.matched_roof, s.pred_roof, s.gt_roof, 100 * s.label_accuracy, 100 * s.roof_area_error, s.mean_ms, s.max_ms);
  int listed = 0;
  for (const FaceBuilding& b : report.buildings)
    if (b.status != "closed_solid" && listed++ < 8) {
      std::string why;
      for (const auto& r : b.reasons) why += r + "; ";
      std::printf("  %s: %s (%s)\n", b.name.c_str(), b.status.c_str(), why.c_str());
    }
  // The GT wireframe holds every edge of the mesh: most buildings must come back closed with their roof facets.
  EXPECT_GT(s.closed_share, 0.8);
  EXPECT_GT(s.roof_recall, 0.8);
  EXPECT_GT(s.roof_precision, 0.8);
}

}  // namespace
}  // namespace lc2wf

// Every published model (each folder of models/ with weights, so a new one is covered by being shipped) loads
// on a fresh clone and turns a building's line cloud into a wireframe: finite scores, edges inside the
// building, most GT corners found. Registered only when models/base holds both weight files
// (tests/infer/CMakeLists.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "model/inference.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

class PretrainedModel : public testing::TestWithParam<std::string> {};

std::vector<std::string> published_models() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(fs::path(LC2WF_SOURCE_DIR) / "models"))
    if (fs::exists(e.path() / "junction.safetensors")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST_P(PretrainedModel, TurnsAHipRoofCloudIntoAWireframe) {
  const fs::path dir = fs::path(LC2WF_SOURCE_DIR) / "models" / GetParam();
  const WireframePredictor predictor(dir);
  const Building building = make_rect_building("hip", RectBuildingSpec{});
  const LineCloud cloud = make_synthetic_line_cloud(building, 3);
  const InferenceResult r = predictor.predict(cloud, PostProcessOptions{});

  ASSERT_FALSE(r.junctions.positions.empty());
  for (size_t i = 0; i < r.junctions.positions.size(); ++i) {
    EXPECT_TRUE(std::isfinite(r.junctions.confidence[i])) << i;
    EXPECT_TRUE(r.junctions.positions[i].allFinite()) << i;
  }
  const Wireframe& w = r.wireframe.wireframe;
  ASSERT_GE(w.edges.size(), 4u) << "the model predicted (almost) no wireframe";
  Vec3 lo = cloud.wireframe.junctions.front(), hi = lo;
  for (const Vec3& j : cloud.wireframe.junctions) {
    lo = lo.cwiseMin(j);
    hi = hi.cwiseMax(j);
  }
  for (const Vec3& v : w.junctions) {
    EXPECT_TRUE((v.array() >= lo.array() - 1.0).all() && (v.array() <= hi.array() + 1.0).all()) << v.transpose();
  }
  // A hip roof's 10 corners (4 eaves, 4 ground, 2 ridge ends): most are found within 0.5 m.
  int found = 0;
  for (const Vec3& g : cloud.wireframe.junctions) {
    for (const Vec3& v : w.junctions) {
      if ((v - g).norm() < 0.5) {
        ++found;
        break;
      }
    }
  }
  EXPECT_GE(found, static_cast<int>(cloud.wireframe.junctions.size()) / 2) << found << " of " << cloud.wireframe.junctions.size();
}

INSTANTIATE_TEST_SUITE_P(Published, PretrainedModel, testing::ValuesIn(published_models()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace lc2wf

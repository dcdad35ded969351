// Height model files (weights folder's height.json, --height-model FILE): parsed, checked, then asked for the
// height of a small cloud, so a file that passes the checks can never crash the reading.
#include <nlohmann/json.hpp>

#include "dataset/photo/line_height.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    const lc2wf::HeightModel m = lc2wf::height_model_from_json(nlohmann::json::parse(lc2wf::fuzz::bytes(data, size)), "fuzz.json");
    std::vector<lc2wf::Segment3> box;
    for (int i = 0; i < 12; ++i) box.push_back({lc2wf::Vec3(i, 0, 0), lc2wf::Vec3(i, 0.5 * i, 3.0 + i)});
    (void)m.predict_height_m(lc2wf::line_statistics(box));
  });
  return 0;
}

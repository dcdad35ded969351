// CityJSON and CityJSONSeq (real LoD2 city models) through the readers and the LoD2 clean-up lc2wf-dataset
// --meshes and lc2wf-eval --gt use: a clean DataError or a skipped building, never a crash.
#include <sstream>

#include "dataset/formats/city_json_io.h"
#include "dataset/geometry/lod2_cleanup.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = lc2wf::fuzz::bytes(data, size);
  auto clean = [](lc2wf::CityBuilding&& b) {
    if (const lc2wf::CityLodGeometry* g = lc2wf::select_lod(b, "")) {
      (void)lc2wf::cleanup_lod2(g->polygons);
    }
  };
  lc2wf::fuzz::expect_clean_rejection([&] { lc2wf::parse_city_json(text, "fuzz.city.json", clean); });
  lc2wf::fuzz::expect_clean_rejection([&] {
    std::istringstream in(text);
    lc2wf::parse_city_json_seq(in, "fuzz.jsonl", clean);
  });
  return 0;
}

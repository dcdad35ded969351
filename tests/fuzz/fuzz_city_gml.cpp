// CityGML 1.0 / 2.0 (real LoD2 city models) through the bounded XML reader, the CityGML reader and the LoD2
// clean-up: a clean DataError or a skipped building, never a crash, a hang or unbounded memory.
#include "dataset/formats/city_gml_io.h"
#include "dataset/geometry/lod2_cleanup.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    lc2wf::parse_city_gml(lc2wf::fuzz::bytes(data, size), "fuzz.gml", [](lc2wf::CityBuilding&& b) {
      if (const lc2wf::CityLodGeometry* g = lc2wf::select_lod(b, "")) {
        (void)lc2wf::cleanup_lod2(g->polygons);
      }
    });
  });
  return 0;
}

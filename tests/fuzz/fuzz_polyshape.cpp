// .polyshape (Roof-Image meshes) through the same parser and building import lc2wf-dataset uses.
#include <sstream>

#include "dataset/geometry/building.h"
#include "dataset/formats/mesh_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    std::istringstream in(lc2wf::fuzz::bytes(data, size));
    const lc2wf::PolyMesh mesh = lc2wf::parse_polyshape(in, "fuzz.polyshape");
    (void)mesh;
  });
  return 0;
}

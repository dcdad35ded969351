// .obj wireframes and meshes (predictions and GT for lc2wf-eval), Z-up and Y-up.
#include <sstream>

#include "dataset/formats/mesh_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  for (const bool y_up : {false, true}) {
    lc2wf::fuzz::expect_clean_rejection([&] {
      std::istringstream in(lc2wf::fuzz::bytes(data, size));
      lc2wf::ObjReadOptions options;
      options.y_up = y_up;
      (void)lc2wf::parse_obj(in, "fuzz.obj", options);
    });
  }
  return 0;
}

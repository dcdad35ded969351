// Line clouds as OBJ ('v' and 'l'): Line3D++'s and LIMAP's `.obj` exports and ours, converted to our cloud.
#include <sstream>

#include "dataset/formats/line_obj_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    std::istringstream in(lc2wf::fuzz::bytes(data, size));
    (void)lc2wf::to_line_cloud(lc2wf::parse_line_obj(in, "fuzz.obj"), "fuzz", "fuzz.obj");
  });
  return 0;
}

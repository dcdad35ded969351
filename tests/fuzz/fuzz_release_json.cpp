// The paper release's LineCloud JSON (junc3DList / label / objGTJunc3D / line_idx).
#include "dataset/formats/release_json.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection(
      [&] { (void)lc2wf::parse_release_line_cloud(lc2wf::fuzz::bytes(data, size), "fuzz.json"); });
  return 0;
}

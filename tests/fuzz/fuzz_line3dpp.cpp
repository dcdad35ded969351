// Line3D++ `.txt` line maps (lc2wf-infer --format line3dpp, auto-detection), converted to our cloud.
#include "dataset/formats/line3dpp_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = lc2wf::fuzz::bytes(data, size);
  (void)lc2wf::looks_like_line3dpp_txt(text);
  lc2wf::fuzz::expect_clean_rejection([&] {
    const lc2wf::LineCloud cloud = lc2wf::to_line_cloud(lc2wf::parse_line3dpp_txt(text, "fuzz.txt"), "fuzz", "fuzz.txt");
    (void)lc2wf::line3dpp_txt_string(cloud);
  });
  return 0;
}

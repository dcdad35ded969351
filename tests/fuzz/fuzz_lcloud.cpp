// Our line-cloud format, binary and JSON variants; an accepted cloud must also write back.
#include "dataset/formats/line_cloud_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    const lc2wf::LineCloud cloud = lc2wf::line_cloud_from_bytes(lc2wf::fuzz::bytes(data, size), "fuzz.lcloud");
    (void)lc2wf::line_cloud_to_bytes(cloud);
  });
  return 0;
}

// One LIMAP `finaltracks/track_<i>.txt` file, converted to our cloud.
#include "dataset/formats/limap_io.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] {
    lc2wf::ExternalLineMap map;
    map.lines.push_back(lc2wf::parse_limap_track(lc2wf::fuzz::bytes(data, size), "track_0.txt"));
    (void)lc2wf::to_line_cloud(map, "fuzz", "track_0.txt");
  });
  return 0;
}

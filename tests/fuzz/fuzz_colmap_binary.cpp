// COLMAP binary models (cameras.bin, images.bin): the first byte picks the file (even: cameras, odd: images,
// read against a fixed camera 1), the rest is its content.
#include "fuzz_common.h"
#include "tools/colmap/colmap_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string bytes = lc2wf::fuzz::bytes(data + 1, size - 1);
  lc2wf::ColmapCameras fixed;
  fixed[1].width = fixed[1].height = 100;
  lc2wf::fuzz::expect_clean_rejection([&] {
    if (data[0] % 2 == 0) (void)lc2wf::parse_colmap_cameras_bin(bytes, "cameras.bin");
    else (void)lc2wf::parse_colmap_images_bin(bytes, "images.bin", fixed);
  });
  return 0;
}

// COLMAP text models (lc2wf-reconstruct --cameras MODEL_DIR): the input is cameras.txt, a NUL byte, then
// images.txt. The images are also read against a fixed camera 1 so they are fuzzed when cameras.txt fails.
#include "fuzz_common.h"
#include "tools/colmap/colmap_model.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input = lc2wf::fuzz::bytes(data, size);
  const size_t split = std::min(input.find('\0'), input.size());
  const std::string cameras_txt = input.substr(0, split), images_txt = split < input.size() ? input.substr(split + 1) : "";
  lc2wf::ColmapCameras fixed;
  fixed[1].width = fixed[1].height = 100;
  lc2wf::fuzz::expect_clean_rejection([&] {
    const lc2wf::ColmapCameras cameras = lc2wf::parse_colmap_cameras_txt(cameras_txt, "cameras.txt");
    (void)lc2wf::parse_colmap_images_txt(images_txt, "images.txt", cameras);
  });
  lc2wf::fuzz::expect_clean_rejection([&] { (void)lc2wf::parse_colmap_images_txt(images_txt, "images.txt", fixed); });
  return 0;
}

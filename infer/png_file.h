// PNG encoding of an 8-bit RGB image with zlib, so the previews need no image-codec library: OpenCV's
// codecs pull in ≈ 120 more shared libraries, whose loading cost every lc2wf-infer and lc2wf-eval
// process ≈ 65 ms before it read a byte.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lc2wf {

// The PNG file (8-bit truecolour, no interlace) of `rgb`, rows top to bottom, 3 bytes per pixel, row after
// row without padding. Throws std::invalid_argument when the sizes do not fit.
std::string encode_png_rgb(const std::vector<uint8_t>& rgb, int width, int height);

}  // namespace lc2wf

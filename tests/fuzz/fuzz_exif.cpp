// JPEG heads as lc2wf-reconstruct reads them for EXIF GPS and focal length (exif_gps, exif_focal): no fix or
// no focal length with a reason is the promised answer to any bytes; a value that comes back is finite.
#include <cmath>
#include <cstdlib>

#include "dataset/photo/exif_focal.h"
#include "dataset/photo/exif_gps.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string jpeg = lc2wf::fuzz::bytes(data, size);
  lc2wf::fuzz::expect_clean_rejection([&] {
    if (const auto fix = lc2wf::exif_gps(jpeg))
      if (!std::isfinite(fix->latitude_deg) || !std::isfinite(fix->longitude_deg) || !std::isfinite(fix->altitude_m)) std::abort();
    if (const auto focal = lc2wf::exif_focal(jpeg, 4000))
      if (!(focal->focal_35mm >= lc2wf::kMinFocal35mm && focal->focal_35mm <= lc2wf::kMaxFocal35mm)) std::abort();
  });
  return 0;
}

#include "dataset/photo/exif_focal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dataset/photo/exif_tiff.h"

namespace lc2wf {
namespace {

using namespace exif;

constexpr uint16_t kFocalLength = 0x920A, kFocal35mm = 0xA405, kPixelX = 0xA002, kPixelY = 0xA003;
constexpr uint16_t kPlaneXResolution = 0xA20E, kPlaneUnit = 0xA210;

ExifFocal focal_from_tiff(std::string_view tiff_bytes, int longer_side_px) {
  const Tiff t(tiff_bytes);
  size_t exif_at = 0;
  read_ifd(t, t.first_ifd(), [&](uint16_t tag, const Entry& e) {
    if (tag == kExifIfdTag) exif_at = whole_number(t, e, "an Exif IFD pointer");
  });
  if (exif_at == 0) throw Failure{"no Exif IFD"};
  double f35 = 0, f_mm = 0, plane_resolution = 0, pixels_x = 0, pixels_y = 0;
  uint32_t unit = 2;  // inches, EXIF's default
  read_ifd(t, exif_at, [&](uint16_t tag, const Entry& e) {
    if (tag == kFocal35mm) f35 = whole_number(t, e, "FocalLengthIn35mmFilm");
    else if (tag == kFocalLength && e.type == kRational && e.count >= 1) f_mm = rational(t, e.value_at, "FocalLength");
    else if (tag == kPlaneXResolution && e.type == kRational && e.count >= 1) plane_resolution = rational(t, e.value_at, "FocalPlaneXResolution");
    else if (tag == kPlaneUnit) unit = whole_number(t, e, "FocalPlaneResolutionUnit");
    else if (tag == kPixelX) pixels_x = whole_number(t, e, "PixelXDimension");
    else if (tag == kPixelY) pixels_y = whole_number(t, e, "PixelYDimension");
  });
  auto plausible = [](double f) { return std::isfinite(f) && f >= kMinFocal35mm && f <= kMaxFocal35mm; };
  if (f35 > 0) {  // 0 means "unknown" in EXIF
    if (!plausible(f35)) throw Failure{"FocalLengthIn35mmFilm " + std::to_string(f35) + " mm is implausible"};
    return {f35, "FocalLengthIn35mmFilm"};
  }
  if (!(f_mm > 0)) throw Failure{"no focal length"};
  const double unit_mm = unit == 2 ? 25.4 : unit == 3 ? 10.0 : unit == 4 ? 1.0 : 0.0;
  if (!(plane_resolution > 0) || unit_mm == 0) throw Failure{"a focal length in mm but no sensor size (FocalPlaneXResolution)"};
  const double longer_px = pixels_x > 0 && pixels_y > 0 ? std::max(pixels_x, pixels_y) : longer_side_px;
  const double sensor_mm = longer_px / plane_resolution * unit_mm;
  const double f = f_mm * 36.0 / sensor_mm;
  if (!plausible(f)) {
    char text[160];
    std::snprintf(text, sizeof text, "FocalLength %.3g mm on a %.3g mm sensor is implausible", f_mm, sensor_mm);
    throw Failure{text};
  }
  return {f, "FocalLength, FocalPlaneXResolution"};
}

}  // namespace

std::optional<ExifFocal> exif_focal(std::string_view jpeg, int longer_side_px, std::string* why_not) {
  try {
    return focal_from_tiff(tiff_block(jpeg), longer_side_px);
  } catch (const Failure& f) {
    if (why_not) *why_not = f.why;
    return std::nullopt;
  }
}

}  // namespace lc2wf

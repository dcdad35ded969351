// The 35 mm-equivalent focal length a camera wrote into a JPEG's EXIF: FocalLengthIn35mmFilm where it is
// given, else the focal length in millimetres over the sensor's size, which FocalPlaneXResolution /
// FocalPlaneResolutionUnit give in pixels per unit (35 mm film's longer side is 36 mm). Phones and drones write
// the first, most cameras the second; without either the caller keeps its default.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace lc2wf {

struct ExifFocal {
  double focal_35mm = 0;  // millimetres, 35 mm film equivalent
  std::string tags;       // "FocalLengthIn35mmFilm" or "FocalLength, FocalPlaneXResolution"
};

// Values outside [kMinFocal35mm, kMaxFocal35mm] are no focal length a photo of a building was taken with: a
// broken tag, not a fisheye or a telescope, and are not used.
constexpr double kMinFocal35mm = 8.0, kMaxFocal35mm = 2000.0;

// From a whole JPEG's bytes (or its head). `longer_side_px`: the photo's longer side in pixels, used with
// the focal-plane resolution when the EXIF gives no PixelXDimension / PixelYDimension. std::nullopt, with the
// reason in *why_not, when there is none.
std::optional<ExifFocal> exif_focal(std::string_view jpeg, int longer_side_px, std::string* why_not = nullptr);

}  // namespace lc2wf

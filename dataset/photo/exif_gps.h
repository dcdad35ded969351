// The GPS position a camera wrote into a JPEG's EXIF (drone photos carry it): GPSLatitude, GPSLongitude and
// GPSAltitude from the APP1 "Exif" segment's TIFF structure. A small bounded reader of our own: every offset
// is checked against the segment, so a broken or hostile file gives "no fix" and a reason, never a crash.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace lc2wf {

struct GpsFix {
  double latitude_deg = 0;   // north positive
  double longitude_deg = 0;  // east positive
  double altitude_m = 0;     // above sea level (0 with has_altitude false when the photo has none)
  bool has_altitude = false;
};

// The fix in a whole JPEG file's bytes, or its head (exif::read_head); std::nullopt when there is none, with
// the reason in *why_not ("no EXIF", "no GPS", "EXIF: offset beyond the segment", ...).
std::optional<GpsFix> exif_gps(std::string_view jpeg, std::string* why_not = nullptr);

}  // namespace lc2wf

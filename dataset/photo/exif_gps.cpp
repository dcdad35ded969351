#include "dataset/photo/exif_gps.h"

#include <cmath>
#include <cstdint>
#include <optional>

#include "dataset/photo/exif_tiff.h"

namespace lc2wf {
namespace {

using namespace exif;

constexpr uint16_t kLatRef = 1, kLat = 2, kLonRef = 3, kLon = 4, kAltRef = 5, kAlt = 6;

double rational(const Tiff& t, size_t at) { return exif::rational(t, at, "a GPS rational"); }

// Degrees, minutes, seconds (three rationals) -> degrees.
double dms(const Tiff& t, const Entry& e) {
  if (e.type != kRational || e.count != 3) throw Failure{"EXIF: a GPS coordinate that is not 3 rationals"};
  t.need(e.value_at, 24);
  return rational(t, e.value_at) + rational(t, e.value_at + 8) / 60.0 + rational(t, e.value_at + 16) / 3600.0;
}

char ref(const Tiff& t, const Entry& e) {
  if (e.type != kAscii || e.count < 1) throw Failure{"EXIF: a GPS reference that is not text"};
  return static_cast<char>(t.u8(e.value_at));
}

GpsFix gps_from_tiff(std::string_view tiff_bytes) {
  const Tiff t(tiff_bytes);
  size_t gps_at = 0;
  read_ifd(t, t.first_ifd(), [&](uint16_t tag, const Entry& e) {
    if (tag == kGpsIfdTag) gps_at = t.u32(e.value_at);
  });
  if (gps_at == 0) throw Failure{"no GPS"};
  std::optional<Entry> lat, lon, alt;
  char lat_ref = 0, lon_ref = 0;
  uint8_t alt_ref = 0;
  read_ifd(t, gps_at, [&](uint16_t tag, const Entry& e) {
    if (tag == kLat) lat = e;
    else if (tag == kLon) lon = e;
    else if (tag == kAlt) alt = e;
    else if (tag == kLatRef) lat_ref = ref(t, e);
    else if (tag == kLonRef) lon_ref = ref(t, e);
    else if (tag == kAltRef && e.count >= 1) alt_ref = t.u8(e.value_at);
  });
  if (!lat || !lon) throw Failure{"no GPS"};
  GpsFix f;
  f.latitude_deg = dms(t, *lat) * (lat_ref == 'S' ? -1 : 1);
  f.longitude_deg = dms(t, *lon) * (lon_ref == 'W' ? -1 : 1);
  if (!(std::abs(f.latitude_deg) <= 90 && std::abs(f.longitude_deg) <= 180)) throw Failure{"EXIF: GPS coordinates out of range"};
  if (alt) {
    if (alt->type != kRational || alt->count != 1) throw Failure{"EXIF: a GPS altitude that is not a rational"};
    f.altitude_m = rational(t, alt->value_at) * (alt_ref == 1 ? -1 : 1);
    f.has_altitude = true;
  }
  return f;
}

}  // namespace

std::optional<GpsFix> exif_gps(std::string_view jpeg, std::string* why_not) {
  try {
    return gps_from_tiff(tiff_block(jpeg));
  } catch (const Failure& f) {
    if (why_not) *why_not = f.why;
    return std::nullopt;
  }
}

}  // namespace lc2wf

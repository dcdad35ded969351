#include "dataset/photo/exif_gps.h"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace lc2wf {
namespace {

constexpr uint16_t kGpsIfdTag = 0x8825;
constexpr uint16_t kLatRef = 1, kLat = 2, kLonRef = 3, kLon = 4, kAltRef = 5, kAlt = 6;
constexpr uint16_t kAscii = 2, kByte = 1, kRational = 5;
constexpr int kMaxEntries = 512;  // IFDs hold tens of entries; more is a broken file

struct Failure {
  std::string why;
};

// The TIFF structure inside an APP1 payload: byte order and bounds-checked reads.
class Tiff {
 public:
  explicit Tiff(std::string_view data) : d_(data) {
    if (d_.size() < 8) throw Failure{"EXIF: TIFF header cut short"};
    if (d_.substr(0, 4) == std::string_view("II*\0", 4)) little_ = true;
    else if (d_.substr(0, 4) == std::string_view("MM\0*", 4)) little_ = false;
    else throw Failure{"EXIF: not a TIFF header"};
  }
  uint16_t u16(size_t at) const {
    need(at, 2);
    const auto b = [&](size_t k) { return static_cast<uint16_t>(static_cast<uint8_t>(d_[at + k])); };
    return little_ ? static_cast<uint16_t>(b(0) | b(1) << 8) : static_cast<uint16_t>(b(0) << 8 | b(1));
  }
  uint32_t u32(size_t at) const {
    need(at, 4);
    const auto b = [&](size_t k) { return static_cast<uint32_t>(static_cast<uint8_t>(d_[at + k])); };
    return little_ ? b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24 : b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
  }
  uint8_t u8(size_t at) const {
    need(at, 1);
    return static_cast<uint8_t>(d_[at]);
  }
  void need(size_t at, size_t n) const {
    if (at > d_.size() || n > d_.size() - at) throw Failure{"EXIF: offset beyond the segment"};
  }

 private:
  std::string_view d_;
  bool little_ = true;
};

struct Entry {
  uint16_t type = 0;
  uint32_t count = 0;
  size_t value_at = 0;  // where the value is: inside the entry when it fits in 4 bytes, else at its offset
};

// Tag -> entry of the IFD at `at` (only the tags asked for).
template <typename Visit>
void read_ifd(const Tiff& t, size_t at, Visit visit) {
  const uint16_t n = t.u16(at);
  if (n > kMaxEntries) throw Failure{"EXIF: an IFD with " + std::to_string(n) + " entries"};
  for (uint16_t k = 0; k < n; ++k) {
    const size_t e = at + 2 + 12 * static_cast<size_t>(k);
    Entry entry{t.u16(e + 2), t.u32(e + 4), e + 8};
    const size_t unit = entry.type == kRational ? 8 : entry.type == kAscii || entry.type == kByte ? 1 : 4;
    if (static_cast<uint64_t>(unit) * entry.count > 4) entry.value_at = t.u32(e + 8);
    visit(t.u16(e), entry);
  }
}

double rational(const Tiff& t, size_t at) {
  const uint32_t num = t.u32(at), den = t.u32(at + 4);
  if (den == 0) throw Failure{"EXIF: a GPS rational with denominator 0"};
  return static_cast<double>(num) / den;
}

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
  read_ifd(t, t.u32(4), [&](uint16_t tag, const Entry& e) {
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
  auto fail = [&](const std::string& why) -> std::optional<GpsFix> {
    if (why_not) *why_not = why;
    return std::nullopt;
  };
  if (jpeg.size() < 4 || static_cast<uint8_t>(jpeg[0]) != 0xFF || static_cast<uint8_t>(jpeg[1]) != 0xD8) return fail("not a JPEG");
  size_t at = 2;
  // Marker segments up to the image data: FF xx, then a 2-byte big-endian length that counts itself.
  while (at + 4 <= jpeg.size()) {
    if (static_cast<uint8_t>(jpeg[at]) != 0xFF) return fail("no EXIF (broken marker)");
    const uint8_t marker = static_cast<uint8_t>(jpeg[at + 1]);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xDA || marker == 0xD9) break;  // image data or end: EXIF comes before
    const size_t length = static_cast<size_t>(static_cast<uint8_t>(jpeg[at + 2])) << 8 | static_cast<uint8_t>(jpeg[at + 3]);
    if (length < 2 || at + 2 + length > jpeg.size()) return fail("no EXIF (a segment runs past the end)");
    const std::string_view payload = jpeg.substr(at + 4, length - 2);
    if (marker == 0xE1 && payload.size() >= 6 && payload.substr(0, 6) == std::string_view("Exif\0\0", 6)) {
      try {
        return gps_from_tiff(payload.substr(6));
      } catch (const Failure& f) {
        return fail(f.why);
      }
    }
    at += 2 + length;
  }
  return fail("no EXIF");
}

std::optional<GpsFix> exif_gps_of_file(const std::filesystem::path& path, std::string* why_not) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  std::string head(256 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return exif_gps(head, why_not);
}

}  // namespace lc2wf

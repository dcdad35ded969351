// EXIF blocks written by hand, as a drone or phone writes them, so the reader's tests and the pipeline's GPS
// scale tests build their JPEGs one way: a TIFF block with IFD0 (the GPS IFD pointer) and a GPS IFD; or IFD0
// with the orientation tag alone.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace lc2wf::testing {

class TiffWriter {
 public:
  explicit TiffWriter(bool little) : little_(little) {}
  void u16(uint16_t v) {
    if (little_) b_.push_back(char(v & 0xFF)), b_.push_back(char(v >> 8));
    else b_.push_back(char(v >> 8)), b_.push_back(char(v & 0xFF));
  }
  void u32(uint32_t v) {
    if (little_) for (int k = 0; k < 4; ++k) b_.push_back(char((v >> (8 * k)) & 0xFF));
    else for (int k = 3; k >= 0; --k) b_.push_back(char((v >> (8 * k)) & 0xFF));
  }
  std::string& bytes() { return b_; }

 private:
  bool little_;
  std::string b_;
};

struct Dms {
  uint32_t d, m, s_num, s_den;
};

// A degree value as EXIF writes it: whole degrees, whole minutes, seconds to 1e-4 s (about 3 mm).
inline Dms to_dms(double deg) {
  const double v = std::abs(deg);
  const uint32_t d = uint32_t(v), m = uint32_t((v - d) * 60);
  return {d, m, uint32_t(std::llround(((v - d) * 60 - m) * 60 * 10000)), 10000};
}

// The TIFF block of one fix: latitude and longitude with their refs, altitude alt_num / alt_den (alt_ref 1:
// below sea level).
inline std::string gps_tiff(bool little, Dms lat, char lat_ref, Dms lon, char lon_ref, uint8_t alt_ref, uint32_t alt_num,
                            uint32_t alt_den) {
  TiffWriter w(little);
  w.bytes() += little ? std::string("II*\0", 4) : std::string("MM\0*", 4);
  w.u32(8);  // IFD0 at 8
  w.u16(1);  // one entry
  w.u16(0x8825), w.u16(4), w.u32(1), w.u32(26);  // GPS IFD pointer -> 26
  w.u32(0);  // next IFD
  // GPS IFD at 26: 6 entries, then the rationals at 26 + 2 + 72 + 4 = 104
  const uint32_t data = 104;
  w.u16(6);
  w.u16(1), w.u16(2), w.u32(2), w.bytes() += std::string{lat_ref, 0, 0, 0};
  w.u16(2), w.u16(5), w.u32(3), w.u32(data);
  w.u16(3), w.u16(2), w.u32(2), w.bytes() += std::string{lon_ref, 0, 0, 0};
  w.u16(4), w.u16(5), w.u32(3), w.u32(data + 24);
  w.u16(5), w.u16(1), w.u32(1), w.bytes() += std::string{char(alt_ref), 0, 0, 0};
  w.u16(6), w.u16(5), w.u32(1), w.u32(data + 48);
  w.u32(0);
  for (const Dms& v : {lat, lon}) w.u32(v.d), w.u32(1), w.u32(v.m), w.u32(1), w.u32(v.s_num), w.u32(v.s_den);
  w.u32(alt_num), w.u32(alt_den);
  return w.bytes();
}

// The TIFF block of a camera's orientation tag alone (IFD0 entry 0x0112: 6 = shown turned 90° clockwise).
inline std::string orientation_tiff(uint16_t orientation) {
  TiffWriter w(true);
  w.bytes() += std::string("II*\0", 4);
  w.u32(8);
  w.u16(1);
  w.u16(0x0112), w.u16(3), w.u32(1), w.u16(orientation), w.u16(0);
  w.u32(0);
  return w.bytes();
}

// One field of an Exif IFD: its value's bytes already in the block's byte order (TiffWriter).
struct TiffField {
  uint16_t tag, type;
  uint32_t count;
  std::string value;
};

// A TIFF block whose IFD0 points to an Exif IFD holding `fields` (values of more than 4 bytes after it).
inline std::string exif_ifd_tiff(bool little, const std::vector<TiffField>& fields) {
  TiffWriter w(little);
  w.bytes() += little ? std::string("II*\0", 4) : std::string("MM\0*", 4);
  w.u32(8);
  w.u16(1);
  w.u16(0x8769), w.u16(4), w.u32(1), w.u32(26);  // Exif IFD pointer -> 26
  w.u32(0);
  uint32_t data = 26 + 2 + 12 * static_cast<uint32_t>(fields.size()) + 4;
  std::string tail;
  w.u16(static_cast<uint16_t>(fields.size()));
  for (const TiffField& f : fields) {
    w.u16(f.tag), w.u16(f.type), w.u32(f.count);
    if (f.value.size() <= 4) {
      w.bytes() += f.value + std::string(4 - f.value.size(), '\0');
    } else {
      w.u32(data + static_cast<uint32_t>(tail.size()));
      tail += f.value;
    }
  }
  w.u32(0);
  return w.bytes() + tail;
}

// Value bytes for TiffField in one byte order.
inline std::string tiff_short(bool little, uint16_t v) {
  TiffWriter w(little);
  w.u16(v);
  return w.bytes();
}
inline std::string tiff_long(bool little, uint32_t v) {
  TiffWriter w(little);
  w.u32(v);
  return w.bytes();
}
inline std::string tiff_rational(bool little, uint32_t num, uint32_t den) {
  TiffWriter w(little);
  w.u32(num), w.u32(den);
  return w.bytes();
}

// The APP1 "Exif\0\0" segment holding a TIFF block.
inline std::string exif_segment(const std::string& tiff) {
  const std::string payload = std::string("Exif\0\0", 6) + tiff;
  const size_t length = payload.size() + 2;
  return std::string("\xFF\xE1", 2) + char(length >> 8) + char(length & 0xFF) + payload;
}

// An encoded JPEG (starting with SOI) with the EXIF segment placed right after its SOI.
inline std::string with_exif(const std::string& jpeg, const std::string& tiff) {
  return jpeg.substr(0, 2) + exif_segment(tiff) + jpeg.substr(2);
}

}  // namespace lc2wf::testing

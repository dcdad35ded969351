// The EXIF GPS reader (dataset/photo/exif_gps.h) on hand-made JPEG byte buffers, both byte orders, and broken
// files (cut short, offsets past the end, zero denominators, huge IFDs): never a crash, always a reason.
#include "dataset/photo/exif_gps.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/photo/local_enu.h"

namespace lc2wf {
namespace {

// A TIFF block with IFD0 (one entry: the GPS IFD pointer) and a GPS IFD, in either byte order.
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

// 47 deg 22' 35.5" N, 8 deg 32' 26.25" E, 431.7 m (or the refs given).
std::string gps_tiff(bool little, char lat_ref = 'N', char lon_ref = 'E', uint8_t alt_ref = 0, uint32_t alt_den = 10) {
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
  for (const Dms& v : {Dms{47, 22, 355, 10}, Dms{8, 32, 2625, 100}}) w.u32(v.d), w.u32(1), w.u32(v.m), w.u32(1), w.u32(v.s_num), w.u32(v.s_den);
  w.u32(4317), w.u32(alt_den);
  return w.bytes();
}

// SOI, an APP0 segment, APP1 "Exif\0\0" + the TIFF block, then the start of the image data.
std::string jpeg_with(const std::string& tiff) {
  std::string j = "\xFF\xD8";
  j += std::string("\xFF\xE0\x00\x06JFIF", 8);
  const std::string payload = std::string("Exif\0\0", 6) + tiff;
  const size_t length = payload.size() + 2;
  j += "\xFF\xE1";
  j += char(length >> 8), j += char(length & 0xFF);
  j += payload;
  j += std::string("\xFF\xDA\x00\x02", 4) + std::string(100, '\x55');
  return j;
}

TEST(ExifGps, ReadsLatitudeLongitudeAltitudeInBothByteOrders) {
  for (bool little : {true, false}) {
    std::string why;
    const std::optional<GpsFix> f = exif_gps(jpeg_with(gps_tiff(little)), &why);
    ASSERT_TRUE(f) << why;
    EXPECT_NEAR(f->latitude_deg, 47 + 22 / 60.0 + 35.5 / 3600, 1e-12);
    EXPECT_NEAR(f->longitude_deg, 8 + 32 / 60.0 + 26.25 / 3600, 1e-12);
    EXPECT_TRUE(f->has_altitude);
    EXPECT_NEAR(f->altitude_m, 431.7, 1e-12);
  }
  const std::optional<GpsFix> sw = exif_gps(jpeg_with(gps_tiff(true, 'S', 'W', 1)));
  ASSERT_TRUE(sw);
  EXPECT_LT(sw->latitude_deg, 0);
  EXPECT_LT(sw->longitude_deg, 0);
  EXPECT_NEAR(sw->altitude_m, -431.7, 1e-12);
}

TEST(ExifGps, NoExifOrNoGpsIsNoFixWithAReason) {
  std::string why;
  EXPECT_FALSE(exif_gps("not a jpeg at all", &why));
  EXPECT_EQ(why, "not a JPEG");
  EXPECT_FALSE(exif_gps(std::string("\xFF\xD8\xFF\xDA\x00\x02", 6), &why));
  EXPECT_EQ(why, "no EXIF");
  TiffWriter w(true);
  w.bytes() += std::string("II*\0", 4);
  w.u32(8), w.u16(0), w.u32(0);  // an IFD0 without entries
  EXPECT_FALSE(exif_gps(jpeg_with(w.bytes()), &why));
  EXPECT_EQ(why, "no GPS");
}

TEST(ExifGps, BrokenFilesGiveAReasonNeverACrash) {
  std::string why;
  const std::string good = jpeg_with(gps_tiff(true));
  // Cut at every length: never a crash, never a fix from a block cut before its rationals.
  for (size_t n = 0; n < good.size(); ++n) {
    const std::optional<GpsFix> f = exif_gps(std::string_view(good).substr(0, n), &why);
    if (f) EXPECT_NEAR(f->altitude_m, 431.7, 1e-9);
  }
  // Every byte of the TIFF block flipped in turn: no crash; what comes back is either a reason or a fix.
  const std::string tiff = gps_tiff(false);
  for (size_t k = 0; k < tiff.size(); ++k) {
    std::string t = tiff;
    t[k] = char(t[k] ^ 0xFF);
    exif_gps(jpeg_with(t), &why);
  }
  EXPECT_FALSE(exif_gps(jpeg_with(gps_tiff(true, 'N', 'E', 0, 0)), &why));
  EXPECT_EQ(why, "EXIF: a GPS rational with denominator 0");
  std::string huge = gps_tiff(true);
  huge[8] = char(0xFF), huge[9] = char(0xFF);  // IFD0 claims 65,535 entries
  EXPECT_FALSE(exif_gps(jpeg_with(huge), &why));
  EXPECT_NE(why.find("entries"), std::string::npos);
}

TEST(LocalEnu, MetresEastNorthUpAroundTheMeanFix) {
  // 0.001 deg of latitude is ~111 m north; of longitude at 47 deg ~76 m east; 10 m of altitude is up.
  const std::vector<GpsFix> fixes = {{47.0, 8.0, 400, true}, {47.001, 8.0, 400, true}, {47.0, 8.001, 410, true}};
  const std::vector<Vec3> p = local_enu(fixes);
  ASSERT_EQ(p.size(), 3u);
  const Vec3 north = p[1] - p[0], east = p[2] - p[0];
  EXPECT_NEAR(north.y(), 111.2, 0.3);
  EXPECT_NEAR(std::abs(north.x()), 0.0, 0.01);
  EXPECT_NEAR(east.x(), 76.0, 0.3);
  EXPECT_NEAR(east.z(), 10.0, 0.01);
}

}  // namespace
}  // namespace lc2wf

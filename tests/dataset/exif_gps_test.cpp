// The EXIF GPS reader (dataset/photo/exif_gps.h) on hand-made JPEG byte buffers, both byte orders, and broken
// files (cut short, offsets past the end, zero denominators, huge IFDs): never a crash, always a reason.
#include "dataset/photo/exif_gps.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/photo/local_enu.h"
#include "tests/common/exif_gps_jpeg.h"

namespace lc2wf {
namespace {

using testing::Dms;
using testing::TiffWriter;

// 47 deg 22' 35.5" N, 8 deg 32' 26.25" E, 431.7 m (or the refs given).
std::string gps_tiff(bool little, char lat_ref = 'N', char lon_ref = 'E', uint8_t alt_ref = 0, uint32_t alt_den = 10) {
  return testing::gps_tiff(little, Dms{47, 22, 355, 10}, lat_ref, Dms{8, 32, 2625, 100}, lon_ref, alt_ref, 4317, alt_den);
}

// SOI, an APP0 segment, APP1 "Exif\0\0" + the TIFF block, then the start of the image data.
std::string jpeg_with(const std::string& tiff) {
  return testing::with_exif(std::string("\xFF\xD8\xFF\xE0\x00\x06JFIF", 10) + std::string("\xFF\xDA\x00\x02", 4) + std::string(100, '\x55'),
                            tiff);
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

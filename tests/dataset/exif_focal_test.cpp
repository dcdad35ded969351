// The EXIF focal-length reader (dataset/photo/exif_focal.h) on hand-made JPEG byte buffers: the 35 mm
// equivalent as phones write it, the focal length over the sensor size as cameras write it, both byte orders,
// and broken or implausible values (a reason, never a crash).
#include "dataset/photo/exif_focal.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/common/exif_gps_jpeg.h"

namespace lc2wf {
namespace {

using testing::TiffField;

std::string jpeg_with(const std::string& tiff) {
  return testing::with_exif(std::string("\xFF\xD8\xFF\xE0\x00\x06JFIF", 10) + std::string("\xFF\xDA\x00\x02", 4) + std::string(100, '\x55'),
                            tiff);
}

constexpr uint16_t kShort = 3, kLong = 4, kRational = 5;

TEST(ExifFocal, ThirtyFiveMillimetreEquivalentAsPhonesWriteIt) {
  for (bool little : {true, false}) {
    std::string why;
    const auto f = exif_focal(jpeg_with(testing::exif_ifd_tiff(little, {{0x920A, kRational, 1, testing::tiff_rational(little, 43, 10)},
                                                                         {0xA405, kShort, 1, testing::tiff_short(little, 26)}})),
                              4032, &why);
    ASSERT_TRUE(f) << why;
    EXPECT_EQ(f->focal_35mm, 26.0);  // the equivalent wins over the 4.3 mm of the small sensor
    EXPECT_EQ(f->tags, "FocalLengthIn35mmFilm");
  }
}

// A camera without the equivalent: 18 mm on an APS-C sensor of 23.6 mm (6000 px at 6000 / 23.6 px per mm),
// 27.5 mm equivalent; the resolution in inches (EXIF's default unit) gives the same.
TEST(ExifFocal, FocalLengthOverTheSensorSize) {
  for (bool little : {true, false}) {
    const double px_per_mm = 6000 / 23.6;
    std::string why;
    auto f = exif_focal(jpeg_with(testing::exif_ifd_tiff(little, {{0x920A, kRational, 1, testing::tiff_rational(little, 18, 1)},
                                                                   {0xA20E, kRational, 1, testing::tiff_rational(little, uint32_t(px_per_mm * 1e4), 10000)},
                                                                   {0xA210, kShort, 1, testing::tiff_short(little, 4)}})),
                        6000, &why);
    ASSERT_TRUE(f) << why;
    EXPECT_NEAR(f->focal_35mm, 18 * 36 / 23.6, 0.01);
    EXPECT_EQ(f->tags, "FocalLength, FocalPlaneXResolution");
    // Inches, and the pixel dimensions of the EXIF rather than the caller's (a photo scaled down since).
    f = exif_focal(jpeg_with(testing::exif_ifd_tiff(little, {{0x920A, kRational, 1, testing::tiff_rational(little, 18, 1)},
                                                              {0xA002, kLong, 1, testing::tiff_long(little, 6000)},
                                                              {0xA003, kLong, 1, testing::tiff_long(little, 4000)},
                                                              {0xA20E, kRational, 1, testing::tiff_rational(little, uint32_t(px_per_mm * 25.4 * 1e4), 10000)}})),
                   1500, &why);
    ASSERT_TRUE(f) << why;
    EXPECT_NEAR(f->focal_35mm, 18 * 36 / 23.6, 0.01);
  }
}

TEST(ExifFocal, NoneOrBrokenGivesAReason) {
  const bool le = true;
  std::string why;
  EXPECT_FALSE(exif_focal("not a jpeg", 100, &why));
  EXPECT_EQ(why, "not a JPEG");
  EXPECT_FALSE(exif_focal(jpeg_with(testing::orientation_tiff(1)), 100, &why));
  EXPECT_EQ(why, "no Exif IFD");
  EXPECT_FALSE(exif_focal(jpeg_with(testing::exif_ifd_tiff(le, {{0xA405, kShort, 1, testing::tiff_short(le, 0)}})), 100, &why));
  EXPECT_EQ(why, "no focal length");  // 0 is EXIF's "unknown"
  EXPECT_FALSE(exif_focal(jpeg_with(testing::exif_ifd_tiff(le, {{0x920A, kRational, 1, testing::tiff_rational(le, 18, 1)}})), 100, &why));
  EXPECT_EQ(why, "a focal length in mm but no sensor size (FocalPlaneXResolution)");
  EXPECT_FALSE(exif_focal(jpeg_with(testing::exif_ifd_tiff(le, {{0xA405, kShort, 1, testing::tiff_short(le, 3)}})), 100, &why));
  EXPECT_EQ(why, "FocalLengthIn35mmFilm 3.000000 mm is implausible");
  EXPECT_FALSE(exif_focal(jpeg_with(testing::exif_ifd_tiff(le, {{0x920A, kRational, 1, testing::tiff_rational(le, 18, 0)}})), 100, &why));
  EXPECT_EQ(why, "EXIF: FocalLength with denominator 0");
  EXPECT_FALSE(exif_focal(jpeg_with(testing::exif_ifd_tiff(le, {{0xA405, kRational, 1, testing::tiff_rational(le, 18, 1)}})), 100, &why));
  EXPECT_EQ(why, "EXIF: FocalLengthIn35mmFilm that is not a whole number");
  // An Exif IFD pointer past the end of the block: cut short, not read beyond.
  std::string cut = testing::exif_ifd_tiff(le, {{0xA405, kShort, 1, testing::tiff_short(le, 26)}});
  cut.resize(28);
  EXPECT_FALSE(exif_focal(jpeg_with(cut), 100, &why));
  EXPECT_EQ(why, "EXIF: offset beyond the segment");
}

}  // namespace
}  // namespace lc2wf

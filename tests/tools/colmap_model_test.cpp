// COLMAP model folders read without COLMAP: text and binary give the same cameras, and hostile files are
// refused naming the file and the field (a header claiming 2^62 cameras, a zero quaternion, a FIFO).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "dataset/formats/errors.h"
#include "tools/colmap/colmap_model.h"

namespace lc2wf {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_colmap_model_test_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

template <class T>
void put(std::string& s, T v) {
  char raw[sizeof(T)];
  std::memcpy(raw, &v, sizeof(T));  // the test machine is little-endian, as COLMAP's files are
  s.append(raw, sizeof(T));
}

// n cameras on a ring looking at the building (built here so the test needs only the reader).
std::vector<Camera> ring(int n) {
  std::vector<Camera> cams;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Vec3 eye(25 * std::cos(a), 25 * std::sin(a), 8 + i % 3 * 4);
    const Vec3 z = (Vec3(0, 0, 2) - eye).normalized(), x = z.cross(Vec3(0, 0, 1)).normalized(), y = z.cross(x);
    Camera c;
    c.K << 622.2, 0, 319.5, 0, 622.2, 239.5, 0, 0, 1;
    c.R.row(0) = x, c.R.row(1) = y, c.R.row(2) = z;
    c.t = -c.R * eye;
    c.width = 640, c.height = 480;
    cams.push_back(c);
  }
  return cams;
}

// The same model in both layouts: camera 3 PINHOLE, images 1..n with one 2D point each.
void write_text_model(const fs::path& dir, const std::vector<Camera>& cams) {
  write(dir / "cameras.txt", "# Camera list\n3 PINHOLE 640 480 622.2 622.2 320 240\n");
  std::ofstream im(dir / "images.txt");
  im.precision(17);
  for (size_t i = 0; i < cams.size(); ++i) {
    const auto q = rotation_to_quaternion(cams[i].R);
    im << i + 1 << " " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << " " << cams[i].t.x() << " " << cams[i].t.y() << " "
       << cams[i].t.z() << " 3 view_" << i << ".png\n10.5 20.5 -1\n";
  }
}

void write_binary_model(const fs::path& dir, const std::vector<Camera>& cams) {
  std::string c;
  put<uint64_t>(c, 1);
  put<uint32_t>(c, 3), put<int32_t>(c, 1), put<uint64_t>(c, 640), put<uint64_t>(c, 480);
  for (double v : {622.2, 622.2, 320.0, 240.0}) put(c, v);
  write(dir / "cameras.bin", c);
  std::string im;
  put<uint64_t>(im, cams.size());
  for (size_t i = 0; i < cams.size(); ++i) {
    put<uint32_t>(im, static_cast<uint32_t>(i + 1));
    const auto q = rotation_to_quaternion(cams[i].R);
    for (int k = 0; k < 4; ++k) put(im, q[k]);
    for (int k = 0; k < 3; ++k) put(im, cams[i].t[k]);
    put<uint32_t>(im, 3);
    im += "view_" + std::to_string(i) + ".png";
    im += '\0';
    put<uint64_t>(im, 1), put(im, 10.5), put(im, 20.5), put<uint64_t>(im, ~uint64_t{0});
  }
  write(dir / "images.bin", im);
}

// Matched by name, as lc2wf-reconstruct does: COLMAP writes its images in no particular order.
void expect_same(const std::vector<ColmapImage>& model, const std::vector<Camera>& cams) {
  ASSERT_EQ(model.size(), cams.size());
  for (const ColmapImage& im : model) {
    const size_t i = static_cast<size_t>(std::stoi(im.name.substr(5)));
    ASSERT_EQ(im.name, "view_" + std::to_string(i) + ".png");
    EXPECT_LT((im.camera.K - cams[i].K).norm(), 1e-9);
    EXPECT_LT((im.camera.R - cams[i].R).norm(), 1e-12);
    EXPECT_LT((im.camera.t - cams[i].t).norm(), 1e-12);
    EXPECT_EQ(im.camera.width, 640);
  }
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const DataError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ColmapModel, BinaryAndTextModelsGiveTheSameCameras) {
  const auto cams = ring(4);
  const fs::path text = scratch("text"), binary = scratch("binary");
  write_text_model(text, cams);
  write_binary_model(binary, cams);
  expect_same(read_colmap_model(text), cams);
  expect_same(read_colmap_model(binary), cams);
}

TEST(ColmapModel, ReadsTheBinaryModelColmapWrites) {
  if (std::system("command -v colmap >/dev/null 2>&1") != 0) GTEST_SKIP() << "colmap not found on PATH (apt-get install colmap)";
  const auto cams = ring(3);
  const fs::path text = scratch("colmap_text"), binary = scratch("colmap_binary");
  write_text_model(text, cams);
  write(text / "points3D.txt", "");
  const std::string cmd = "colmap model_converter --input_path " + text.string() + " --output_path " + binary.string() +
                          " --output_type BIN >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  expect_same(read_colmap_model(binary), cams);
}

TEST(ColmapModel, HostileBinaryHeadersAreRefusedBeforeReadingOn) {
  std::string huge;
  put<uint64_t>(huge, uint64_t{1} << 62);  // 2^62 cameras in an 8-byte file: COLMAP itself aborts
  EXPECT_EQ(error_of([&] { parse_colmap_cameras_bin(huge, "m/cameras.bin"); }), "m/cameras.bin: byte 8: file ends inside camera_id of camera 1");

  ColmapCameras one;
  one[1].width = one[1].height = 10;
  std::string im;
  put<uint64_t>(im, 1), put<uint32_t>(im, 1);
  for (double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}) put(im, v);
  put<uint32_t>(im, 1);
  im += std::string("a.png") + '\0';
  std::string points = im;
  put<uint64_t>(points, uint64_t{1} << 60);  // 2D points claimed, none present
  EXPECT_EQ(error_of([&] { parse_colmap_images_bin(points, "images.bin", one); }),
            "images.bin: byte 86: num_points2D of image 1 count 1152921504606846976 exceeds the bytes left in the file");
  std::string trailing = im;
  put<uint64_t>(trailing, 0);
  trailing += "xyz";
  EXPECT_EQ(error_of([&] { parse_colmap_images_bin(trailing, "images.bin", one); }), "images.bin: byte 86: 3 bytes after the last of 1 images");
  std::string unnamed = im.substr(0, im.size() - 6);  // the name loses its NUL
  EXPECT_EQ(error_of([&] { parse_colmap_images_bin(unnamed, "images.bin", one); }),
            "images.bin: byte 72: file ends inside name of image 1 (no terminating NUL)");

  std::string model;
  put<uint64_t>(model, 1), put<uint32_t>(model, 1), put<int32_t>(model, 4), put<uint64_t>(model, 640), put<uint64_t>(model, 480);
  EXPECT_EQ(error_of([&] { parse_colmap_cameras_bin(model, "cameras.bin"); }),
            "cameras.bin: camera 1 at byte 8: unsupported camera model id 4 (0-3: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL)");
  std::string wide;
  put<uint64_t>(wide, 1), put<uint32_t>(wide, 1), put<int32_t>(wide, 0), put<uint64_t>(wide, uint64_t{1} << 40), put<uint64_t>(wide, 480);
  for (double v : {500.0, 320.0, 240.0}) put(wide, v);
  EXPECT_EQ(error_of([&] { parse_colmap_cameras_bin(wide, "cameras.bin"); }),
            "cameras.bin: camera 1 at byte 8: image size 1099511627776 x 480 outside 1..1000000");
}

TEST(ColmapModel, BadTextFieldsNameTheFileLineAndField) {
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("1 PINHOLE 640 480 0 500 320 240\n", "cameras.txt"); }),
            "cameras.txt:1: focal length must be > 0");
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("# c\n1 PINHOLE 640 480 1 1 1 1\n1 PINHOLE 640 480 1 1 1 1\n", "cameras.txt"); }),
            "cameras.txt:3: camera id 1 is listed twice");
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("1 OPENCV 640 480 1 1 1 1 0.1 0 0 0\n", "cameras.txt"); }),
            "cameras.txt:1: unsupported camera model 'OPENCV' (PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL or RADIAL)");
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("1 SIMPLE_RADIAL 640 480 500 320 240 0.1\n", "cameras.txt"); }),
            "cameras.txt:1: lens distortion is not supported; undistort the images first");
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("1 PINHOLE 0 480 1 1 1 1\n", "cameras.txt"); }),
            "cameras.txt:1: image size 0 x 480 outside 1..1000000");
  EXPECT_EQ(error_of([] { parse_colmap_cameras_txt("1 PINHOLE 640 480 1 1 nan 1\n", "cameras.txt"); }),
            "cameras.txt:1: parameter 'nan' is not a finite number");

  const ColmapCameras cams = parse_colmap_cameras_txt("1 PINHOLE 640 480 500 500 320 240\n", "cameras.txt");
  // A zero quaternion has no rotation: Eigen would normalise it to NaN.
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 0 0 0 0 0 0 0 1 a.png\n\n", "images.txt", cams); }),
            "images.txt:1: quaternion is zero (no rotation)");
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 2e9 1 a.png\n\n", "images.txt", cams); }),
            "images.txt:1: translation is not finite or beyond +-1e9");
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 1e999 1 a.png\n\n", "images.txt", cams); }),
            "images.txt:1: TZ '1e999' is not a finite number");
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 7 a.png\n\n", "images.txt", cams); }),
            "images.txt:1: unknown camera id 7");
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 1\n\n", "images.txt", cams); }),
            "images.txt:1: expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, found 9 values");
  EXPECT_EQ(error_of([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 a.png\n\n1 1 0 0 0 0 0 0 1 b.png\n", "images.txt", cams); }),
            "images.txt:3: image id 1 is listed twice");
}

TEST(ColmapModel, FifoAndDirectoryFilesAreRefusedWithoutBlocking) {
  const fs::path dir = scratch("fifo");
  write(dir / "cameras.txt", "1 PINHOLE 640 480 500 500 320 240\n");
  ASSERT_EQ(mkfifo((dir / "images.txt").c_str(), 0600), 0);
  EXPECT_EQ(error_of([&] { read_colmap_model(dir); }), (dir / "images.txt").string() + ": is not a regular file (a FIFO, socket or device)");
  const fs::path bin = scratch("dir");
  fs::create_directories(bin / "cameras.bin");
  write(bin / "images.bin", "");
  EXPECT_EQ(error_of([&] { read_colmap_model(bin); }), (bin / "cameras.bin").string() + ": is a directory, not a file");
  const fs::path empty = scratch("empty");
  EXPECT_EQ(error_of([&] { read_colmap_model(empty); }),
            empty.string() + ": not a COLMAP model (no cameras.txt/images.txt or cameras.bin/images.bin)");
}

}  // namespace
}  // namespace lc2wf

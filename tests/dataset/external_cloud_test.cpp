// Readers for line clouds made elsewhere (Line3D++ .txt, LIMAP finaltracks/, line OBJ) and our converter
// to Line3D++ .txt. Every fixture is written here.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/limap_io.h"
#include "dataset/formats/line3dpp_io.h"
#include "dataset/formats/line_obj_io.h"
#include "dataset/sampling/rng.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "test_util.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

// Two lines: one of two collinear segments with three supports, one of one segment without supports.
const char* kLine3dpp =
    "2 0 0 0 1 0 0 1.5 0 0 3 0 0 3 1 7 10 20 30 40 2 3 11 21 31 41 5 0 1.5 2.5 3.5 4.5\n"
    "\n"
    "1 0 0 1 0 0 2.25 0\n";

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const DataError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Line3dppTxt, ParsesSegmentsAndSupports) {
  const ExternalLineMap map = parse_line3dpp_txt(kLine3dpp, "l.txt");
  ASSERT_EQ(map.lines.size(), 2u);
  ASSERT_EQ(map.lines[0].segments.size(), 2u);
  EXPECT_EQ(map.lines[0].segments[1].a, Vec3(1.5, 0, 0));
  EXPECT_EQ(map.lines[0].segments[1].b, Vec3(3, 0, 0));
  ASSERT_EQ(map.lines[0].supports.size(), 3u);
  EXPECT_EQ(map.lines[0].supports[1].image_id, 2);
  EXPECT_EQ(map.lines[0].supports[1].segment_id, 3);
  EXPECT_EQ(map.lines[0].supports[2].seg.b, Vec2(3.5, 4.5));
  EXPECT_TRUE(map.lines[1].supports.empty());
  EXPECT_TRUE(looks_like_line3dpp_txt(kLine3dpp));
  EXPECT_FALSE(looks_like_line3dpp_txt("{\"format\": 1}"));
  EXPECT_FALSE(looks_like_line3dpp_txt("1 0 0 0 1 1 1 2 5"));  // m = 2 but no supports follow
}

TEST(Line3dppTxt, ConversionKeepsSupportsOnlyWithCameras) {
  const ExternalLineMap map = parse_line3dpp_txt(kLine3dpp, "l.txt");
  ExternalConversionReport report;
  const LineCloud bare = to_line_cloud(map, "b", "l.txt", {}, &report);
  EXPECT_EQ(bare.segments.size(), 3u);  // each collinear segment is its own cloud segment
  EXPECT_TRUE(bare.support.empty());
  EXPECT_EQ(report.supports_dropped, 3);

  std::map<long long, Camera> cameras;
  for (long long id : {1, 2}) {
    Camera c;
    c.K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
    c.t = Vec3(0, 0, 10);
    c.width = 640;
    c.height = 480;
    cameras[id] = c;
  }
  ExternalConversionOptions options;
  options.cameras = &cameras;
  options.metres_per_unit = 2.0;
  ExternalConversionReport r2;
  const LineCloud cloud = to_line_cloud(map, "b", "l.txt", options, &r2);
  ASSERT_EQ(cloud.support.size(), 3u);
  EXPECT_EQ(cloud.support[0].size(), 2u);  // image 5 has no camera
  EXPECT_EQ(cloud.support[1].size(), 2u);
  EXPECT_EQ(cloud.support[0][1].view, 1);
  EXPECT_EQ(r2.supports_dropped, 1);
  EXPECT_EQ(cloud.segments[2].b, Vec3(0, 0, 4.5));
}

TEST(Line3dppTxt, MalformedInputNamesLineAndField) {
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("1 0 0 0 1 0 0 0\n1 0 0 0 1 x 0 0\n", "f.txt"); }),
            "f.txt:2: Qy of segment 1 'x' is not a finite number");
  // A count far beyond what the line holds fails before any allocation.
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("999999999999999 0 0 0 1 0 0 0\n", "f.txt"); }),
            "f.txt:1: segment count n = 999999999999999 exceeds the numbers on the line");
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("1 0 0 0 1 0 0 2 1 0 1 2 3 4\n", "f.txt"); }),
            "f.txt:1: support count m = 2 does not match the 6 values after it (6 per support)");
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("1 0 0 0 1 0 0 1 -1 0 1 2 3 4\n", "f.txt"); }),
            "f.txt:1: camera id of support 1 '-1' is not an integer >= 0");
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("0 1\n", "f.txt"); }), "f.txt:1: segment count n '0' is not an integer >= 1");
  EXPECT_EQ(error_of([] { parse_line3dpp_txt("\n# nothing\n", "f.txt"); }), "f.txt: no 3D line (empty Line3D++ file)");
  EXPECT_EQ(error_of([] { to_line_cloud(parse_line3dpp_txt("1 1 1 1 1 1 1 0\n", "f.txt"), "z", "f.txt"); }),
            "f.txt: no 3D line segment");
}

TEST(Line3dppTxt, GarbageNeverCrashes) {
  DataRng rng(99);
  for (int trial = 0; trial < 200; ++trial) {
    std::string bytes(1 + rng.next() % 300, '\0');
    for (char& c : bytes) c = trial % 2 ? static_cast<char>(rng.next()) : "0123456789 .-e\n"[rng.next() % 15];
    try {
      parse_line3dpp_txt(bytes, "g.txt");
    } catch (const DataError&) {
    }
  }
}

TEST(Line3dppTxt, ConverterRoundTripsOurCloud) {
  SyntheticCloudOptions o;
  o.cameras.num_views = 6;
  const LineCloud ours = make_synthetic_line_cloud(make_rect_building("box", RectBuildingSpec{}), 3, o);
  const fs::path file = test::scratch_dir("l3dpp_roundtrip") / "box.txt";
  write_line3dpp_txt(file, ours);
  std::map<long long, Camera> cameras;
  for (size_t v = 0; v < ours.cameras.size(); ++v) cameras[static_cast<long long>(v) + 1] = ours.cameras[v];
  ExternalConversionOptions options;
  options.cameras = &cameras;
  const LineCloud back = to_line_cloud(read_line3dpp_txt(file), "box", file.string(), options);
  ASSERT_EQ(back.segments.size(), ours.segments.size());
  for (size_t k = 0; k < ours.segments.size(); ++k) {
    EXPECT_LT((back.segments[k].a - ours.segments[k].a).norm(), 1e-6);
    EXPECT_LT((back.segments[k].b - ours.segments[k].b).norm(), 1e-6);
    ASSERT_EQ(back.support[k].size(), ours.support[k].size());
    for (size_t s = 0; s < ours.support[k].size(); ++s) {
      EXPECT_EQ(back.support[k][s].view, ours.support[k][s].view);
      EXPECT_LT((back.support[k][s].seg.a - ours.support[k][s].seg.a).norm(), 1e-5);
    }
  }
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string limap_track(const std::string& line, int n, const std::string& tail = "END\n") {
  std::string s = line + "\n" + std::to_string(n) + " " + std::to_string(n) + "\nimage_id_list";
  for (int k = 0; k < n; ++k) s += " " + std::to_string(k + 1);
  s += "\nline_id_list";
  for (int k = 0; k < n; ++k) s += " " + std::to_string(10 + k);
  s += "\nline2d_list\n";
  for (int k = 0; k < n; ++k) s += "1.0000000000 2.0000000000 3.0000000000 " + std::to_string(4 + k) + ".0000000000\n";
  return s + "score_list 1 1\n" + tail;
}

TEST(LimapTracks, ReadsFinaltracksInOrder) {
  const fs::path out = test::scratch_dir("limap_ok");
  fs::create_directories(out / "finaltracks");
  write(out / "finaltracks" / "track_0.txt", limap_track("0 0 0 1 0 0", 2));
  write(out / "finaltracks" / "track_1.txt", limap_track("0 0 0 0 0 2", 3));
  EXPECT_TRUE(is_limap_tracks_dir(out));
  EXPECT_TRUE(is_limap_tracks_dir(out / "finaltracks"));
  const ExternalLineMap map = read_limap_tracks(out);
  ASSERT_EQ(map.lines.size(), 2u);
  EXPECT_EQ(map.lines[1].segments[0].b, Vec3(0, 0, 2));
  ASSERT_EQ(map.lines[1].supports.size(), 3u);
  EXPECT_EQ(map.lines[1].supports[2].image_id, 3);
  EXPECT_EQ(map.lines[1].supports[2].segment_id, 12);
  EXPECT_EQ(map.lines[1].supports[2].seg.b, Vec2(3, 6));
}

TEST(LimapTracks, MalformedInputNamesFileLineAndField) {
  const fs::path dir = test::scratch_dir("limap_bad");
  write(dir / "track_0.txt", limap_track("0 0 0 1 0 0", 1));
  write(dir / "track_2.txt", limap_track("0 0 0 1 0 0", 1));
  EXPECT_THAT(error_of([&] { read_limap_tracks(dir); }), HasSubstr("track_1.txt: missing"));
  EXPECT_EQ(error_of([] { parse_limap_track("0 0 0 1 0 nan\n1 1\n", "t.txt"); }),
            "t.txt:1: end coordinate 'nan' is not a finite number");
  EXPECT_EQ(error_of([] { parse_limap_track("0 0 0 1 0 0\n1000000000 1\nimage_id_list 1\n", "t.txt"); }),
            "t.txt:2: n_lines = 1000000000 exceeds the lines left in the file");
  EXPECT_EQ(error_of([] { parse_limap_track("0 0 0 1 0 0\n1 1\nimage_ids 1\nline_id_list 1\nline2d_list\n1 2 3 4\n", "t.txt"); }),
            "t.txt:3: expected the keyword 'image_id_list'");
  EXPECT_EQ(error_of([] { parse_limap_track("0 0 0 1 0 0\n2 1\nimage_id_list 1\nline_id_list 1 2\nline2d_list\n1 2 3 4\n1 2\n", "t.txt"); }),
            "t.txt:3: image_id_list needs n_lines = 2 ids, found 1");
  EXPECT_EQ(error_of([] { parse_limap_track("0 0 0 1 0 0\n1 1\nimage_id_list 1\nline_id_list 1\nline2d_list\n", "t.txt"); }),
            "t.txt: file ends before 2D segment row 1");
}

TEST(LineObj, ReadsSegmentsAndRejectsMeshes) {
  const fs::path dir = test::scratch_dir("line_obj");
  write(dir / "c.obj", "# Line3D++\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 1 2\nl 1 2\nl 3 4\n");
  const ExternalLineMap map = read_line_obj(dir / "c.obj");
  ASSERT_EQ(map.lines.size(), 2u);
  EXPECT_EQ(map.lines[1].segments[0].b, Vec3(0, 1, 2));
  write(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(error_of([&] { read_line_obj(dir / "m.obj"); }), (dir / "m.obj").string() + ": has faces ('f'): a line-cloud OBJ holds 'v' and 'l' only");
  write(dir / "e.obj", "v 0 0 0\nl 1 7\n");
  EXPECT_EQ(error_of([&] { read_line_obj(dir / "e.obj"); }), (dir / "e.obj").string() + ":2: vertex reference 7 out of range (1 vertices so far)");

  SyntheticCloudOptions o;
  o.cameras.num_views = 4;
  const LineCloud ours = make_synthetic_line_cloud(make_rect_building("box", RectBuildingSpec{}), 5, o);
  write_line_obj(dir / "ours.obj", ours);
  const LineCloud back = to_line_cloud(read_line_obj(dir / "ours.obj"), "ours", "ours.obj");
  ASSERT_EQ(back.segments.size(), ours.segments.size());
  EXPECT_LT((back.segments.back().b - ours.segments.back().b).norm(), 1e-6);
}

}  // namespace
}  // namespace lc2wf

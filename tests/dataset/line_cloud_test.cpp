#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/labels/labelling.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"
#include "dataset/labels/visibility.h"
#include "test_util.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

LineCloud small_cloud() {
  const Building b = make_rect_building("box", RectBuildingSpec{});
  SyntheticCloudOptions o;
  o.cameras.num_views = 6;
  return make_synthetic_line_cloud(b, 7, o);
}

void expect_same(const LineCloud& x, const LineCloud& y) {
  ASSERT_EQ(x.segments.size(), y.segments.size());
  EXPECT_EQ(x.name, y.name);
  for (size_t i = 0; i < x.segments.size(); ++i) {
    EXPECT_EQ(x.segments[i].a, y.segments[i].a);
    EXPECT_EQ(x.segments[i].b, y.segments[i].b);
  }
  ASSERT_EQ(x.support.size(), y.support.size());
  for (size_t i = 0; i < x.support.size(); ++i) {
    ASSERT_EQ(x.support[i].size(), y.support[i].size());
    for (size_t k = 0; k < x.support[i].size(); ++k) {
      EXPECT_EQ(x.support[i][k].view, y.support[i][k].view);
      EXPECT_EQ(x.support[i][k].seg.a, y.support[i][k].seg.a);
      EXPECT_EQ(x.support[i][k].seg.b, y.support[i][k].seg.b);
    }
  }
  ASSERT_EQ(x.cameras.size(), y.cameras.size());
  for (size_t v = 0; v < x.cameras.size(); ++v) {
    EXPECT_EQ(x.cameras[v].K, y.cameras[v].K);
    EXPECT_EQ(x.cameras[v].R, y.cameras[v].R);
    EXPECT_EQ(x.cameras[v].t, y.cameras[v].t);
    EXPECT_EQ(x.cameras[v].width, y.cameras[v].width);
  }
  EXPECT_EQ(x.wireframe.edges, y.wireframe.edges);
  EXPECT_EQ(x.wireframe.junctions, y.wireframe.junctions);
  EXPECT_EQ(x.units.raw_per_metre, y.units.raw_per_metre);
  EXPECT_EQ(x.units.origin_raw, y.units.origin_raw);
  EXPECT_TRUE(x.labels == y.labels);
}

TEST(LineCloudIo, BinaryAndJsonRoundTripExactly) {
  const LineCloud c = small_cloud();
  ASSERT_GT(c.segments.size(), 50u);
  const auto dir = test::scratch_dir("lc_rt");
  write_line_cloud(dir / "b.lc2wf", c);
  LineCloudWriteOptions json;
  json.binary = false;
  write_line_cloud(dir / "j.json", c, json);
  expect_same(c, read_line_cloud(dir / "b.lc2wf"));
  expect_same(c, read_line_cloud(dir / "j.json"));
  EXPECT_LT(std::filesystem::file_size(dir / "b.lc2wf"), std::filesystem::file_size(dir / "j.json"));
}

TEST(LineCloudIo, FingerprintFollowsTheSegmentsAndTheName) {
  const LineCloud c = small_cloud();
  const LineCloud read_back = line_cloud_from_bytes(line_cloud_to_bytes(c), "mem");
  EXPECT_EQ(segments_fingerprint(c), segments_fingerprint(read_back));  // what the stored cloud gives back
  LineCloud moved = c, renamed = c, relabelled = c;
  moved.segments.back().b.z() += 1e-9;
  renamed.name += "x";
  relabelled.labels.clear();
  EXPECT_NE(segments_fingerprint(moved), segments_fingerprint(c));
  EXPECT_NE(segments_fingerprint(renamed), segments_fingerprint(c));
  EXPECT_EQ(segments_fingerprint(relabelled), segments_fingerprint(c));  // labels are not an input to prediction
}

TEST(LineCloudIo, EmptyCloudRoundTrips) {
  LineCloud c;
  c.name = "empty";
  const LineCloud r = line_cloud_from_bytes(line_cloud_to_bytes(c), "mem");
  EXPECT_TRUE(r.segments.empty());
  EXPECT_EQ(r.name, "empty");
}

TEST(LineCloudIo, EndpointLabelsFollowTheTuple) {
  LineCloud c;
  c.wireframe.junctions = {Vec3(0, 0, 0), Vec3(4, 0, 0)};
  c.wireframe.edges = {{0, 1}};
  c.segments = {{Vec3(3.9, 0.1, 0), Vec3(0.5, 0, 0)}, {Vec3(0, 3, 0), Vec3(1, 3, 0)}};
  c.labels = {make_edge_label(c.segments[0], c.wireframe, 0, 1), SegmentLabel{}};
  // The first endpoint sits near junction 1, so i1 = 1.
  EXPECT_EQ(c.labels[0].i1, 1);
  EXPECT_EQ(c.labels[0].i2, 0);
  EXPECT_NEAR(c.labels[0].d1, std::hypot(0.1, 0.1), 1e-12);
  EXPECT_NEAR(c.labels[0].d2, 0.5, 1e-12);
  EXPECT_EQ(endpoint_labels(c), (std::vector<int>{1, 0, -1, -1}));
  EXPECT_EQ(endpoint_labels(c, 0.3), (std::vector<int>{1, -1, -1, -1}));
}

std::string replace_once(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

void expect_error(const std::string& bytes, const std::string& needle) {
  try {
    line_cloud_from_bytes(bytes, "cloud.json");
    FAIL() << "no error, wanted: " << needle;
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("cloud.json")) << e.what();
    EXPECT_THAT(std::string(e.what()), HasSubstr(needle)) << e.what();
  }
}

// A one-edge wireframe with one labelled segment on it.
LineCloud one_labelled_segment() {
  LineCloud c;
  c.name = "t";
  c.wireframe.junctions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  c.wireframe.edges = {{0, 1}};
  c.segments = {{Vec3(0, 0, 0), Vec3(1, 0, 0)}};
  c.labels = {make_edge_label(c.segments[0], c.wireframe, 0, 1)};
  return c;
}

TEST(LineCloudIo, KeepSegmentsKeepsLabelsAndSupportsInStep) {
  const LineCloud c = small_cloud();
  ASSERT_GT(c.segments.size(), 3u);
  ASSERT_EQ(c.support.size(), c.segments.size());
  std::vector<bool> keep(c.segments.size(), false);
  keep[1] = keep[c.segments.size() - 1] = true;
  const LineCloud k = keep_segments(c, keep);
  ASSERT_EQ(k.segments.size(), 2u);
  ASSERT_EQ(k.labels.size(), 2u);
  ASSERT_EQ(k.support.size(), 2u);
  EXPECT_EQ(k.segments[1].b, c.segments.back().b);
  EXPECT_EQ(k.labels[0].i1, c.labels[1].i1);
  EXPECT_EQ(k.support[0].size(), c.support[1].size());
  EXPECT_EQ(k.wireframe.edges, c.wireframe.edges);
  EXPECT_EQ(k.cameras.size(), c.cameras.size());
  EXPECT_NO_THROW(validate_line_cloud(k, "kept"));
  EXPECT_THROW(keep_segments(c, std::vector<bool>(2, true)), std::invalid_argument);
}

TEST(LineCloudIo, BadInputsGiveNamedErrors) {
  const LineCloud c = one_labelled_segment();
  LineCloudWriteOptions json;
  json.binary = false;
  const std::string good = line_cloud_to_bytes(c, json);
  EXPECT_NO_THROW(line_cloud_from_bytes(good, "cloud.json"));
  expect_error("", "file is empty");
  expect_error(good.substr(0, good.size() / 2), "malformed JSON");
  expect_error("garbage", "not a line-cloud file");
  expect_error(replace_once(good, "\"lc2wf-linecloud\"", "\"other\""), "format");
  expect_error(replace_once(good, "\"num_segments\": 1", "\"num_segments\": 2"), "wrong shape");
  expect_error(replace_once(good, "[\n    0,\n    1\n   ]\n  ]", "[\n    0,\n    5\n   ]\n  ]"), "GT edge 0");

  // Non-finite and zero-length segments, junction ids out of range: rejected before writing.
  LineCloud bad = c;
  bad.segments[0].b = Vec3(std::nan(""), 0, 0);
  EXPECT_THROW(line_cloud_to_bytes(bad), DataError);
  bad = c;
  bad.segments[0].b = bad.segments[0].a;
  try {
    line_cloud_to_bytes(bad);
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("segment 0 has zero length"));
  }
  bad = c;
  bad.labels[0].i2 = 9;
  EXPECT_THROW(line_cloud_to_bytes(bad), DataError);
  bad = c;
  bad.support = {{Observation{3, {}}}};
  try {
    line_cloud_to_bytes(bad);
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("support view 3 out of range")) << e.what();
  }

  // Binary: truncated blob and a header length past the end.
  const std::string bin = line_cloud_to_bytes(c);
  expect_error(bin.substr(0, bin.size() - 8), "outside the binary block");
  expect_error(replace_once(bin, bin.substr(0, bin.find('\n')), "LC2WF-LINECLOUD 1 999999"), "header runs past");
  expect_error(replace_once(bin, "LC2WF-LINECLOUD 1", "LC2WF-LINECLOUD 7"), "unsupported version 7");
  // A NaN written straight into the binary block (segments come first in the blob).
  const size_t first_line = bin.find('\n');
  const size_t header_len = std::stoul(bin.substr(bin.rfind(' ', first_line) + 1, first_line));
  std::string nan_bin = bin;
  const double nan = std::nan("");
  std::memcpy(&nan_bin[first_line + 1 + header_len], &nan, sizeof nan);
  expect_error(nan_bin, "segment 0 has a non-finite coordinate");
}

// Regression: header counts are checked against the file size before allocating (a 224 KB file claiming
// 10^8 segments reached 4.5 GB), and JSON numbers are exact (0.7 -> 0, true -> 1, 300 -> 44 in a byte).
TEST(LineCloudIo, HostileHeadersAreRejectedBeforeAllocating) {
  const LineCloud c = one_labelled_segment();
  LineCloudWriteOptions text;
  text.binary = false;
  const nlohmann::json good = nlohmann::json::parse(line_cloud_to_bytes(c, text));
  auto with = [&](const nlohmann::json::json_pointer& at, const nlohmann::json& value) {
    nlohmann::json j = good;
    j[at] = value;
    return j.dump();
  };
  using ptr = nlohmann::json::json_pointer;
  expect_error(with(ptr("/num_segments"), 100000000), "num_segments 100000000 does not fit");
  expect_error(with(ptr("/num_segments"), 0.7), "num_segments: expected an integer");
  expect_error(with(ptr("/arrays/label_f/data/0"), 300), "label_f.data[0]: 300 is out of range");
  expect_error(with(ptr("/arrays/label_f/data/0"), true), "label_f.data[0]: expected an integer");
  expect_error(with(ptr("/arrays/label_junctions/data/0"), 4294967296), "out of range");
  expect_error(with(ptr("/wireframe/edges/0/1"), 4294967297), "wireframe.edges[1]: 4294967297 is out of range");
  expect_error(with(ptr("/wireframe/junctions/1/0"), 1e155), "GT junction 1 is not finite or beyond +-1e9");

  // Binary: the same claim in a rebuilt header.
  const std::string bin = line_cloud_to_bytes(c);
  const size_t eol = bin.find('\n');
  const size_t header_len = std::stoul(bin.substr(bin.rfind(' ', eol) + 1, eol));
  nlohmann::json h = nlohmann::json::parse(bin.substr(eol + 1, header_len));
  h["num_segments"] = 100000000;
  h["arrays"]["segments"]["shape"] = {100000000, 6};
  const std::string header = h.dump();
  expect_error("LC2WF-LINECLOUD 1 " + std::to_string(header.size()) + "\n" + header + bin.substr(eol + 1 + header_len),
               "does not fit the file's size");
}

TEST(LineCloudIo, MissingFileIsNamed) {
  try {
    read_line_cloud("/nonexistent/a.lc2wf");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("/nonexistent/a.lc2wf"));
  }
}

TEST(SyntheticCloud, DeterministicAndShapedLikeThePaper) {
  const Building b = make_l_building("l", LBuildingSpec{});
  const LineCloud x = make_synthetic_line_cloud(b, 3);
  const LineCloud y = make_synthetic_line_cloud(b, 3);
  EXPECT_EQ(line_cloud_to_bytes(x), line_cloud_to_bytes(y));
  EXPECT_NE(line_cloud_to_bytes(x), line_cloud_to_bytes(make_synthetic_line_cloud(b, 4)));
  EXPECT_NO_THROW(validate_line_cloud(x, "synthetic"));
  double mean_edge = 0;
  for (const auto& e : b.wireframe.edges) mean_edge += (b.wireframe.junctions[e[0]] - b.wireframe.junctions[e[1]]).norm();
  mean_edge /= static_cast<double>(b.wireframe.edges.size());
  int shorter = 0, positives = 0, supported = 0;
  for (size_t i = 0; i < x.segments.size(); ++i) {
    shorter += x.segments[i].length() < mean_edge;
    positives += x.labels[i].f;
    supported += x.support[i].size() >= 2;
  }
  const double n = static_cast<double>(x.segments.size());
  EXPECT_GT(shorter / n, 0.75);  // the paper: ~85% shorter than the mean GT edge
  EXPECT_GT(positives / n, 0.3);
  EXPECT_LT(positives / n, 0.8);
  EXPECT_GT(supported / n, 0.8);
}

// Labelling from 2D support must recover the generator's truth on clean synthetic data.
TEST(Labelling, SupportRecoversGeneratorLabels) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Building b = make_random_building(seed, "r");
    const LineCloud c = make_synthetic_line_cloud(b, seed);
    const auto labels = label_by_support(c, b.mesh);
    int agree = 0, pos = 0, tp = 0, fp = 0;
    for (size_t i = 0; i < labels.size(); ++i) {
      const auto& t = c.labels[i];
      const auto& l = labels[i];
      pos += t.f;
      if (t.f && l.f && t.i1 == l.i1 && t.i2 == l.i2) ++tp;
      if (l.f && !t.f) ++fp;
      agree += (t.f == l.f) && (!t.f || (t.i1 == l.i1 && t.i2 == l.i2));
    }
    const double n = static_cast<double>(labels.size());
    EXPECT_GT(agree / n, 0.9) << "seed " << seed;
    EXPECT_GT(tp / static_cast<double>(pos), 0.85) << "seed " << seed;
    EXPECT_LT(fp / n, 0.05) << "seed " << seed;
  }
}

TEST(Labelling, GeometryRecoversGeneratorLabels) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Building b = make_random_building(seed, "r");
    const LineCloud c = make_synthetic_line_cloud(b, seed);
    const auto labels = label_by_geometry(c.segments, c.wireframe);
    int agree = 0;
    for (size_t i = 0; i < labels.size(); ++i) {
      const auto& t = c.labels[i];
      const auto& l = labels[i];
      agree += (t.f == l.f) && (!t.f || (t.i1 == l.i1 && t.i2 == l.i2 && std::abs(t.d1 - l.d1) < 1e-12));
    }
    EXPECT_GT(agree / static_cast<double>(labels.size()), 0.95) << "seed " << seed;
  }
}

TEST(Labelling, HandMadeGeometryCases) {
  Wireframe w;
  w.junctions = {Vec3(0, 0, 0), Vec3(10, 0, 0), Vec3(10, 5, 0)};
  w.edges = {{0, 1}, {1, 2}};
  const std::vector<Segment3> s = {
      {Vec3(2, 0.05, 0), Vec3(5, -0.05, 0)},  // on edge 0
      {Vec3(2, 0.5, 0), Vec3(5, 0.5, 0)},     // parallel, too far
      {Vec3(10, 4, 0), Vec3(10.02, 1, 0)},    // on edge 1, reversed -> i1 = 2
      {Vec3(12, 0, 0), Vec3(14, 0, 0)},       // collinear but outside edge 0
      {Vec3(2, 0, 0), Vec3(3, 0.5, 0)},       // wrong angle
  };
  const auto l = label_by_geometry(s, w);
  EXPECT_TRUE(l[0].f);
  EXPECT_EQ(l[0].i1, 0);
  EXPECT_EQ(l[0].i2, 1);
  EXPECT_NEAR(l[0].d1, std::hypot(2, 0.05), 1e-12);
  EXPECT_FALSE(l[1].f);
  EXPECT_TRUE(l[2].f);
  EXPECT_EQ(l[2].i1, 2);
  EXPECT_EQ(l[2].i2, 1);
  EXPECT_FALSE(l[3].f);
  EXPECT_FALSE(l[4].f);
  EXPECT_EQ(l[4].i1, -1);
}

TEST(Labelling, OccludedEdgeGetsNoVotes) {
  // A camera looking straight down on a flat-topped box sees the top outline but not the base outline.
  PolyMesh box;
  box.vertices = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, {-2, -2, 3}, {2, -2, 3}, {2, 2, 3}, {-2, 2, 3}};
  box.faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Camera cam;
  cam.K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  cam.R << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // looking down -z
  cam.t = -cam.R * Vec3(0.5, 0.3, 20);
  cam.width = 640;
  cam.height = 480;
  const MeshOccluder occ(box);
  // A base edge just inside the footprint's shadow: hidden; the top edge above it: visible.
  const ProjectedEdge top = project_edge(cam, box.vertices[4], box.vertices[5], occ, 16, 0.01);
  const ProjectedEdge base = project_edge(cam, box.vertices[0], box.vertices[1], occ, 16, 0.01);
  ASSERT_EQ(top.visible.size(), 1u);
  EXPECT_NEAR(top.visible[0][0], 0.0, 1e-9);
  EXPECT_NEAR(top.visible[0][1], 1.0, 1e-9);
  EXPECT_TRUE(base.visible.empty());
}

TEST(Labelling, OptionsCheckNamesField) {
  SupportLabelOptions s;
  s.pixel_tol = -1;
  EXPECT_THROW(s.Check(), std::invalid_argument);
  GeometricLabelOptions g;
  g.min_overlap = 2;
  try {
    g.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("min_overlap"));
  }
}

}  // namespace
}  // namespace lc2wf

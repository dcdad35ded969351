// The rule that keeps only edges the cloud's lines run along (model/edge_support.h) and its flag.
#include "model/edge_support.h"
#include "infer/post_process_flags.h"
#include "model/edge_visibility.h"
#include "dataset/synthetic/synthetic_building.h"
#include "dataset/synthetic/synthetic_line_cloud.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

namespace lc2wf {
namespace {

// A square's four sides; segments cover the two sides on y = 0 and x = 4, half of y = 4, nothing on x = 0.
ScoredWireframe square() {
  ScoredWireframe w;
  w.wireframe.junctions = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(0, 4, 0)};
  w.wireframe.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
  w.junction_scores = {0.9, 0.8, 0.7, 0.6};
  w.edge_scores = {0.5, 0.6, 0.7, 0.8};
  return w;
}

std::vector<Segment3> segments() {
  return {{Vec3(0.1, 0.05, 0), Vec3(2.0, 0.0, 0)}, {Vec3(2.0, -0.05, 0), Vec3(3.9, 0, 0)},  // y = 0, all of it
          {Vec3(4, 0.2, 0), Vec3(4.1, 3.8, 0.1)},                                          // x = 4
          {Vec3(2.2, 4, 0), Vec3(4, 4, 0)},                                                // half of y = 4
          {Vec3(0, 1, 0), Vec3(1, 1, 2)}};                                                 // crosses x = 0 steeply
}

TEST(EdgeSupport, KeepsEdgesTheLinesRunAlongAndDropsJunctionsLeftAlone) {
  EdgeSupportOptions o;
  o.min_support = 0.6;
  const SupportedEdges r = keep_supported_edges(square(), segments(), {}, o);
  const Wireframe& w = r.wireframe.wireframe;
  ASSERT_EQ(w.edges.size(), 2u);
  EXPECT_EQ(r.dropped_edges, 2);
  EXPECT_EQ(r.dropped_junctions, 1);  // (0, 4) keeps no edge
  ASSERT_EQ(w.junctions.size(), 3u);
  EXPECT_EQ(r.wireframe.edge_scores, (std::vector<double>{0.5, 0.6}));
  EXPECT_EQ(r.wireframe.junction_scores, (std::vector<double>{0.9, 0.8, 0.7}));
  r.wireframe.check("kept");
}

TEST(EdgeSupport, AHalfCoveredEdgePassesALowerShare) {
  EdgeSupportOptions o;
  o.min_support = 0.4;
  EXPECT_EQ(keep_supported_edges(square(), segments(), {}, o).wireframe.wireframe.edges.size(), 3u);
}

TEST(EdgeSupport, OffKeepsEverythingAndEmptyInputsStayEmpty) {
  EdgeSupportOptions off;
  off.min_support = 0;
  const SupportedEdges all = keep_supported_edges(square(), {}, {}, off);
  EXPECT_EQ(all.wireframe.wireframe.edges.size(), 4u);
  EXPECT_EQ(all.dropped_edges, 0);
  const SupportedEdges none = keep_supported_edges(square(), {}, {}, EdgeSupportOptions{});
  EXPECT_TRUE(none.wireframe.wireframe.edges.empty());
  EXPECT_TRUE(none.wireframe.wireframe.junctions.empty());
  EXPECT_EQ(none.dropped_junctions, 4);
  EXPECT_TRUE(keep_supported_edges(ScoredWireframe{}, segments(), {}, EdgeSupportOptions{}).wireframe.wireframe.edges.empty());
}

// A 10 x 6 x 4 m box seen from +y only (cameras at azimuth 45-135 degrees, street-like elevation). The back
// wall's vertical corners are in view of the end cameras, along the side walls; its horizontal edges are not.
struct FrontView {
  ScoredWireframe box;
  std::vector<Camera> cameras;
};

FrontView front_view() {
  FrontView f;
  Wireframe& w = f.box.wireframe;
  for (double z : {0.0, 4.0})
    for (auto [x, y] : {std::pair{-5.0, -3.0}, {5.0, -3.0}, {5.0, 3.0}, {-5.0, 3.0}}) w.junctions.push_back(Vec3(x, y, z));
  for (int k = 0; k < 4; ++k) {
    w.edges.push_back({k, (k + 1) % 4});          // ground
    w.edges.push_back({4 + k, 4 + (k + 1) % 4});  // roof
    w.edges.push_back({k, 4 + k});                // corners
  }
  for (auto& e : w.edges) e = {std::min(e[0], e[1]), std::max(e[0], e[1])};
  f.box.junction_scores.assign(w.junctions.size(), 1.0);
  f.box.edge_scores.assign(w.edges.size(), 1.0);
  Building b;
  b.mesh.vertices = w.junctions;
  CameraRingOptions ring;
  ring.num_views = 16;
  ring.elevation_deg = 5;  // below the roof: its back edge is out of sight
  const std::vector<Camera> all = make_camera_ring(b, ring);
  f.cameras.assign(all.begin() + 2, all.begin() + 7);
  return f;
}

TEST(EdgeVisibility, TheFrontIsSeenTheBackIsHidden) {
  const FrontView f = front_view();
  const FootprintOccluder occ(f.box.wireframe);
  const Vec3 eye(0, 20, 2);
  EXPECT_FALSE(occ.hides(eye, Vec3(0, 3, 2), 0.5));   // front wall
  EXPECT_TRUE(occ.hides(eye, Vec3(0, -3, 2), 0.5));   // back wall, behind the box
  EXPECT_FALSE(occ.hides(Vec3(0, 0, 30), Vec3(0, -3, 4), 0.5));  // the roof's back edge from straight above
  EXPECT_FALSE(FootprintOccluder(Wireframe{}).hides(eye, Vec3(0, -3, 2), 0.5));  // no wireframe, nothing hidden
  EXPECT_EQ(cameras_seeing(Vec3(-5, 3, 0), Vec3(5, 3, 0), f.cameras, occ, 0.5), 5);   // front ground edge
  EXPECT_EQ(cameras_seeing(Vec3(-5, -3, 0), Vec3(5, -3, 0), f.cameras, occ, 0.5), 0);  // back ground edge
}

TEST(EdgeVisibility, TheSeenPartKeepsTheFrontAndDropsTheBack) {
  const FrontView f = front_view();
  const Wireframe seen = seen_part(f.box.wireframe, f.cameras, 2, 0.5);
  ASSERT_FALSE(seen.edges.empty());
  EXPECT_LT(seen.edges.size(), f.box.wireframe.edges.size());
  std::vector<int> used(seen.junctions.size(), 0);
  bool front_ground = false, front_roof = false;
  for (const auto& e : seen.edges) {
    const Vec3 &u = seen.junctions[e[0]], &v = seen.junctions[e[1]];
    ++used[e[0]], ++used[e[1]];
    EXPECT_FALSE(u.y() < -2.9 && v.y() < -2.9 && u.z() == v.z()) << "back edge seen: " << u.transpose() << " - " << v.transpose();
    front_ground |= u.y() > 2.9 && v.y() > 2.9 && u.z() == 0 && v.z() == 0;
    front_roof |= u.y() > 2.9 && v.y() > 2.9 && u.z() == 4 && v.z() == 4;
  }
  EXPECT_TRUE(front_ground);
  EXPECT_TRUE(front_roof);
  for (int n : used) EXPECT_GT(n, 0) << "a junction without a seen edge kept";
  // Every camera sees the front, none more: asking for more cameras than there are leaves nothing.
  EXPECT_TRUE(seen_part(f.box.wireframe, f.cameras, 6, 0.5).edges.empty());
  EXPECT_TRUE(seen_part(f.box.wireframe, {}, 1, 0.5).junctions.empty());
}

TEST(EdgeSupport, CamerasKeepAnUnlinedEdgeInViewAndNotOneOnTheHiddenSide) {
  const FrontView f = front_view();
  const std::vector<Segment3> none;
  EdgeSupportOptions with_cameras;
  with_cameras.min_cameras = 2;
  const SupportedEdges r = keep_supported_edges(f.box, none, f.cameras, with_cameras);
  const Wireframe& w = r.wireframe.wireframe;
  EXPECT_GT(r.kept_by_cameras, 0);
  EXPECT_EQ(r.kept_by_cameras, static_cast<int>(w.edges.size()));
  bool front_ground = false;
  for (const auto& e : w.edges) {
    const Vec3 &u = w.junctions[e[0]], &v = w.junctions[e[1]];
    EXPECT_FALSE(u.y() < -2.9 && v.y() < -2.9 && u.z() == v.z()) << "back edge kept: " << u.transpose() << " - " << v.transpose();
    front_ground |= u.y() > 2.9 && v.y() > 2.9 && u.z() == 0 && v.z() == 0;
  }
  EXPECT_TRUE(front_ground);
  // The default: the lines alone decide.
  EXPECT_TRUE(keep_supported_edges(f.box, none, f.cameras, EdgeSupportOptions{}).wireframe.wireframe.edges.empty());
}

// The square with both diagonals and a fifth junction at its centre joined to every corner: the corners meet
// 4 edges, the centre 4, and no line runs along a diagonal or a spoke.
ScoredWireframe square_with_clique() {
  ScoredWireframe w = square();
  w.wireframe.junctions.push_back(Vec3(2, 2, 0));
  w.junction_scores.push_back(0.5);
  for (std::array<int, 2> e : {std::array{0, 2}, {1, 3}, {0, 4}, {1, 4}, {2, 4}, {3, 4}}) {
    w.wireframe.edges.push_back(e);
    w.edge_scores.push_back(0.9);
  }
  return w;
}

TEST(EdgeSupport, OverConnectedJunctionsLoseTheirUnlinedEdgesOnly) {
  EdgeSupportOptions o;
  o.min_support = 0.99;  // the share of partial captures: not the judge's
  o.judge_min_support = 0.4;
  o.judge_degree_above = 3;
  const SupportedEdges r = keep_supported_edges(square_with_clique(), segments(), {}, o, JudgedEdges::over_connected_only);
  // Every junction has > 3 edges, so every edge is judged by its lines: the three lined sides stay.
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 3u);
  EXPECT_EQ(r.dropped_edges, 7);
  // Junctions of at most 5 edges are left alone, lined or not.
  o.judge_degree_above = 5;
  EXPECT_EQ(keep_supported_edges(square_with_clique(), segments(), {}, o, JudgedEdges::over_connected_only)
                .wireframe.wireframe.edges.size(), 10u);
  // The plain square's corners meet 2 edges: above 2 they are not judged, not even without any line.
  o.judge_degree_above = 2;
  EXPECT_EQ(keep_supported_edges(square(), {}, {}, o, JudgedEdges::over_connected_only).wireframe.wireframe.edges.size(), 4u);
  // Off (0) keeps every edge; the cameras do not rescue an over-connected junction's edge (they see inside).
  o.judge_degree_above = 0;
  EXPECT_EQ(keep_supported_edges(square_with_clique(), {}, {}, o, JudgedEdges::over_connected_only).dropped_edges, 0);
  o.judge_degree_above = 3;
  const FrontView f = front_view();
  EXPECT_EQ(keep_supported_edges(square_with_clique(), segments(), f.cameras, o, JudgedEdges::over_connected_only).kept_by_cameras, 0);
}

TEST(EdgeSupport, BadOptionsAndInputsAreNamed) {
  EdgeSupportOptions o;
  o.min_support = 1.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.radius_m = 0;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.min_cameras = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.judge_degree_above = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  ScoredWireframe bad = square();
  bad.wireframe.edges.push_back({0, 9});
  bad.edge_scores.push_back(0.5);
  EXPECT_THROW(keep_supported_edges(bad, segments(), {}, EdgeSupportOptions{}), std::invalid_argument);
}

TEST(EdgeSupport, FlagSetsTheShareAndReleaseQuirksTurnItOff) {
  EXPECT_GT(PostProcessOptions{}.edge_support.min_support, 0.0);
  EXPECT_EQ(PostProcessOptions::release_quirks().edge_support.min_support, 0.0);
  EXPECT_GT(PostProcessOptions{}.edge_support.judge_degree_above, 0);  // over-connected junctions are judged
  std::vector<std::string> args = {"x", "--edge-support", "0.5"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  PostProcessFlags flags;
  int i = 1;
  ASSERT_TRUE(flags.parse(args[1], static_cast<int>(argv.size()), argv.data(), i));
  EXPECT_EQ(flags.options().edge_support.min_support, 0.5);
  std::vector<std::string> degree_args = {"x", "--judge-degree-above", "6"};
  std::vector<char*> degree_argv;
  for (auto& a : degree_args) degree_argv.push_back(a.data());
  i = 1;
  ASSERT_TRUE(flags.parse(degree_args[1], static_cast<int>(degree_argv.size()), degree_argv.data(), i));
  EXPECT_EQ(flags.options().edge_support.judge_degree_above, 6);
  flags.edge_support = 2.0;
  try {
    flags.options();
    FAIL() << "2.0 accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--edge-support"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lc2wf

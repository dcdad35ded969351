// Small flat parts of a photo cloud's wireframe (model/flat_parts.h): a box with a window frame on its facade
// and a flat shape beside it.
#include "model/flat_parts.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "infer/post_process_flags.h"

namespace lc2wf {
namespace {

// A 10 x 6 x 5 m box (12 edges), a window frame on its front (4 edges, 0.2 m in front of the wall, not
// touching it), a leaning 3D tetrahedron apart (6 edges), and a lone edge.
ScoredWireframe scene() {
  ScoredWireframe w;
  auto add = [&](const Vec3& p) { w.wireframe.junctions.push_back(p), w.junction_scores.push_back(0.9); return static_cast<int>(w.wireframe.junctions.size()) - 1; };
  auto edge = [&](int a, int b) { w.wireframe.edges.push_back({a, b}), w.edge_scores.push_back(0.8); };
  int box[8];
  for (int k = 0; k < 8; ++k) box[k] = add(Vec3(k & 1 ? 10 : 0, k & 2 ? 6 : 0, k & 4 ? 5 : 0));
  for (int k = 0; k < 8; ++k)
    for (int bit : {1, 2, 4})
      if (!(k & bit)) edge(box[k], box[k | bit]);
  const int a = add(Vec3(2, -0.2, 1)), b = add(Vec3(3.5, -0.2, 1)), c = add(Vec3(3.5, -0.2, 2.5)), d = add(Vec3(2, -0.2, 2.5));
  edge(a, b), edge(b, c), edge(c, d), edge(d, a);
  const int t0 = add(Vec3(20, 0, 0)), t1 = add(Vec3(22, 0, 0)), t2 = add(Vec3(21, 2, 0)), t3 = add(Vec3(21, 1, 2));
  edge(t0, t1), edge(t1, t2), edge(t2, t0), edge(t0, t3), edge(t1, t3), edge(t2, t3);
  edge(add(Vec3(-5, -5, 0)), add(Vec3(-5, -3, 0)));
  return w;
}

TEST(FlatParts, SmallFlatPartsGoTheLargestAndTheSolidOnesStay) {
  FlatPartOptions o;
  o.max_edges = 10;
  const FlatPartsDropped r = drop_flat_parts(scene(), o);
  EXPECT_EQ(r.dropped_parts, 2);  // the window frame and the lone edge
  EXPECT_EQ(r.dropped_edges, 5);
  EXPECT_EQ(r.wireframe.wireframe.edges.size(), 18u);  // the box and the tetrahedron
  EXPECT_EQ(r.wireframe.wireframe.junctions.size(), 12u);
  EXPECT_EQ(r.wireframe.edge_scores.size(), 18u);
  for (const Vec3& j : r.wireframe.wireframe.junctions) EXPECT_FALSE(j.y() == -0.2) << "window corner kept";
}

TEST(FlatParts, TheLargestPartStaysEvenWhenFlat) {
  // A facade seen alone from the street: one flat rectangle.
  ScoredWireframe w;
  w.wireframe.junctions = {Vec3(0, 0, 0), Vec3(8, 0, 0), Vec3(8, 0, 6), Vec3(0, 0, 6)};
  w.wireframe.edges = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  w.junction_scores = {1, 1, 1, 1};
  w.edge_scores = {1, 1, 1, 1};
  FlatPartOptions o;
  o.max_edges = 10;
  EXPECT_EQ(drop_flat_parts(w, o).wireframe.wireframe.edges.size(), 4u);
}

TEST(FlatParts, TheLongestPartStaysNotTheOneWithMostEdges) {
  // A walk past a house: the gable's outline (3 long edges, flat) and a zigzag of 4 short edges on a bush in
  // front (flat too). The house is the larger thing in view; counting edges would keep the bush.
  ScoredWireframe w;
  w.wireframe.junctions = {Vec3(0, 0, 4), Vec3(0, 4, 7), Vec3(0, 8, 4), Vec3(0, 8, 0),                      // gable
                           Vec3(-3, 1, 0.5), Vec3(-3, 1.5, 1.2), Vec3(-3, 2, 0.6), Vec3(-3, 2.6, 1.1), Vec3(-3, 3, 0.4)};  // bush
  w.wireframe.edges = {{0, 1}, {1, 2}, {2, 3}, {4, 5}, {5, 6}, {6, 7}, {7, 8}};
  w.junction_scores.assign(9, 0.9);
  w.edge_scores.assign(7, 0.9);
  FlatPartOptions o;
  o.max_edges = 10;
  const FlatPartsDropped r = drop_flat_parts(w, o);
  EXPECT_EQ(r.dropped_parts, 1);
  EXPECT_EQ(r.dropped_edges, 4);
  ASSERT_EQ(r.wireframe.wireframe.edges.size(), 3u);
  for (const Vec3& j : r.wireframe.wireframe.junctions) EXPECT_EQ(j.x(), 0.0) << "a bush corner kept";
}

TEST(FlatParts, OffOrLooseSettingsKeepEverything) {
  EXPECT_EQ(drop_flat_parts(scene(), FlatPartOptions{}).wireframe.wireframe.edges.size(), 23u);  // off by default
  FlatPartOptions few;
  few.max_edges = 2;  // only parts of one edge may go
  EXPECT_EQ(drop_flat_parts(scene(), few).dropped_edges, 1);
  FlatPartOptions thin;
  thin.max_edges = 10;
  thin.plane_tolerance_m = 0.0;  // the window frame is exactly flat, the lone edge too
  EXPECT_EQ(drop_flat_parts(scene(), thin).dropped_parts, 2);
}

TEST(FlatParts, BadOptionsAreRefusedByNameAndTheFlagSetsThem) {
  FlatPartOptions bad;
  bad.plane_tolerance_m = -1;
  EXPECT_THROW(bad.Check(), std::invalid_argument);
  bad = {};
  bad.max_edges = -1;
  try {
    bad.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_edges"), std::string::npos);
  }
  std::vector<std::string> args = {"x", "--drop-flat-parts", "12"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  PostProcessFlags flags;
  int i = 1;
  ASSERT_TRUE(flags.parse(args[1], static_cast<int>(argv.size()), argv.data(), i));
  EXPECT_EQ(flags.options().flat_parts.max_edges, 12);
}

}  // namespace
}  // namespace lc2wf

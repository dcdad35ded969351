// The graph view of a wireframe (dataset/geometry/wireframe_graph.h).
#include "dataset/geometry/wireframe_graph.h"

#include <gtest/gtest.h>

namespace lc2wf {
namespace {

TEST(WireframeGraph, EdgesAndDegreesPerJunction) {
  Wireframe wf;
  wf.junctions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(5, 5, 5)};  // the last has no edge
  wf.edges = {{0, 1}, {1, 2}, {0, 2}};
  EXPECT_EQ(incident_edges(wf), (std::vector<std::vector<int>>{{0, 2}, {0, 1}, {1, 2}, {}}));
  EXPECT_EQ(junction_degrees(wf), (std::vector<int>{2, 2, 2, 0}));
  EXPECT_TRUE(incident_edges(Wireframe{}).empty());
  EXPECT_TRUE(junction_degrees(Wireframe{}).empty());
}

}  // namespace
}  // namespace lc2wf

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

TEST(WireframeGraph, ConnectedPartsNumberedByTheirFirstJunction) {
  // Junctions 0-1-2 joined, 3 alone, 4-5 joined through an edge listed before the first part's.
  EXPECT_EQ(connected_parts(6, {{5, 4}, {0, 1}, {2, 1}}), (std::vector<int>{0, 0, 0, 1, 2, 2}));
  EXPECT_EQ(connected_parts(3, {}), (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(connected_parts(0, {}).empty());
}

}  // namespace
}  // namespace lc2wf

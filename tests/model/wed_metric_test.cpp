#include "model/wed_metric.h"

#include <gtest/gtest.h>

#include <cmath>

namespace lc2wf {
namespace {

Wireframe square() {
  Wireframe gt;
  gt.junctions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  gt.edges = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
  return gt;
}

// p3 duplicates GT vertex 0; edges: hit 01, duplicate 01, hit 12, diagonal 02 (non-GT), degenerate 00.
Wireframe messy_prediction() {
  Wireframe p;
  p.junctions = {{0, 0, 0.2}, {2, 0, 0}, {2, 2, 0}, {0.1, 0, 0}};
  p.edges = {{0, 1}, {1, 3}, {1, 2}, {0, 2}, {0, 3}};
  return p;
}

TEST(WedMetric, ReleaseVariantByHand) {
  const WedResult r = wed_release(messy_prediction(), square(), 20.0);
  EXPECT_EQ(r.gt_vertices, 4);
  EXPECT_EQ(r.gt_edges, 4);
  EXPECT_EQ(r.pred_vertices, 4);
  EXPECT_EQ(r.pred_edges, 5);
  // sqrt of raw distances (0.2 m = 4 raw, 0.1 m = 2 raw) over 20.
  EXPECT_NEAR(r.move, (2.0 + std::sqrt(2.0)) / 20.0, 1e-12);
  EXPECT_EQ(r.add_vertex, 1);
  EXPECT_EQ(r.del_vertex, 0);
  EXPECT_EQ(r.add_edge, 2);
  EXPECT_NEAR(r.add_edge_length, 4.0, 1e-12);
  EXPECT_EQ(r.del_edge, 1);  // only the duplicate hit; diagonal and degenerate edges are free
  EXPECT_NEAR(r.del_edge_length, 2.0, 1e-12);
  EXPECT_EQ(r.total_num(), 4);
  EXPECT_NEAR(r.total_dist(), (2.0 + std::sqrt(2.0)) / 20.0 + 6.0, 1e-12);
}

TEST(WedMetric, StrictVariantChargesSpuriousEdgesAndVertices) {
  const WedResult r = wed_strict(messy_prediction(), square());
  EXPECT_NEAR(r.move, 0.3, 1e-12);
  EXPECT_EQ(r.add_vertex, 1);
  EXPECT_EQ(r.del_vertex, 1);
  EXPECT_EQ(r.add_edge, 2);
  EXPECT_NEAR(r.add_edge_length, 4.0, 1e-12);
  EXPECT_EQ(r.del_edge, 3);  // duplicate (2 m) + diagonal (2.83 m) + degenerate (0 m)
  EXPECT_NEAR(r.del_edge_length, 2.0 + 2.0 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(r.total_num(), 7);
  EXPECT_NEAR(r.total_dist(), 0.3 + 4.0 + 2.0 + 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(WedMetric, PerfectPredictionCostsNothing) {
  for (const WedResult& r : {wed_release(square(), square()), wed_strict(square(), square())}) {
    EXPECT_EQ(r.total_num(), 0);
    EXPECT_EQ(r.total_dist(), 0.0);
  }
}

TEST(WedMetric, EmptyPredictionAddsEverything) {
  for (const WedResult& r : {wed_release({}, square()), wed_strict({}, square())}) {
    EXPECT_EQ(r.add_vertex, 4);
    EXPECT_EQ(r.add_edge, 4);
    EXPECT_NEAR(r.add_edge_length, 8.0, 1e-12);
    EXPECT_EQ(r.move, 0.0);
    EXPECT_EQ(r.del_edge, 0);
    EXPECT_EQ(r.total_num(), 8);
  }
}

// Regression: a vertex whose distance to every GT vertex overflows to inf kept nearest index -1 (heap corruption).
TEST(WedMetric, VertexInfinitelyFarFromEveryGtVertexMapsToTheFirst) {
  Wireframe p;
  p.junctions = {{1e155, 1e155, 1e155}, {2, 0, 0}};
  p.edges = {{0, 1}};
  for (const WedResult& r : {wed_release(p, square()), wed_strict(p, square())}) {
    EXPECT_EQ(r.add_vertex, 2);  // GT vertices 2 and 3 unclaimed
    EXPECT_TRUE(std::isinf(r.move));
    EXPECT_EQ(r.add_edge, 3);  // edge 0-1 is hit through the far vertex's fallback to GT vertex 0
  }
}

TEST(WedMetric, EmptyGroundTruth) {
  Wireframe p;
  p.junctions = {{0, 0, 0}, {3, 4, 0}};
  p.edges = {{0, 1}};
  const WedResult release = wed_release(p, {});
  EXPECT_EQ(release.pred_vertices, 2);
  EXPECT_EQ(release.total_num(), 0);
  EXPECT_EQ(release.total_dist(), 0.0);
  const WedResult strict = wed_strict(p, {});
  EXPECT_EQ(strict.del_vertex, 2);
  EXPECT_EQ(strict.del_edge, 1);
  EXPECT_NEAR(strict.del_edge_length, 5.0, 1e-12);
  EXPECT_EQ(strict.total_num(), 3);
}

}  // namespace
}  // namespace lc2wf

// Junction refinement: snaps to the meeting point of the segments ending near a junction, ignores far and
// short segments, leaves under-supported or degenerate junctions alone, and rejects bad options.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "dataset/selection/junction_refine.h"

namespace lc2wf {
namespace {

JunctionRefineOptions radius(double r) {
  JunctionRefineOptions o;
  o.radius = r;
  return o;
}

// Three roof edges meeting at a corner C, seen as noise-free partial segments that stop short of C.
std::vector<Segment3> corner_segments(const Vec3& C) {
  return {{C + Vec3(0.1, 0, 0), C + Vec3(3, 0, 0)},
          {C + Vec3(0, 4, 0), C + Vec3(0, 0.05, 0)},
          {C + Vec3(0, 0, -0.2), C + Vec3(0, 0, -2.5)}};
}

TEST(JunctionRefine, SnapsToTheCornerOfItsSegments) {
  const Vec3 C(2, 3, 5);
  const auto refined = refine_junctions({C + Vec3(0.2, -0.15, 0.1)}, corner_segments(C), radius(0.5));
  EXPECT_LT((refined[0] - C).norm(), 0.02) << refined[0].transpose();
}

TEST(JunctionRefine, OffLeavesPositionsUntouched) {
  const Vec3 C(2, 3, 5), P = C + Vec3(0.2, -0.15, 0.1);
  EXPECT_EQ(refine_junctions({P}, corner_segments(C), radius(0.0))[0], P);
}

TEST(JunctionRefine, IgnoresFarAndShortSegments) {
  const Vec3 C(0, 0, 0), P(0.1, 0.1, 0);
  std::vector<Segment3> segs = corner_segments(C);
  segs.push_back({Vec3(0.9, 0.9, 0), Vec3(5, 0.9, 0)});         // both endpoints beyond the radius
  segs.push_back({Vec3(0.05, 0.2, 0), Vec3(0.1, 0.25, 0.05)});  // too short to carry a direction
  EXPECT_LT((refine_junctions({P}, segs, radius(0.5))[0] - C).norm(), 0.02);
}

TEST(JunctionRefine, KeepsUnderSupportedAndDegenerateJunctions) {
  const Vec3 P(0.1, 0.1, 0);
  // One segment only.
  EXPECT_EQ(refine_junctions({P}, {{Vec3(0, 0, 0), Vec3(3, 0, 0)}}, radius(0.5))[0], P);
  // Two parallel lines: no meeting point along them; the prior keeps the along-line position, and the
  // result may not leave the radius.
  const auto r = refine_junctions({P}, {{Vec3(0, 0, 0), Vec3(3, 0, 0)}, {Vec3(0, 0.01, 0), Vec3(3, 0.01, 0)}},
                                  radius(0.5));
  EXPECT_NEAR(r[0].x(), P.x(), 1e-9);
  EXPECT_LE((r[0] - P).norm(), 0.5);
  // A junction with no segment nearby and an empty cloud.
  EXPECT_EQ(refine_junctions({Vec3(50, 50, 50)}, corner_segments(Vec3(0, 0, 0)), radius(0.5))[0], Vec3(50, 50, 50));
  EXPECT_TRUE(refine_junctions({}, {}, radius(0.5)).empty());
}

TEST(JunctionRefine, NoisyCornersGetCloser) {
  std::mt19937 g(7);
  std::normal_distribution<double> n(0, 0.15);
  double before = 0, after = 0;
  for (int k = 0; k < 50; ++k) {
    const Vec3 C(k, 2 * k, 3);
    const Vec3 P = C + Vec3(n(g), n(g), n(g));
    before += (P - C).norm();
    after += (refine_junctions({P}, corner_segments(C), radius(0.5))[0] - C).norm();
  }
  EXPECT_LT(after, 0.25 * before);
}

// A fourth segment ends near the corner but passes it 0.2 m away (another edge's fragment, a texture line):
// plain least squares is dragged towards it, the robust weights outvote it.
TEST(JunctionRefine, RobustScaleIgnoresALineThatPassesTheCornerBy) {
  const Vec3 C(1, -2, 4);
  std::vector<Segment3> segs = corner_segments(C);
  segs.push_back({C + Vec3(-2, 0.2, 0.1), C + Vec3(0.1, 0.2, 0.1)});
  const Vec3 P = C + Vec3(0.1, 0.1, -0.1);
  JunctionRefineOptions plain = radius(0.5), robust = radius(0.5);
  robust.robust_scale = 0.05;
  const double plain_error = (refine_junctions({P}, segs, plain)[0] - C).norm();
  const double robust_error = (refine_junctions({P}, segs, robust)[0] - C).norm();
  EXPECT_GT(plain_error, 0.04);
  EXPECT_LT(robust_error, 0.01) << "plain " << plain_error;
  // Without the stray line both agree on the corner.
  EXPECT_LT((refine_junctions({P}, corner_segments(C), robust)[0] - C).norm(), 0.02);
}

TEST(JunctionRefine, RejectsBadOptions) {
  JunctionRefineOptions o;
  o.radius = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.min_segments = 1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.prior_weight = 0;
  EXPECT_THROW(refine_junctions({}, {}, o), std::invalid_argument);
  o = {};
  o.robust_scale = -0.05;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = {};
  o.robust_iterations = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf

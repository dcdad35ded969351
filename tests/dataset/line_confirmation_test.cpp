#include "dataset/photo/line_confirmation.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "dataset/geometry/segment_overlap.h"

namespace lc2wf {
namespace {

// A line triangulated from view `view` (its source: the first support).
void add_line(LineCloud& c, const Vec3& a, const Vec3& b, int view) {
  c.segments.push_back({a, b});
  c.support.push_back({Observation{view, Segment2{}}, Observation{view + 1, Segment2{}}});
}

TEST(SegmentOverlap, AMidpointRunsAlongAnotherSegmentWithinTenCentimetresAndFiveDegrees) {
  const Segment3 edge{Vec3(0, 0, 0), Vec3(4, 0, 0)};
  EXPECT_TRUE(midpoint_runs_along({Vec3(1, 0.05, 0), Vec3(2, 0.05, 0)}, edge));
  EXPECT_FALSE(midpoint_runs_along({Vec3(1, 0.15, 0), Vec3(2, 0.15, 0)}, edge));  // 15 cm off it
  EXPECT_FALSE(midpoint_runs_along({Vec3(1, 0, 0), Vec3(2, 0.1, 0)}, edge));       // 5.7 degrees
  EXPECT_FALSE(midpoint_runs_along({Vec3(4.5, 0, 0), Vec3(5.5, 0, 0)}, edge));     // past its end
  EXPECT_FALSE(midpoint_runs_along(edge, {Vec3(1, 0, 0), Vec3(1, 0, 0)}));         // degenerate other
  // One way only: the short piece's midpoint is on the edge, the edge's (2, 0, 0) is not on the piece.
  EXPECT_FALSE(midpoint_runs_along(edge, {Vec3(0, 0, 0), Vec3(1, 0, 0)}));
  const std::vector<Segment3> segments = {edge, {Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(1.5, 0.02, 0), Vec3(2.5, 0.02, 0)},
                                          {Vec3(0, 1, 0), Vec3(4, 1, 0)}};
  const SegmentOverlapIndex index(segments);
  std::vector<int> along;
  index.runs_along(1, along);
  EXPECT_EQ(along, std::vector<int>({0}));
  index.runs_along(0, along);
  EXPECT_EQ(along, std::vector<int>({2}));  // (2, 0, 0) lies on segment 2, not on segment 1
  index.runs_along(3, along);
  EXPECT_TRUE(along.empty());
}

TEST(LineConfirmation, AnEdgeSeenFromSeveralViewsStaysALoneLineGoes) {
  LineCloud c;
  c.name = "b";
  add_line(c, Vec3(0, 0, 0), Vec3(4, 0, 0), 0);        // 0: a long line of view 0 ...
  add_line(c, Vec3(0.2, 0.03, 0), Vec3(1.2, 0.03, 0), 1);  // 1: ... with a short fragment of view 1 on it
  add_line(c, Vec3(2, 0, 0.02), Vec3(3.8, 0, 0.02), 2);    // 2: and one of view 2
  add_line(c, Vec3(3, 0.01, 0), Vec3(3.5, 0.01, 0), 0);  // 3: view 0 again: confirms nothing of view 0
  add_line(c, Vec3(0, 5, 9), Vec3(2, 6, 9), 4);        // 4: floats alone
  add_line(c, Vec3(0, 2, 0), Vec3(3, 2, 0), 5);        // 5: parallel to line 0, 2 m away
  add_line(c, Vec3(0, 2.05, 0), Vec3(3, 2.05, 0), 5);  // 6: the same view as line 5
  // Line 0 is confirmed by views 1 and 2 (the fragment's midpoint is on it, its own midpoint on line 2);
  // line 2 by view 0 (lines 0 and 3: one view); line 3 by view 2 only; 5 and 6 by nothing (one source view).
  EXPECT_EQ(confirming_views(c), std::vector<int>({2, 1, 1, 1, 0, 0, 0}));
  LineConfirmationOptions o;
  const LineCloud kept = keep_confirmed_lines(c, o);
  ASSERT_EQ(kept.segments.size(), 4u);
  EXPECT_EQ(kept.segments[3].a, c.segments[3].a);
  EXPECT_EQ(kept.support.size(), 4u);  // supports travel with their lines
  o.min_other_views = 2;
  EXPECT_EQ(keep_confirmed_lines(c, o).segments.size(), 1u);
  o.min_other_views = 0;
  EXPECT_EQ(keep_confirmed_lines(c, o).segments.size(), c.segments.size());
  o.min_other_views = -1;
  EXPECT_THROW(keep_confirmed_lines(c, o), std::invalid_argument);
}

TEST(LineConfirmation, ACloudWithoutSupportsIsKeptWholeAndCannotBeCounted) {
  LineCloud c;
  c.name = "release";
  c.segments = {{Vec3(0, 0, 0), Vec3(1, 0, 0)}, {Vec3(0, 3, 0), Vec3(1, 3, 0)}};
  EXPECT_EQ(keep_confirmed_lines(c, LineConfirmationOptions{}).segments.size(), 2u);
  EXPECT_THROW(confirming_views(c), std::invalid_argument);
  c.support = {{Observation{0, Segment2{}}}, {}};  // one segment without a support: nothing to go by either
  EXPECT_EQ(keep_confirmed_lines(c, LineConfirmationOptions{}).segments.size(), 2u);
}

}  // namespace
}  // namespace lc2wf

// Lines of a triangulated cloud that no other view confirms. Each line of our clouds is one 2D segment's
// triangulation (its source view is the first of its supports), so a real edge or texture line seen from
// many views carries fragments from several source views, while a chance match among dense texture lines
// stands alone: in photo-like clouds 79 % of the lines floating above the roof are overlapped by no line
// of another source view, against 11 % of the lines on a GT edge (reconstruct/README.md). Used by
// lc2wf-reconstruct; our rendered training clouds are left whole (the model reads their lone lines as context).
#pragma once

#include <vector>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct LineConfirmationOptions {
  // A line is kept when lines from at least this many other source views overlap it (one's midpoint runs
  // along the other: segment_overlap.h); 0 keeps every line.
  int min_other_views = 1;
  void Check() const;  // throws std::invalid_argument naming the field
};

// Per segment, the number of distinct source views other than its own among the segments that overlap it
// (either midpoint on the other). Needs the supports (throws std::invalid_argument naming the cloud when a
// segment has none).
std::vector<int> confirming_views(const LineCloud& cloud);

// The cloud without the segments confirmed by fewer than min_other_views other views (everything else as
// keep_segments keeps it). A cloud without supports is returned whole: nothing says which view saw what.
LineCloud keep_confirmed_lines(const LineCloud& cloud, const LineConfirmationOptions& options);

}  // namespace lc2wf

// Line maps that merge the views' fragments into one line per edge stretch (Line3D++'s clustered lines,
// LIMAP's tracks) cut back into overlapping pieces, like the per-view fragments of our training clouds
// (reconstruct/README.md, "One model, clouds of other statistics").
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

constexpr int64_t kMaxSplitSegments = 2'000'000;

// Every segment longer than max_length_m becomes two chains of consecutive pieces along it: n =
// ceil(length / max_length_m) equal pieces, and the same pieces staggered by half a piece (a half piece at
// each end). Both chains keep the segment's endpoints, as the overlapping fragments of several views of one
// edge do. Shorter segments stay as they are. The result keeps the name, cameras, wireframe, units and origin and
// drops the 2D supports and labels (inference uses neither; no view saw a piece). max_length_m <= 0 returns
// the cloud unchanged. Throws std::invalid_argument for a non-finite max_length_m and DataError naming the
// cloud when there would be more than kMaxSplitSegments segments.
LineCloud split_long_segments(const LineCloud& cloud, double max_length_m);

// The pieces split_long_segments makes of one segment, appended to out (the segment itself when it is not
// longer than max_length_m > 0). Pieces at the segment's ends keep its endpoints exactly.
void append_staggered_pieces(const Segment3& s, double max_length_m, std::vector<Segment3>& out);

// Fraction of the segments longer than min_length_m that another segment overlaps along the same line
// (directions within 5 degrees, the midpoint within 10 cm of the other segment and inside its extent); 1
// when none is that long. Per-view fragment clouds have several views' fragments on every edge (ours, also
// with photo-like texture lines added: 0.81-1.00 on the 957 val/test buildings); merged line maps one line
// per edge stretch (long-fragment clouds: 0.23-0.63; SfM-texture renders, whose texture lines are single,
// 0.55-0.69). Linear in the cloud's length (a grid of points every 5 cm along the
// segments, at most kMaxSplitSegments of them: longer clouds are sampled more sparsely).
double overlapped_long_fraction(const LineCloud& cloud, double min_length_m);

// The rule of --max-segment-length auto: a cloud read from another program's line map
// (LineCloud::external_line_map) is cut when fewer than this fraction of its long segments are overlapped.
constexpr double kMergedMapOverlap = 0.7;
// The pieces' length of --max-segment-length auto: the best of 0.5-3 m for models/base on long-fragment clouds.
constexpr double kMergedMapPieceLength = 1.5;

}  // namespace lc2wf

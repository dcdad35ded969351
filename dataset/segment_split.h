// Line maps that merge the views' fragments into one line per edge stretch (Line3D++'s clustered lines,
// LIMAP's tracks) cut back into overlapping pieces, like the per-view fragments of our training clouds
// (reconstruct/README.md, "One model, clouds of other statistics").
#pragma once

#include <cstdint>

#include "dataset/line_cloud.h"

namespace lc2wf {

constexpr int64_t kMaxSplitSegments = 2'000'000;

// Every segment longer than max_length_m becomes two chains of consecutive pieces along it: n =
// ceil(length / max_length_m) equal pieces, and the same pieces staggered by half a piece (a half piece at
// each end). Both chains keep the segment's endpoints, as the overlapping fragments of several views of one
// edge do. Shorter segments stay as they are. The result keeps the name, cameras, wireframe and units and
// drops the 2D supports and labels (inference uses neither; no view saw a piece). max_length_m <= 0 returns
// the cloud unchanged. Throws std::invalid_argument for a non-finite max_length_m and DataError naming the
// cloud when there would be more than kMaxSplitSegments segments.
LineCloud split_long_segments(const LineCloud& cloud, double max_length_m);

}  // namespace lc2wf

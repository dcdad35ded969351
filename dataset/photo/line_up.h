// Up from a building's lines alone, for line maps made elsewhere without cameras (Line3D++, LIMAP, OBJ) in an
// arbitrary frame: the lines' three dominant orthogonal directions; the vertical is the one most of the line
// length is perpendicular to (eaves, ridges, ground and window lines are horizontal); its sign puts the
// ground - the end whose structure spreads widest (footprint, ground lines; roofs taper) - at the bottom.
// Wrong for towers taller than wide with few horizontal lines: give the up then (--up).
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct LineUp {
  Vec3 up = Vec3::UnitZ();
  Vec3 axes[3];                 // the dominant orthogonal directions, axes[0] the most common
  double perpendicular_share = 0;  // share of the line length perpendicular (within 10 deg) to up
  double runner_up_share = 0;      // the same for the best other axis
  double spread_ratio = 1;         // spread of the bottom end's structure over the top end's (>= 1)
};

// Throws std::invalid_argument when there is no line with a length.
LineUp up_from_lines(const std::vector<Segment3>& segments);

}  // namespace lc2wf

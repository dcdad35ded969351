// The first step of the face finder: one junction per corner and one edge per stretch between corners,
// so faces that share a corner or a side share its ids. Closes the small gaps of predicted wireframes.
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Junctions closer than `merge_distance` become one (at their mean), an edge passing within
// `merge_distance` of another junction is split there, self-loops and duplicate edges are dropped, and
// junctions no edge uses are removed.
Wireframe clean_wireframe(const Wireframe& wireframe, double merge_distance);

}  // namespace lc2wf

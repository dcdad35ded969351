// Wing layouts of L, T, U and courtyard footprints (x along the main wing, origin at its corner). A hipped
// or flat roof uses every wing's whole rectangle (the highest roof wins where wings overlap, which gives
// the hips and valleys of a straight skeleton); a gabled roof starts the side wings at the main wing's ridge
// line, so their ridges run into the main roof with valleys (cross gables).
#pragma once

#include <vector>

#include "dataset/synthetic/roof_shapes.h"

namespace lc2wf {

struct Wing {
  Rect rect;
  bool along_x = true;  // ridge direction
};

// Main wing [0, a] x [0, w] and a wing [0, w] x [0, b] along y.
std::vector<Wing> l_wings(double a, double b, double w, bool gabled);
// Main wing [0, a] x [0, w] and a stem of width `stem` from x = `at`, reaching y = b.
std::vector<Wing> t_wings(double a, double b, double w, double stem, double at, bool gabled);
// Main wing [0, a] x [0, w] and wings [0, w] and [a - w, a] along y up to b.
std::vector<Wing> u_wings(double a, double b, double w, bool gabled);
// Four wings of width w around an a x b rectangle; the wings along x come first.
std::vector<Wing> courtyard_wings(double a, double b, double w, bool gabled);

}  // namespace lc2wf

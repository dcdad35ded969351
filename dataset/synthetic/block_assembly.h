// A building as the union of axis-aligned blocks, each with a roof that is the lowest of a few planes over
// its rectangle (flat, shed, gable, hip, pyramid, mansard, gambrel). Blocks may overlap or share walls;
// the mesh is the outer surface of their union: where blocks overlap the higher roof wins (two hipped wings
// meet in hips and valleys, a dormer's roof runs into the main roof), walls stand only where the roof height
// jumps, and coplanar neighbours become one face.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct RoofPlane {  // z = a x + b y + c
  double a = 0, b = 0, c = 0;
  double at(double x, double y) const { return a * x + b * y + c; }
};

struct RoofedBlock {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // x0 < x1, y0 < y1, metres
  std::vector<RoofPlane> planes;          // the roof is the lowest plane at each point, above the ground
  double roof_at(double x, double y) const;
  void Check() const;  // a block of at least 1 cm, one plane or more, roof above the ground
};

// Closed mesh (metres, ground z = 0) of the union of the blocks, faces labelled roof / wall / base.
// Throws std::invalid_argument for a bad block, std::logic_error when the pieces do not close.
PolyMesh assemble_blocks(const std::vector<RoofedBlock>& blocks);

}  // namespace lc2wf

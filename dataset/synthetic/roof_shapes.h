// Roofs of one rectangular block as the lowest of a few planes (block_assembly.h): every pitched roof
// form the procedural buildings use. Slopes are rise over run (tangents), heights in metres.
#pragma once

#include "dataset/synthetic/block_assembly.h"

namespace lc2wf {

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double dx() const { return x1 - x0; }
  double dy() const { return y1 - y0; }
};

enum class Side { South, North, West, East };  // y = y0, y = y1, x = x0, x = x1

// z = height + slope * (distance from the side's line into the block - inset).
RoofPlane plane_rising_from(const Rect& r, Side side, double height, double slope, double inset = 0);

RoofedBlock flat_block(const Rect& r, double height);
// One plane: `low` at the `low_side` wall, rising across the block.
RoofedBlock shed_block(const Rect& r, Side low_side, double low, double slope);
// Ridge along x (along_x) or y; vertical gable ends.
RoofedBlock gable_block(const Rect& r, double eave, double slope, bool along_x);
// Ridge along x or y, hip ends rising at end_slope.
RoofedBlock hip_block(const Rect& r, double eave, double slope, double end_slope, bool along_x);
// Four triangles meeting in one apex `rise` above the eaves.
RoofedBlock pyramid_block(const Rect& r, double eave, double rise);
// Steep lower slopes on all four sides up to `inset` from the walls, then a shallow hipped top
// (upper_slope > 0) or a flat top (upper_slope == 0).
RoofedBlock mansard_block(const Rect& r, double eave, double lower_slope, double inset, double upper_slope);
// Two slopes on each long side (ridge along x or y), vertical gable ends.
RoofedBlock gambrel_block(const Rect& r, double eave, double lower_slope, double inset, double upper_slope, bool along_x);

}  // namespace lc2wf

// Roof / wall / ground from a face's normal and height: walls are near-vertical, the ground is a
// near-horizontal face at the lowest level that walls reach down to, everything else is roof.
#pragma once

#include "infer/surfaces/surface_model.h"

namespace lc2wf {

// Sets the label of every face of `model`. `wall_tilt_deg`: a face within this of vertical is a wall;
// `level_distance`: a face within this of the lowest vertex is at ground level.
void label_faces(SurfaceModel& model, double wall_tilt_deg, double level_distance);

}  // namespace lc2wf

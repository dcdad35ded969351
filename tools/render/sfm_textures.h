// Photo-like surface colours for structure from motion (the rasteriser's side of `--textures sfm`):
// high-contrast value noise summed over octaves from 9 cm to 6 m, which never repeats, tinted per
// surface kind. Each face reads the noise at its own far-apart offset, so symmetric faces differ and
// COLMAP cannot match one side of a house with the other. Pure functions of the world point.
#pragma once

#include <cstdint>

#include "tools/render/face_frames.h"
#include "tools/render/procedural_textures.h"

namespace lc2wf {

Rgb sfm_surface_colour(const FaceFrame& frame, const Vec3& X, uint64_t seed);
Rgb sfm_ground_colour(double x, double y, uint64_t seed);

}  // namespace lc2wf

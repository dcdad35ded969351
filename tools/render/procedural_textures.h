// Procedural surface colours by surface kind, in linear RGB, following the look of the LC2WF figures:
// terracotta roof tiles whose channels run down the slope, light siding or brick walls, grass ground.
// Every function is a pure function of the world point, so all views of a building agree.
#pragma once

#include <cstdint>

#include "tools/render/face_frames.h"

namespace lc2wf {

struct Rgb {
  float r = 0, g = 0, b = 0;
};

enum class WallStyle : uint8_t { Siding, Brick };

struct TextureStyle {
  WallStyle wall = WallStyle::Siding;
  uint64_t seed = 0;  // varies tile/board brightness and noise phase
};

// Colour of a point X lying on a face with the given frame.
Rgb surface_colour(const FaceFrame& frame, const Vec3& X, const TextureStyle& style);
// Colour of the ground (z = ground height) at world (x, y).
Rgb ground_colour(double x, double y, const TextureStyle& style);
// Sky colour for rays that miss everything.
Rgb sky_colour();

}  // namespace lc2wf

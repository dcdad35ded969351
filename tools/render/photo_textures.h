// Surface colours of the `--textures photo` look, in linear RGB: plaster walls with framed windows, sills
// and doors by storey (facade_layout.h), gutters under the eaves, finely coursed roof tiles, grass with a
// path and a road with kerbs, and the clutter objects of photo_scene.h (chimneys, balconies, cars, trees,
// neighbouring buildings). Pure functions of the world point and the scene, so all views agree.
#pragma once

#include <cstdint>

#include "tools/render/face_frames.h"
#include "tools/render/photo_scene.h"
#include "tools/render/procedural_textures.h"

namespace lc2wf {

class PhotoTextures {
 public:
  PhotoTextures(const PhotoScene& scene, uint64_t seed);

  // Face `face` of the building (index into scene.facades).
  Rgb building(int face, const FaceFrame& frame, const Vec3& X) const;
  // Face `face` of scene.clutter.
  Rgb clutter(int face, const FaceFrame& frame, const Vec3& X) const;
  Rgb ground(double x, double y) const;

 private:
  Rgb wall(const FacadeLayout& L, int face, const FaceFrame& frame, const Vec3& X) const;
  Rgb roof(const FaceFrame& frame, const Vec3& X) const;

  PhotoScene scene_;
  uint64_t seed_;
  Rgb plaster_, roof_, window_frame_;
};

}  // namespace lc2wf

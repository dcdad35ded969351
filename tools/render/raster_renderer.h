// Software renderer for Roof-Image buildings: z-buffer over the mesh's faces, per-surface procedural
// textures, Lambert shading from a sun, optional hard shadows (shadow map), grass ground and sky.
// Same scene content as the Blender script, at a fraction of the cost.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "tools/render/face_frames.h"
#include "tools/render/photo_scene.h"
#include "tools/render/photo_textures.h"
#include "tools/render/procedural_textures.h"

namespace lc2wf {

struct RasterOptions {
  int supersample = 1;               // samples per pixel side (1 = none); the image is box-filtered down
  bool shadows = true;               // hard shadows from the sun
  double sun_azimuth_deg = 140.0;    // from +x towards +y
  double sun_elevation_deg = 55.0;
  double ambient = 0.38;             // share of light that reaches surfaces facing away from the sun
  // Paper textures: share of that ambient light that falls off with the angle to the camera (as the studio light
  // of Blender's renders of the paper look): with a constant ambient, every two walls facing away from the sun
  // have the same shade and their corner draws no line. 0 = constant ambient (the renders before 2026-12-06).
  // The sfm and photo textures keep the view-independent light structure from motion matches across views.
  double view_light = 0.8;
  double noise_sigma = 1.5;          // Gaussian sensor noise, 8-bit levels (0 = none)
  // Optical blur (Gaussian, pixels) before the noise. Point-sampled tile textures alias into many
  // high-contrast texture segments; 1 px brings the line clouds close to Blender's anti-aliased renders
  // at ~2 ms per view (supersampling costs ~3x the render).
  double blur_sigma_px = 1.0;
  int shadow_map_size = 1024;
  uint64_t seed = 0;                 // texture variation and noise
  // or "sfm": non-repeating noise that COLMAP can match (sfm_textures.h); or "photo": windows, clutter
  // objects and per-view exposure (photo_scene.h, photo_textures.h)
  std::string textures = "paper";
  // The view light the images get: view_light with the paper look, 0 (a view-independent light) otherwise.
  double effective_view_light() const { return textures == "paper" ? view_light : 0.0; }
  void Check() const;
};

struct RasterImage {
  cv::Mat image;  // CV_8UC3, BGR, camera.width x camera.height
};

class RasterRenderer {
 public:
  // Throws std::invalid_argument for a bad mesh or bad options. `scene` is used with textures "photo"
  // (its clutter is drawn and casts shadows; the default scene has none).
  RasterRenderer(const PolyMesh& mesh, const RasterOptions& options, const PhotoScene& scene = {});

  // view_seed varies the sensor noise per view. Deterministic; safe to call from several threads.
  RasterImage render(const Camera& camera, uint64_t view_seed) const;

  // Camera-space depth (z) of the building per pixel, +inf where no face is hit; face ids (-1 = none; ids
  // from the building's face count on are the photo scene's clutter faces).
  void depth_map(const Camera& camera, cv::Mat& depth, cv::Mat& face_ids) const;

  const FacedMesh& mesh() const { return mesh_; }

 private:
  bool in_shadow(const Vec3& X) const;
  void build_shadow_map();

  FacedMesh mesh_;  // the building's faces, then (photo) the clutter's
  RasterOptions options_;
  int building_faces_ = 0;
  double ground_z_ = 0;
  PhotoOptions photo_options_;
  std::shared_ptr<const PhotoTextures> photo_;  // set with textures "photo"
  TextureStyle style_;
  Vec3 sun_ = Vec3::UnitZ();  // unit vector towards the sun
  Vec3 sun_a_ = Vec3::UnitX(), sun_b_ = Vec3::UnitY();
  double shadow_min_a_ = 0, shadow_min_b_ = 0, shadow_texel_ = 1;
  cv::Mat shadow_height_;  // CV_32F, max of sun . X per texel
};

// Camera whose pixel grid is `factor` times finer, with the same pixel-centre convention.
Camera supersampled_camera(const Camera& camera, int factor);

}  // namespace lc2wf

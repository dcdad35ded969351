// The `--textures photo` scene around a building: what real photos show besides the modelled surfaces.
// Balconies, chimneys, cars, trees and neighbouring buildings are extra 3D objects (a clutter mesh that is
// no part of the GT wireframe: it hides GT edges when labelling and its own lines come out f = 0); the
// ground gets a path from the front door and a road with kerbs; the sun and the per-view exposure, noise
// and blur vary. Every size derives from the building's storey height or extent, never a fixed building
// size. Deterministic in the seed; objects keep clear of the given camera centres and never hide the
// building's centre from a camera.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "tools/render/facade_layout.h"

namespace lc2wf {

struct PhotoOptions {
  FacadeOptions facades;        // windows (frames, sills) by storey, doors
  bool roof_tiles = true;       // fine course lines on pitched roofs (else a plain weathered roof)
  bool gutters = true;          // a dark gutter band under every eave
  bool balconies = true;        // boxes below some upper windows
  bool chimneys = true;         // boxes on some roofs
  bool ground = true;           // path, road with kerbs, cars
  bool trees = true;            // cones and blobs near the building
  bool neighbours = true;       // one or two building boxes at a distance
  bool vary_sun = true;         // sun direction per building (else RasterOptions' sun)
  double exposure_stops = 0.5;  // per-view exposure change, uniform in +-stops
  double noise_gain = 2.0;      // per-view sensor noise: the renderer's sigma times uniform [1, gain]
  double blur_gain = 1.6;       // per-view optical blur: the renderer's sigma times uniform [1, gain]
  void Check() const;
};

enum class ClutterKind : uint8_t { Chimney, Balcony, CarBody, CarCabin, Trunk, Foliage, NeighbourWall, NeighbourRoof };

struct GroundLayout {
  bool road = false;
  Vec2 road_point = Vec2::Zero(), road_dir = Vec2::UnitX();  // centre line
  double road_half_width = 0;
  std::vector<std::array<Vec2, 2>> paths;  // from each door outwards (centre line)
  double path_half_width = 0;
};

struct PhotoScene {
  PhotoOptions options;
  std::vector<FacadeLayout> facades;   // one per building face
  PolyMesh clutter;                    // extra objects; faces are triangles or planar quads/polygons
  std::vector<ClutterKind> kinds;      // one per clutter face
  std::vector<uint32_t> objects;       // one per clutter face: object id (varies colours)
  GroundLayout ground;
  double sun_azimuth_deg = 140.0, sun_elevation_deg = 55.0;
  double storey_height = 3.0;          // of the tallest wall (sizes chimneys, balconies, paths)
};

// Throws std::invalid_argument for bad options or a mesh without faces.
PhotoScene make_photo_scene(const PolyMesh& building, const std::vector<Vec3>& camera_centres, const PhotoOptions& options,
                            uint64_t seed);

// The building's mesh followed by the clutter's faces (for the renderers' depth and shadows and the
// labels' visibility test); the clutter faces are labelled Wall.
PolyMesh scene_mesh(const PolyMesh& building, const PhotoScene& scene);

// Per-view photometry of a photo render.
struct ViewPhotometry {
  double exposure = 1.0;    // linear gain
  double noise_gain = 1.0;
  double blur_gain = 1.0;
};
ViewPhotometry view_photometry(const PhotoOptions& options, uint64_t seed, uint64_t view);

}  // namespace lc2wf

// Seeded augmentation of a building mesh before rendering: its height scaled to a drawn target (the
// Roof-Image buildings are all 7-9 m tall; real ones 3-60 m), independent horizontal stretches along its own
// x and y, and a turn about the vertical. Affine, so faces stay planar and the mesh stays closed; the
// ground stays at z = 0 and the turn is about the centre of the footprint's bounding box (put at x = y = 0).
#pragma once

#include <cstdint>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct MeshAugmentOptions {
  bool scale_height = true;
  double height_min_m = 3.0;    // target height, drawn log-uniform in [min, max]
  double height_max_m = 60.0;
  double stretch_min = 0.8;     // horizontal scale per axis, drawn log-uniform in [min, max]
  double stretch_max = 1.25;
  bool turn = true;             // a uniform turn about the vertical
  void Check() const;
};

struct MeshAugmentation {
  double target_height_m = 0;   // 0: height kept
  double scale_x = 1, scale_y = 1;
  double turn_rad = 0;
};

// Draws rounded to centimetres / thousandths, so the result does not hang on a C library's last bit.
MeshAugmentation draw_mesh_augmentation(uint64_t seed, const MeshAugmentOptions& options);

// Mesh in metres (any ground height); throws std::invalid_argument for a mesh without height.
PolyMesh augment_mesh(const PolyMesh& mesh, const MeshAugmentation& augmentation);
PolyMesh augment_mesh(const PolyMesh& mesh, uint64_t seed, const MeshAugmentOptions& options);

}  // namespace lc2wf

// Texture lines a photo reconstruction finds on a building's faces and on the ground around it. Clouds
// triangulated from textured photos are mostly such lines (≈ 5,000 per building, ≈ 11 % on GT edges,
// half of the rest outside the building's footprint), while our renders have few; a model that never saw
// them finds almost no junction in those clouds. Faces are not stored with a cloud, so the face lines
// lie in the corners of the wireframe: the triangle spanned by two edges that meet at a junction (at a
// junction of degree 3, every such pair bounds a face).
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/line_cloud.h"
#include "dataset/sampling/rng.h"

namespace lc2wf {

struct SurfaceClutterOptions {
  int face_lines = 0;           // lines in the wireframe's corners
  int ground_lines = 0;         // lines on the ground plane (lowest junction) around the footprint
  double ground_margin_m = 8.0; // ground lines reach this far beyond the junctions' xy box
  double corner_reach_m = 3.0;  // a corner's triangle spans at most this far along each edge
  double min_length_m = 0.05;   // lengths are uniform in [min, max]
  double max_length_m = 1.0;
  void Check() const;
};

// Random lines, none inside the footprint box on the ground (a roof hides that ground). Empty when the
// wireframe has no corner (face lines) or no junction (all lines). Deterministic for the generator.
std::vector<Segment3> make_surface_clutter(const Wireframe& wireframe, const SurfaceClutterOptions& options,
                                           DataRng& rng);

// The cloud with such lines appended: unlabelled (f = 0, no junction) and with empty support lists.
LineCloud with_surface_clutter(const LineCloud& cloud, const SurfaceClutterOptions& options, uint64_t seed);

}  // namespace lc2wf

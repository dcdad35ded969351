// Procedural LoD2 buildings of every roof kind and size (lod2_kinds.h): seeded, the same buildings on every
// compiler (xoshiro256** draws, sizes rounded to centimetres, slopes to 1/1000), each a closed mesh whose
// polygon edges are the edges a person would draw (coplanar neighbours merged, no triangulation), labelled
// roof / wall / base like Roof-Image. Heights from about 3 m (a garden shed) to 60 m (a tower), footprints
// from about 3.5 m to 150 m.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/synthetic/block_assembly.h"
#include "dataset/synthetic/lod2_kinds.h"

namespace lc2wf {

struct Lod2Options {
  Lod2KindWeights kinds;               // how often each kind is drawn (generate_lod2_building(seed, ...))
  bool turn = true;                    // a random turn about the vertical (footprints are drawn axis-aligned)
  double min_vertex_distance_m = 0.1;  // a draw with corners closer than this is redrawn
  int max_attempts = 16;               // redraws before giving up
  void Check() const;
};

struct GeneratedBuilding {
  Lod2Kind kind = Lod2Kind::Flat;
  PolyMesh mesh;                  // metres, ground at z = 0, footprint's bounding box centred on x = y = 0
  double height_m = 0;            // highest vertex
  double footprint_long_m = 0;    // footprint's bounding box in the building's own axes (before the turn)
  double footprint_short_m = 0;
  int attempts = 1;               // draws it took (redraws when corners came too close)
};

// The blocks of one draw of a kind, in the building's own axes (for tests and for the generator).
std::vector<RoofedBlock> lod2_blocks(Lod2Kind kind, uint64_t seed);

Lod2Kind pick_lod2_kind(uint64_t seed, const Lod2KindWeights& weights);
GeneratedBuilding generate_lod2_building(Lod2Kind kind, uint64_t seed, const Lod2Options& options = {});
// Kind drawn from options.kinds with the same seed.
GeneratedBuilding generate_lod2_building(uint64_t seed, const Lod2Options& options = {});

}  // namespace lc2wf

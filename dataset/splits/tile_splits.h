// The split of real city buildings: by map tile, never by building, so neighbours (the same street, the same
// modeller's habits) never sit on both sides of it; and per source, so every source is in every split.
// Rule: tile = (file, floor(x / tile_size), floor(y / tile_size)) of the building's footprint centre in
// the file's coordinates. Within each source, tiles sorted by (mix(FNV-1a-64(tile key), seed), tile key):
// a tile goes to test while the source's test buildings are below test_share of its buildings, then to val
// while val is below val_share, the rest to train. Each list is written sorted by name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/splits/splits.h"

namespace lc2wf {

struct TileSplitEntry {
  std::string name;    // unique building name
  std::string source;  // e.g. "nrw", "3dbag"
  std::string file;    // the file the building came from (tiles never span two files)
  double x = 0, y = 0; // footprint centre, metres in the file's frame
};

struct TileSplitRule {
  uint64_t seed = 1555;
  double tile_size_m = 500;
  double test_share = 0.08;
  double val_share = 0.04;
  void Check() const;
};

std::string tile_key(const TileSplitEntry& entry, double tile_size_m);

// Throws std::invalid_argument on duplicate names or a non-finite position.
Splits make_tile_splits(const std::vector<TileSplitEntry>& entries, const TileSplitRule& rule = {});

// The source of a file from rules "PATTERN=SOURCE" (shell patterns on the path relative to the data folder,
// first match wins); "" when no rule matches.
std::string source_of(const std::string& relative_path, const std::vector<std::string>& rules);

}  // namespace lc2wf

// The published split of real city buildings (configs/splits/lod2/): every building of the given folders
// loaded as lc2wf-dataset loads it, placed on its map tile, split by tile_splits.h, and described per
// source and split (heights, footprints, roof kinds, wireframe sizes) so the split can be judged at a glance.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dataset/formats/building_sources.h"
#include "dataset/splits/tile_splits.h"

namespace lc2wf {

struct CitySplitOptions {
  std::vector<std::filesystem::path> inputs;  // folders (their files, not sub-folders) or files
  std::filesystem::path root;                 // source rules match paths relative to this
  std::vector<std::string> source_rules;      // "PATTERN=SOURCE", first match wins; unmatched: the file's folder
  BuildingSourceOptions sources;
  TileSplitRule rule;
  int threads = 1;
  void Check() const;
};

// One building as the split saw it.
struct CitySplitBuilding {
  std::string name, source, file, split, roof_kind;
  double x = 0, y = 0;            // footprint centre in the file's frame (metres; lon/lat scaled for geographic)
  double height_m = 0, long_side_m = 0, short_side_m = 0;
  int junctions = 0, edges = 0;   // GT wireframe
};

struct CitySplitResult {
  Splits splits;
  std::vector<CitySplitBuilding> buildings;          // sorted by name
  std::vector<std::pair<std::string, std::string>> skipped;  // name (or file), reason
};

CitySplitResult make_city_split(const CitySplitOptions& options);

// Markdown: per source and split, buildings, height / footprint p10-p50-p90, roof kinds, junctions / edges.
std::string city_split_statistics_markdown(const CitySplitResult& result);

}  // namespace lc2wf

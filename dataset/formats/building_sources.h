// The one way to list and load buildings: a folder (or a single file) of Roof-Image `.polyshape` meshes
// and real city models (CityJSON `.city.json` / `.json`, CityJSONSeq `.jsonl`, CityGML `.gml` /
// `.gml.gz`) -> a sorted list of named buildings, and one building by name. lc2wf-dataset --meshes and
// lc2wf-eval --gt read buildings through here.
//
// Names: a polyshape's file stem (as before); a city-model building `<file stem>__<building id>`, sanitised
// to [A-Za-z0-9._-] (other bytes -> '_'; over 150 bytes: cut, plus a hash of the whole), a repeated
// name gets `__2`, `__3`, ... in listing order. Each city-model file is parsed once to list it and once
// more when its buildings are loaded (a small cache of parsed files serves the rest of its buildings,
// so load them grouped by file, e.g. in name order); memory stays at a few files' polygons.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "dataset/formats/city_model.h"
#include "dataset/formats/errors.h"
#include "dataset/geometry/building.h"
#include "dataset/geometry/lod2_cleanup.h"

namespace lc2wf {

struct BuildingSourceOptions {
  std::string lod;  // LoD of city models: "2.2", "2.1", "2" (= "2.0"); empty = the highest 2.x a building has
  Lod2CleanupOptions cleanup;
  int cached_files = 4;  // parsed city-model files kept for loading their buildings
  void Check() const;
};

enum class BuildingFormat { kPolyshape, kCityJson, kCityJsonSeq, kCityGml };

struct BuildingEntry {
  std::string name;
  std::filesystem::path file;
  BuildingFormat format = BuildingFormat::kPolyshape;
  std::string object_id;  // city models: the Building's id in the file
  int ordinal = 0;        // city models: index among the file's listed buildings (ids may repeat)
};

// Per city-model file: what listing found.
struct SourceFileListing {
  std::filesystem::path file;
  BuildingFormat format = BuildingFormat::kCityJson;
  int buildings = 0;        // listed (have the requested LoD)
  int without_lod = 0;      // Buildings without it (e.g. LoD 0/1 only): not listed
  std::string error;        // non-empty: the file could not be read and lists no building
};

// A city-model building rejected by the clean-up; reason() is a short key for counting.
class Lod2Skipped : public BuildingSkipped {
 public:
  Lod2Skipped(const std::string& name, const std::string& detail, std::string reason)
      : BuildingSkipped(name, detail), reason_(std::move(reason)) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

// What loading a city-model building did (for statistics).
struct CityLoadInfo {
  std::string lod;
  CityCrs crs = CityCrs::kProjected;
  TangentPlane tangent_plane;  // geographic CRS: the local frame's origin
  Lod2CleanupReport cleanup;
};

// True for the names city-model files end with (`.city.json`, `.json`, `.jsonl`, `.gml`, `.gml.gz`).
bool is_city_model_file_name(const std::filesystem::path& path);
// `name` as a safe file name: [A-Za-z0-9._-] only, no leading '.', at most 150 bytes.
std::string sanitise_building_name(const std::string& name);

class BuildingCatalog {
 public:
  // Lists every building of a folder's files (not its sub-folders) or of one file. A city-model file
  // that cannot be read lists nothing and is named in files() with its error. Throws DataError when the
  // folder cannot be listed or the file is not a building source.
  explicit BuildingCatalog(const std::filesystem::path& folder_or_file, BuildingSourceOptions options = {});

  const std::vector<BuildingEntry>& entries() const { return entries_; }  // sorted by name
  std::vector<std::string> names() const;
  const BuildingEntry* find(const std::string& name) const;
  const std::vector<SourceFileListing>& files() const { return files_; }  // city-model files, sorted

  // One building in metres. Polyshapes: load_roof_image_building(file, options), unchanged. City models:
  // the chosen LoD's polygons in a local frame (projected CRS: shifted by the building's offset;
  // geographic CRS: the tangent plane at the building's centre, TangentPlane), cleaned (lod2_cleanup.h),
  // then make_building with raw_per_metre 1, so `units` maps back to CRS metres (tangent-plane metres for
  // a geographic CRS). Throws DataError (unknown name, unreadable file) or Lod2Skipped. Thread-safe.
  Building load(const std::string& name, const BuildingOptions& options = {}, CityLoadInfo* info = nullptr) const;

 private:
  struct ParsedFile;
  std::shared_ptr<const ParsedFile> parsed(const BuildingEntry& entry) const;

  BuildingSourceOptions options_;
  std::vector<BuildingEntry> entries_;
  std::vector<SourceFileListing> files_;
  mutable std::mutex mu_;
  mutable std::vector<std::pair<std::filesystem::path, std::shared_ptr<const ParsedFile>>> cache_;  // most recent last
};

}  // namespace lc2wf

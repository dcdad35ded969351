// Readers for CityJSON 1.0 / 1.1 / 2.0 (`.city.json`, `.json`) and CityJSONSeq (`.jsonl`: a CityJSON
// header line with the `transform`, then one CityJSONFeature per line with its own vertices). Every
// `Building` with its `BuildingPart` children (recursively) becomes one CityBuilding holding each LoD 2.x
// it has; `transform` is applied. Throws DataError("<file>:<line>: <problem>").
#pragma once

#include <filesystem>
#include <functional>
#include <istream>
#include <string>

#include "dataset/formats/city_model.h"

namespace lc2wf {

using CityBuildingVisitor = std::function<void(CityBuilding&&)>;

// One CityJSON document (the whole file is parsed at once; its DOM is freed before returning).
void read_city_json(const std::filesystem::path& path, const CityBuildingVisitor& visit);
void parse_city_json(const std::string& text, const std::string& source_name, const CityBuildingVisitor& visit);

// CityJSONSeq, one line at a time (memory: the header plus the largest feature).
void read_city_json_seq(const std::filesystem::path& path, const CityBuildingVisitor& visit);
void parse_city_json_seq(std::istream& in, const std::string& source_name, const CityBuildingVisitor& visit);

// Whether a `.json` file is a CityJSON document (its first 64 KiB name the type "CityJSON"); other JSON
// files in a folder of buildings are not building sources.
bool looks_like_city_json(const std::filesystem::path& path);

}  // namespace lc2wf

// Reader for CityGML 1.0 / 2.0 building models (`.gml`, or gzip-compressed `.gml.gz`), one Building
// element at a time (xml_reader.h). A Building with its BuildingParts becomes one CityBuilding with its
// LoD 2 polygons: those of the `boundedBy` semantic surfaces (RoofSurface, WallSurface, ...,
// `lod2MultiSurface`), plus polygons of `lod2Solid` / `lod2MultiSurface` no semantic surface holds (no
// semantics). `xlink:href` references inside the building are resolved. Throws DataError.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/formats/city_json_io.h"  // CityBuildingVisitor
#include "dataset/formats/city_model.h"

namespace lc2wf {

void read_city_gml(const std::filesystem::path& path, const CityBuildingVisitor& visit);
void parse_city_gml(std::string text, const std::string& source_name, const CityBuildingVisitor& visit);

}  // namespace lc2wf

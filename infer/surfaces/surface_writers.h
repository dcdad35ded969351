// A surface model on disk, beside the wireframe `NAME.obj` of the same run and in its frame and units:
// `NAME.city.json` (CityJSON 2.0: one Building, LoD 2.2 Solid when the shell is a valid closed solid, else
// MultiSurface, with RoofSurface / WallSurface / GroundSurface semantics) and `NAME.faces.obj` (one polygon
// per face, grouped `g roof`, `g wall`, `g ground`). Both written atomically.
#pragma once

#include <filesystem>
#include <string>

#include "infer/surfaces/surface_model.h"

namespace lc2wf {

struct SurfaceOutputOptions {
  // Coordinates as the wireframe .obj written with --units raw: the source's raw units (`source_units`
  // maps metres back); false: metres.
  bool raw_units = false;
  UnitTransform source_units;   // the cloud's metres <-> raw transform; recorded in the metadata when not the identity
  std::string reference_system; // CRS URL (http://www.opengis.net/def/crs/...) when the source has one
  double scale = 0.001;         // CityJSON `transform.scale`: the coordinate step in output units
};

// The CityJSON text; `name` is the Building's id. Throws std::invalid_argument on a bad scale or a
// reference system that is not an OGC CRS URL.
std::string cityjson_string(const SurfaceModel& model, const std::string& name, const SurfaceOutputOptions& options = {});
std::string faces_obj_string(const SurfaceModel& model, const SurfaceOutputOptions& options = {});

// Writes `<dir>/<name>.city.json` and `<dir>/<name>.faces.obj`. Throws std::invalid_argument when `name` is
// not a plain file name, std::runtime_error on I/O errors.
void write_surface_outputs(const std::filesystem::path& dir, const std::string& name, const SurfaceModel& model,
                           const SurfaceOutputOptions& options = {});

}  // namespace lc2wf

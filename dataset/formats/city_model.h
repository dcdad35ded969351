// A building as the city-model readers (city_json_io.h, city_gml_io.h) hand it over: its LoD 2.x polygons
// in the file's coordinates (transform applied), with their semantic surface and the part they came from,
// before any clean-up. The clean-up into a PolyMesh is dataset/geometry/lod2_cleanup.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Semantic surface of a polygon; kUnknown when the file gives none (classified later by normal and height).
enum class CitySurface : uint8_t { kUnknown, kRoof, kWall, kGround };

// RoofSurface -> roof; GroundSurface -> ground; every other surface type (WallSurface, ClosureSurface,
// OuterCeilingSurface, OuterFloorSurface, Window, Door, ...) -> wall; empty -> unknown.
CitySurface city_surface_of(const std::string& city_type);

struct CityPolygon {
  std::vector<Vec3> exterior;                 // as written (a closing repeat of the first vertex is allowed)
  std::vector<std::vector<Vec3>> interiors;   // inner rings (holes)
  CitySurface kind = CitySurface::kUnknown;
  int part = 0;                               // 0 = the Building itself, 1.. = its parts in file order
};

struct CityLodGeometry {
  std::string lod;  // normalised: "2", "2.1", "2.2" ("2.0" is written "2")
  std::vector<CityPolygon> polygons;
};

// How a file's coordinates are to be read.
enum class CityCrs : uint8_t {
  kProjected,     // x, y, z in metres (a projected CRS, or none given)
  kLatLonHeight,  // geographic, latitude first (GML axis order of EPSG:6697, EPSG:4326, ...)
  kLonLatHeight,  // geographic, longitude first (CityJSON's x-y-z order with a geographic CRS)
};

struct CityBuilding {
  std::string id;      // the Building's id in the file
  int line = 0;        // 1-based line of the building in its file (0 when unknown), for messages
  int parts = 1;       // the Building plus its BuildingParts
  CityCrs crs = CityCrs::kProjected;
  std::vector<CityLodGeometry> lods;  // every LoD 2.x the building or its parts carry, highest first
};

// "2", "2.0" -> "2"; "2.2" -> "2.2"; numbers as CityJSON 1.0 writes them (2, 2.2) after formatting.
// Empty for anything that is not a LoD 2.x ("1.2", "3", "abc").
std::string normalise_lod2(const std::string& lod);

// The geometry of the requested LoD ("" = the highest present; "2" and "2.0" are the same); nullptr when
// the building has none.
const CityLodGeometry* select_lod(const CityBuilding& building, const std::string& lod);

// Whether a CRS name (EPSG URN/URL, "EPSG:6697", srsName) is a geographic (latitude/longitude) CRS.
bool is_geographic_crs(const std::string& crs_name);

// A local metric frame about `origin`: east, north, up metres on the tangent plane of the GRS80 ellipsoid
// (the same as WGS84 to 0.1 mm) at the origin's latitude/longitude, heights taken as ellipsoidal. Over a
// building (< 1 km) the plane deviates from the ellipsoid by < 8 cm at 1 km and by < 1 mm within 100 m.
struct TangentPlane {
  double lat0_deg = 0, lon0_deg = 0, h0 = 0;
  Vec3 to_local(double lat_deg, double lon_deg, double h) const;
};

}  // namespace lc2wf

// Hand-made and seeded random buildings (rectangles and L-shapes with hip or gable ends) shaped like the
// Roof-Image meshes: eaves at 3.75 m, labelled faces (roof / base / wall), roof vertices first.
// Unit tests and the demo use these instead of the real data.
#pragma once

#include <cstdint>
#include <string>

#include "dataset/geometry/building.h"

namespace lc2wf {

enum class RoofEnd { Hip, Gable };

// Rectangle length x width (x along the ridge), roof ends west (-x) / east (+x).
struct RectBuildingSpec {
  double length = 12.0;
  double width = 9.0;
  double eave_height = 3.75;
  double slope_deg = 37.0;
  RoofEnd west = RoofEnd::Hip;
  RoofEnd east = RoofEnd::Hip;
  void Check() const;
};

// L footprint (0,0) (length_x,0) (length_x,wing) (wing,wing) (wing,length_y) (0,length_y); both wings
// have width `wing`; the roof ends at x = length_x and y = length_y are hips or gables, the outer corner
// is a hip and the inner corner a valley.
struct LBuildingSpec {
  double length_x = 16.0;
  double length_y = 14.0;
  double wing = 8.0;
  double eave_height = 3.75;
  double slope_deg = 37.0;
  RoofEnd end_x = RoofEnd::Hip;
  RoofEnd end_y = RoofEnd::Hip;
  void Check() const;
};

// Meshes in metres (not yet centred).
PolyMesh make_rect_mesh(const RectBuildingSpec& spec);
PolyMesh make_l_mesh(const LBuildingSpec& spec);

// Buildings go through the same import as Roof-Image (raw = 20 x metres, recentred), so the units
// round-trip to Roof-Image-like raw coordinates.
Building make_rect_building(const std::string& name, const RectBuildingSpec& spec);
Building make_l_building(const std::string& name, const LBuildingSpec& spec);

// Seeded random variant: rectangle or L, hip or gable ends, sizes and slope in the Roof-Image ranges.
Building make_random_building(uint64_t seed, const std::string& name);

}  // namespace lc2wf

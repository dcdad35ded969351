// Writes the CityJSON (and faces OBJ) of the hand-made buildings into a folder, for the schema test
// (cityjson_schema_test.sh): every shape closed, one with a missing edge, a roof without walls (MultiSurface),
// raw units with a source transform, a wireframe without faces and a roof closed by the prism rule.
#include <cstdio>
#include <exception>

#include "infer/surfaces/surface_writers.h"
#include "infer/surfaces/wireframe_surfaces.h"
#include "tests/infer/surface_fixtures.h"

int main(int argc, char** argv) {
  using namespace lc2wf;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path out = argv[1];
    for (const testing::FixtureBuilding& b : testing::all_fixture_buildings()) {
      write_surface_outputs(out, b.name, surfaces_from_wireframe(b.wireframe));
      write_surface_outputs(out, b.name + "_missing_edge", surfaces_from_wireframe(testing::without_edge(b.wireframe, b.removable_edge)));
    }
    const testing::FixtureBuilding g = testing::gabled_building();
    SurfaceOutputOptions raw;
    raw.raw_units = true;
    raw.source_units.raw_per_metre = 20;
    raw.source_units.origin_raw = Vec3(2600000, 1200000, 400);
    raw.reference_system = "https://www.opengis.net/def/crs/EPSG/0/2056";
    write_surface_outputs(out, "roof_only_raw",
                          surfaces_from_wireframe(testing::make_wireframe(g.wireframe.junctions,
                                                                          {{4, 5}, {7, 6}, {4, 8}, {7, 8}, {5, 9}, {6, 9}, {8, 9}})),
                          raw);
    write_surface_outputs(out, "no_faces", surfaces_from_wireframe(Wireframe{}));
    // A hipped roof with vertical edges at two corners only and no ground edges: closed by the prism rule.
    const testing::FixtureBuilding h = testing::hipped_building();
    write_surface_outputs(out, "hipped_prism",
                          surfaces_from_wireframe(testing::make_wireframe(h.wireframe.junctions,
                                                                          {{4, 5}, {5, 6}, {6, 7}, {4, 7}, {4, 8}, {7, 8}, {5, 9},
                                                                           {6, 9}, {8, 9}, {0, 4}, {2, 6}})));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 3;
  }
  return 0;
}

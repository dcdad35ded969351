// A building in metres: its labelled mesh, the ground-truth wireframe and the raw<->metre transform,
// plus mesh checks/repairs (duplicate vertices, non-planar faces, non-manifold edges).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct WireframeOptions {
  // The release keeps every unique polygon edge; dropping edges between coplanar faces gives a
  // "sharp edges only" wireframe (e.g. no gable-triangle/wall seam).
  bool drop_coplanar_edges = false;
  double coplanar_angle_deg = 1.0;  // faces whose normals differ by less than this are coplanar
  void Check() const;
};

// Junctions = all vertices; edges = unique consecutive vertex pairs of every face, stored (min, max), in
// first-seen order (the release's definition).
Wireframe build_wireframe(const PolyMesh& mesh, const WireframeOptions& options = {});

// Facts about a mesh, in the mesh's own units.
struct MeshReport {
  int duplicate_vertex_pairs = 0;   // vertex pairs closer than the tolerance
  int non_manifold_edges = 0;       // undirected edges not shared by exactly two faces
  double max_planarity_deviation = 0;  // max distance of a face vertex to its face's best-fit plane
  int unique_edges = 0;
  int roof_faces = 0;
};
MeshReport analyse_mesh(const PolyMesh& mesh, double duplicate_tolerance);

// Merges vertices closer than `tolerance` (to the lowest id), removes repeated consecutive ids and faces
// left with fewer than 3 distinct vertices. Returns the number of merged vertices; `dropped_faces` is
// incremented per removed face.
int merge_duplicate_vertices(PolyMesh& mesh, double tolerance, int* dropped_faces = nullptr);

enum class NonPlanarPolicy { Keep, Skip };

struct BuildingOptions {
  double raw_per_metre = kRawUnitsPerMetre;  // Roof-Image meshes are in raw units
  bool recentre_xy = true;          // x/y origin at the centre of the footprint's bounding box
  double duplicate_tol_m = 0.005;   // 5 mm: merges 48 near-duplicate vertices in 20 Roof-Image buildings
  double planarity_tol_m = 0.05;    // typical faces deviate by 1e-7 m; the one bad building by 1.6 m
  NonPlanarPolicy non_planar = NonPlanarPolicy::Keep;
  WireframeOptions wireframe;
  // false: the GT wireframe is the release's (every polyshape vertex, every unique polygon edge), taken
  // before the duplicate repair that only the rendered mesh needs; true: the repaired mesh's wireframe.
  bool gt_after_repair = false;
  void Check() const;
};

struct BuildingIssues {
  int merged_vertices = 0;
  int dropped_faces = 0;
  int non_manifold_edges = 0;         // after repair; harmless for the wireframe, reported only
  double max_planarity_dev_m = 0;
  bool non_planar = false;
  std::vector<std::string> warnings;  // human-readable, each names the building
};

struct Building {
  std::string name;
  PolyMesh mesh;        // metres, z up, ground at 0, near-duplicate vertices merged (for rendering)
  UnitTransform units;  // metres <-> raw units of the source file
  Wireframe wireframe;  // metres; junction ids are the source file's vertex ids unless gt_after_repair
  BuildingIssues issues;
};

// Converts a raw mesh (source units) into a Building. Throws BuildingSkipped when a policy rejects it and
// DataError for unusable meshes (fewer than 2 vertices, no faces).
Building make_building(const std::string& name, PolyMesh raw_mesh, const BuildingOptions& options = {});

// Loads `<dir>/<name>.polyshape`; the building name is the file stem.
Building load_roof_image_building(const std::filesystem::path& polyshape, const BuildingOptions& options = {});

// Sorted building names (file stems) of all `.polyshape` files in a folder.
std::vector<std::string> list_polyshape_names(const std::filesystem::path& dir);

}  // namespace lc2wf

// Clean-up of a real LoD2 building's polygons into the mesh a person would draw the wireframe of: in this
// order, inner rings dropped; vertices within 5 mm welded; coplanar adjacent faces of one semantic type
// merged (triangulated input becomes polygons); coincident face pairs removed (walls shared by two parts,
// interior faces); T-junctions made conforming; degree-2 vertices on a straight line removed; buildings
// that do not close or are degenerate rejected with a reason. The result is a PolyMesh, so rendering,
// labels and the GT wireframe (unique polygon edges) work on it unchanged. Each step is a function of its
// own, tested on its own (tests/dataset/lod2_cleanup_test.cpp).
#pragma once

#include <string>
#include <vector>

#include "dataset/formats/city_model.h"
#include "dataset/geometry/geometry.h"
#include "dataset/geometry/mesh_repair.h"

namespace lc2wf {

struct Lod2CleanupOptions {
  double weld_tol_m = 0.005;          // vertices closer than this are one vertex
  double coplanar_distance_m = 0.03;  // a merged face's vertices lie within this of the surface's plane
  double coplanar_angle_deg = 3.0;    // and its normal within this angle of the plane's normal ...
  double sliver_height_m = 0.05;      // ... unless it is a sliver this thin (rounded coordinates tilt it)
  double on_edge_tol_m = 0.01;        // a vertex this close to another face's edge is inserted into it
  double collinear_tol_m = 0.01;      // a degree-2 vertex this close to its neighbours' line is removed
  double ground_tol_m = 0.05;         // unlabelled downward faces this close to the lowest vertex are ground
  void Check() const;
};

// Indexed faces with their semantic surface and the building part they came from (the working form).
struct Lod2Mesh {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
  std::vector<CitySurface> kinds;
  std::vector<int> parts;
};

// Counts of what each step did, and vertices / unique edges before (exact coordinates, every ring) and after.
struct Lod2CleanupReport {
  int input_polygons = 0;
  int vertices_before = 0, edges_before = 0;
  int inner_rings_dropped = 0;
  int welded_vertices = 0;            // vertices merged into another within weld_tol_m
  int degenerate_faces_dropped = 0;   // fewer than 3 distinct vertices or no area after welding
  int unlabelled_faces = 0;           // classified by normal and height
  int faces_merged = 0;               // faces absorbed into a coplanar neighbour's polygon
  int coincident_faces_removed = 0;
  int t_junction_vertices = 0;        // vertices inserted into edges
  int collinear_vertices_removed = 0;
  int vertices_after = 0, edges_after = 0, faces_after = 0, roof_faces_after = 0;
};

// Step 1: inner rings dropped (returns how many).
int drop_inner_rings(std::vector<CityPolygon>& polygons);
// Step 2: indexed mesh through the shared VertexWelder (mesh_repair.h): vertices within `tol` welded (to the
// first one seen), repeated consecutive ids, faces with < 3 distinct vertices or of no area dropped.
Lod2Mesh weld_polygons(const std::vector<CityPolygon>& polygons, double tol, Lod2CleanupReport* report = nullptr);
// Faces without semantics: within 10 degrees of vertical -> wall; facing down with every vertex within
// ground_tol_m of the lowest vertex -> ground; other downward faces -> wall (overhangs); upward -> roof.
// "Down" follows the mesh's orientation, flipped when its signed volume is negative. Returns how many.
int classify_unlabelled_faces(Lod2Mesh& mesh, const Lod2CleanupOptions& options);
// Step 3: adjacent faces of one kind, same orientation, whose planes agree, become one polygon (the
// boundary of their union; holes the union encloses are dropped like inner rings). Seeds are taken
// largest face first; the plane is the area-weighted one of the faces merged so far. Edges are first
// made conforming at weld_tol_m so triangles that meet at a T still count as adjacent. Returns the
// number of faces absorbed.
int merge_coplanar_faces(Lod2Mesh& mesh, const Lod2CleanupOptions& options);
// Step 4: faces with the same vertex set: both removed when they run in opposite directions (a wall shared
// by two parts, an interior face), one of them kept when they are plain duplicates. Returns faces removed.
int remove_coincident_faces(Lod2Mesh& mesh);
// Step 5 (T-junctions, at on_edge_tol_m) and step 6 (collinear vertices, at collinear_tol_m) are the shared
// conform_t_junctions and remove_collinear_vertices of mesh_repair.h, run on the mesh's vertices and faces.
// Why the mesh is not a usable closed building, empty when it is: every edge must belong to two faces or
// lie on a face (within on_face_tol of its plane, inside its outline: where an inner ring was dropped); the
// edges are counted by the shared closure check (closed_mesh.h).
// `reason` gets a short key (not_closed, no_roof, too_few_faces, flat) for counting.
std::string closure_problem(const Lod2Mesh& mesh, std::string* reason = nullptr, double on_face_tol = 0.03);

// Unused vertices dropped; labels Roof / Wall / Base (ground).
PolyMesh to_poly_mesh(const Lod2Mesh& mesh);

struct Lod2CleanupResult {
  PolyMesh mesh;              // valid when skip_reason is empty
  Lod2CleanupReport report;
  std::string skip_reason;    // short key (see closure_problem; also no_polygons)
  std::string skip_detail;    // human-readable
};

// All steps in order. Coordinates should be local (near the origin) for full precision.
Lod2CleanupResult cleanup_lod2(std::vector<CityPolygon> polygons, const Lod2CleanupOptions& options = {});

}  // namespace lc2wf

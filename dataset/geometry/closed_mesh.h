// Closed polygon meshes from faces given as point lists, and the one check of closure: every edge used by
// exactly two faces in opposite directions, no vertex in the middle of another face's edge, no duplicate
// vertex, planar faces, outward orientation. The procedural buildings and the mesh augmentation are held
// to all of it; the LoD2 clean-up to its open edges (an edge lying on another face allowed).
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/geometry/mesh_repair.h"

namespace lc2wf {

struct PointFace {
  std::vector<Vec3> points;  // counter-clockwise seen from outside
  FaceLabel label = FaceLabel::Wall;
};

// The shared repair steps (mesh_repair.h) in order: weld (faces with < 3 distinct vertices or no area
// dropped), every vertex that lies on another face's edge put into that face (so each edge is shared by
// exactly two faces), vertices that only continue a straight edge removed, unused vertices dropped: the
// polygon edges left are the ones a person would draw.
PolyMesh mesh_from_faces(const std::vector<PointFace>& faces, const MeshRepairOptions& options = {});

struct ClosedMeshOptions {
  double tol = 1e-6;         // vertices closer than this are duplicates; this close to an edge, a T-junction
  double on_face_tol = 0;    // > 0: an edge of one face lying on another face (within this of its plane,
                             // inside its outline) is not open: the rim of a dropped inner ring
  void Check() const;
};

struct ClosedMeshReport {
  int edges_not_shared_by_two = 0;   // undirected edges used by one face or by more than two
  int edges_used_once = 0;           // of those, by one face ...
  int edges_on_faces = 0;            // ... lying on another face (counted with on_face_tol > 0 only)
  int open_edges = 0;                // ... the rest: holes in the surface
  double open_length = 0;            // their total length
  int edges_same_direction = 0;      // edges whose two faces walk them the same way (flipped face)
  int vertices_inside_edges = 0;     // T-junctions: a vertex strictly inside an edge of some face
  int duplicate_vertex_pairs = 0;    // vertex pairs closer than the tolerance
  int degenerate_faces = 0;          // < 3 vertices, or a vertex repeated within a face
  int unused_vertices = 0;
  double max_planarity_deviation = 0;
  double min_vertex_distance = 0;
  double volume = 0;                 // > 0 when the faces point outwards
  bool closed() const {
    return edges_not_shared_by_two == 0 && edges_same_direction == 0 && vertices_inside_edges == 0 &&
           duplicate_vertex_pairs == 0 && degenerate_faces == 0 && unused_vertices == 0 && volume > 0;
  }
};

ClosedMeshReport inspect_closed_mesh(const PolyMesh& mesh, const ClosedMeshOptions& options = {});

}  // namespace lc2wf
